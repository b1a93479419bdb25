// The wasm backend's Kernel (wasm_backend.h): the module's bytes handed to JavaScript, which
// compiles and instantiates them against this program's memory and function table; batches run
// in groups of the module's points per turn with the tail padded (backends::run_padded), as the
// SSE code's do.
#include "backends/wasm/wasm_backend.h"

#include <emscripten.h>

#include <cstring>
#include <string>
#include <vector>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/wasm/wasm_compile.h"
#include "runtime/support/scratch.h"

EM_JS(int, fs_wasm_validate, (const uint8_t* bytes, int size),
      { return WebAssembly.validate(HEAPU8.slice(bytes, bytes + size)) ? 1 : 0; });
// The instances live in a JavaScript list; a kernel holds its index (0: none, and the engine's
// reason in `why`).
EM_JS(int, fs_wasm_instantiate,
      (const uint8_t* bytes, int size, const uint32_t* imports, int count, char* why, int why_size), {
        var code = HEAPU8.slice(bytes, bytes + size);
        try {
          var env = {memory : wasmMemory};
          for (var k = 0; k < count; ++k) env['f' + k] = wasmTable.get(HEAPU32[(imports >> 2) + k]);
          var module = new WebAssembly.Module(code);
          var kernel = new WebAssembly.Instance(module, {env : env}).exports.kernel;
          if (!Module.fsKernels) Module.fsKernels = [null];
          Module.fsKernels.push(kernel);
          return Module.fsKernels.length - 1;
        } catch (e) {
          stringToUTF8(String(e && e.message ? e.message : e), why, why_size);
          return 0;
        }
      });
EM_JS(int, fs_wasm_call, (int id, const void* inputs, const void* outputs, int n, void* scratch, void* arrays),
      { return Module.fsKernels[id](inputs, outputs, n, scratch, arrays); });
EM_JS(void, fs_wasm_release, (int id), { Module.fsKernels[id] = null; });

namespace fscript::wasm {
namespace {

class WasmKernel : public backends::Kernel {
 public:
  WasmKernel(int id, const CompiledModule& c, const backends::Budgets& budgets)
      : id_(id), inputs_(c.inputs), outputs_(c.outputs), scratch_floats_(c.scratch_bytes / 4), row_from_(c.row_from),
        group_(c.group), budgets_(budgets), arrays_(c.array_names) {}
  ~WasmKernel() override { fs_wasm_release(id_); }
  size_t num_inputs() const override { return inputs_; }
  size_t num_outputs() const override { return outputs_; }

  // A kernel with row parameters takes a batch as one row (the tiered kernel's convention).
  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                  backends::RuntimeError& err) const override {
    if (row_from_) return eval_rows(inputs[0], n, inputs + 1, 1, outputs, err);
    return run(inputs, outputs, n, err);
  }
  bool eval(const float* inputs, float* outputs, backends::RuntimeError& err) const override {
    return backends::eval_one(*this, inputs_, outputs_, inputs, outputs, err);
  }
  // Rows go in one call, their values spread over their points: a call per row (the SSE code's way)
  // crosses into JavaScript and back for every row.
  bool eval_rows(const float* first, size_t count, const float* const* rest, size_t rows, float* const* outputs,
                 backends::RuntimeError& err) const override {
    if (!row_from_) return Kernel::eval_rows(first, count, rest, rows, outputs, err);
    const size_t n = rows * count;
    support::ScratchFloats spread(inputs_ * n);  // (per-thread room, reused: rows come often)
    backends::Scratch<const float*> in(inputs_);
    for (size_t k = 0; k < inputs_; ++k) {
      float* column = spread.get() + k * n;
      for (size_t r = 0; r < rows; ++r) {  // (the first input per point, the others per row)
        if (k == 0) std::copy(first, first + count, column + r * count);
        else std::fill_n(column + r * count, count, rest[k - 1][r]);
      }
      in.data[k] = column;
    }
    return run(in.data, outputs, n, err);
  }

 private:
  // Every input one value a point.
  bool run(const float* const* inputs, float* const* outputs, size_t n, backends::RuntimeError& err) const {
    if (n == 0) return true;
    backends::LaneArrays arrays;  // (set up only for a kernel with arrays: small batches are many)
    if (!arrays_.empty()) arrays.init(4, budgets_.max_array_elements, arrays_);
    backends::Scratch<uint64_t, 32> room(scratch_floats_ / 2 + 2);
    auto* scratch = reinterpret_cast<uint8_t*>((reinterpret_cast<uintptr_t>(room.data) + 15) & ~uintptr_t{15});
    auto group = [&](const float* const* in, float* const* out, size_t count) {
      if (!fs_wasm_call(id_, in, out, static_cast<int>(count), scratch, arrays_.empty() ? nullptr : &arrays))
        return true;
      uint64_t code;
      std::memcpy(&code, scratch, sizeof code);
      return backends::jit_status(code, arrays, budgets_, err);
    };
    return backends::run_padded(group_, inputs_, outputs_, inputs, outputs, n, group);
  }

  int id_;
  size_t inputs_, outputs_, scratch_floats_;
  uint32_t row_from_, group_;
  backends::Budgets budgets_;
  std::vector<std::string> arrays_;  // names by slot
};

}  // namespace

bool valid_module(const std::vector<uint8_t>& bytes) {
  return fs_wasm_validate(bytes.data(), static_cast<int>(bytes.size())) != 0;
}

std::unique_ptr<backends::Kernel> WasmBackend::compile(const ir::Module& m, const backends::Budgets& budgets,
                                                       std::string& error) const {
  CompiledModule c;
  if (!compile_module(m, budgets, c, error)) {
    error = "the wasm backend does not compile this kernel yet: " + error;
    return nullptr;
  }
  std::vector<uint32_t> imports;
  for (const void* f : c.imports) imports.push_back(static_cast<uint32_t>(reinterpret_cast<uintptr_t>(f)));
  char why[256] = "";
  int id = fs_wasm_instantiate(c.bytes.data(), static_cast<int>(c.bytes.size()), imports.data(),
                               static_cast<int>(imports.size()), why, sizeof why);
  if (id == 0) {  // (compiling validates; a refused module is named as the emitter's bug if it is one)
    error = valid_module(c.bytes) ? std::string("the browser refused the wasm backend's module: ") + why
                                  : "the wasm backend wrote a module WebAssembly.validate refuses: " + std::string(why);
    return nullptr;
  }
  return std::make_unique<WasmKernel>(id, c, budgets);
}

}  // namespace fscript::wasm
