#pragma once
// The wasm backend (the browser build only): the kernel compiled to a WebAssembly module in memory
// (wasm_compile.h), instantiated by the JavaScript around the program (WebAssembly.Module and
// Instance, sharing its memory and its runtime functions) and called through the Kernel interface.
#include <cstdint>
#include <vector>

#include "backends/backend.h"

namespace fscript::wasm {

class WasmBackend : public backends::Backend {
 public:
  std::string name() const override { return "wasm"; }
  std::unique_ptr<backends::Kernel> compile(const ir::Module& m, const backends::Budgets& budgets,
                                            std::string& error) const override;
};

// The engine's WebAssembly.validate of a module's bytes (compile asks it of a module it refuses).
bool valid_module(const std::vector<uint8_t>& bytes);

}  // namespace fscript::wasm
