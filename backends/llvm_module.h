#pragma once
// The llvm backend's entry points. The backend and LLVM itself live in a module (libfs_llvm.so)
// loaded on first use: loading and relocating LLVM's shared library costs 10 to 60 ms per process,
// which small jobs (the paper's figures, the REPL, the language server) would pay for nothing.
#include <cstdint>
#include <memory>
#include <string>

#include "backends/backend.h"

namespace fscript::backends {

struct LlvmCacheStats {
  uint64_t hits = 0, compiles = 0, disk_hits = 0;  // disk hits are also counted in compiles
  uint64_t keys = 0;  // programs the memory cache knows by key (live ones, and expired ones not yet swept)
  uint64_t quick_compiles = 0;  // compiles of modules with too many blocks for LLVM's full pipeline
};

class LlvmModule {
 public:
  virtual ~LlvmModule() = default;
  // The backend at `width` lanes (0: the host's SIMD width).
  virtual std::unique_ptr<Backend> backend(uint32_t width) const = 0;
  // The kernel as optimised LLVM IR or as the host's assembly; empty with a message on failure.
  virtual std::string kernel_text(const ir::Module& m, const Budgets& budgets, bool assembly,
                                  std::string& error) const = 0;
  // Whether the kernel's code at the host's width is in a cache (memory or disk).
  virtual bool code_cached(const ir::Module& m, const Budgets& budgets) const = 0;
  virtual LlvmCacheStats cache_stats() const = 0;
  // Off: every compile compiles (for measuring cold compile times); on by default.
  virtual void set_cache_enabled(bool on) const = 0;
  // The on-disk cache of object code; returns its directory, "" when off or when none can be made.
  virtual std::string set_disk_cache_enabled(bool on) const = 0;
  // The loading process's support::cancel_slot(), which generated code reads (the module links its
  // own copy of fs_support, whose flag nobody sets).
  virtual void set_cancel_slot(const void* slot) const = 0;
};

// The module, loaded by the first call (any thread); nullptr with the reason in `error` when this
// build has no llvm backend or the module cannot be loaded.
const LlvmModule* llvm_module(std::string* error = nullptr);
// Whether an earlier call loaded it (without loading it).
bool llvm_module_loaded();

}  // namespace fscript::backends

// The module's one exported symbol (backends/llvm/llvm_module.cpp).
extern "C" const fscript::backends::LlvmModule* fs_llvm_module_v1();
