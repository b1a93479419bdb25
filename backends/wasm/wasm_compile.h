#pragma once
// The IR's kernel function as a WebAssembly module (our own encoder, wasm_encoder.h): four points
// per iteration in f32x4 values, control flow under lane masks as the SSE emitter runs it, the
// transcendental functions called in runtime/math's batch twins (imported from the program that
// loads the module, so the results are its bits). The browser build instantiates it
// (wasm_backend.h); any build can compile it (the tests validate the bytes with Node).
#include <cstdint>
#include <string>
#include <vector>

#include "backends/backend.h"

namespace fscript::wasm {

// The module exports "kernel": (inputs i32, outputs i32, n i32, scratch i32, arrays i32) -> i32,
// where inputs and outputs point to arrays of pointers to each input's and output's floats, n is a
// multiple of `group` (every input one value a point: the Kernel expands a row parameter,
// ir::Function::row_params_from), scratch to `scratch_bytes` aligned to 16, arrays to a backends::LaneArrays for four
// lanes with `array_names` (or 0 when there are none); it returns 0, or 1 with
// backends::trap_code(kind, position) as an i64 at scratch's start. It imports "env"
// "memory" (the loader's memory) and "env" "f0", "f1", ...: the functions in `imports`, in order
// (runtime batch functions and backends/lane_arrays.h's helpers).
struct CompiledModule {
  std::vector<uint8_t> bytes;
  std::vector<const void*> imports;
  std::vector<std::string> array_names;  // by slot
  size_t inputs = 0, outputs = 0;
  size_t scratch_bytes = 0;
  uint32_t row_from = 0;  // the kernel's row parameters (0: none)
  uint32_t group = 4;     // points per turn of the kernel's loop: n is a multiple of it
};

// False with a message where the kernel uses what this emitter does not compile (a loop budget
// past 2^31 - 2): the VM runs those.
bool compile_module(const ir::Module& m, const backends::Budgets& budgets, CompiledModule& out, std::string& error);

}  // namespace fscript::wasm
