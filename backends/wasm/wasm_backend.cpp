// The wasm backend's Kernel (wasm_backend.h): the module's bytes handed to JavaScript, which
// compiles and instantiates them against this program's memory and function table; batches run
// in groups of four points with the tail padded (backends::run_padded), as the SSE code's do.
#include "backends/wasm/wasm_backend.h"

#include <emscripten.h>

#include <vector>

#include "backends/jit_support.h"
#include "backends/lane_arrays.h"
#include "backends/wasm/wasm_compile.h"

// The instances live in a JavaScript list; a kernel holds its index (0: none).
EM_JS(int, fs_wasm_instantiate, (const uint8_t* bytes, int size, const uint32_t* imports, int count), {
  try {
    var env = {memory : wasmMemory};
    for (var k = 0; k < count; ++k) env['f' + k] = wasmTable.get(HEAPU32[(imports >> 2) + k]);
    var module = new WebAssembly.Module(HEAPU8.slice(bytes, bytes + size));
    var kernel = new WebAssembly.Instance(module, {env : env}).exports.kernel;
    if (!Module.fsKernels) Module.fsKernels = [null];
    Module.fsKernels.push(kernel);
    return Module.fsKernels.length - 1;
  } catch (e) {
    return 0;
  }
});
// The kernel's status as two halves (a JavaScript BigInt does not cross into C++ here).
EM_JS(uint32_t, fs_wasm_call,
      (int id, const void* inputs, const void* outputs, int n, void* scratch, void* arrays, uint32_t* high), {
        var status = Module.fsKernels[id](inputs, outputs, n, scratch, arrays);
        var mask = BigInt(0xffffffff);  // (no BigInt literals: Emscripten's JavaScript optimiser reads ES2018)
        HEAPU32[high >> 2] = Number((status >> BigInt(32)) & mask);
        return Number(status & mask);
      });
EM_JS(void, fs_wasm_release, (int id), { Module.fsKernels[id] = null; });

namespace fscript::wasm {
namespace {

class WasmKernel : public backends::Kernel {
 public:
  WasmKernel(int id, const CompiledModule& c, const backends::Budgets& budgets)
      : id_(id), inputs_(c.inputs), outputs_(c.outputs), scratch_floats_(c.scratch_bytes / 4), budgets_(budgets),
        arrays_(c.array_names) {}
  ~WasmKernel() override { fs_wasm_release(id_); }
  size_t num_inputs() const override { return inputs_; }
  size_t num_outputs() const override { return outputs_; }

  bool eval_batch(const float* const* inputs, float* const* outputs, size_t n,
                  backends::RuntimeError& err) const override {
    if (n == 0) return true;
    backends::LaneArrays arrays;
    arrays.init(4, budgets_.max_array_elements, arrays_);
    return backends::run_padded(
        4, inputs_, outputs_, inputs, outputs, n, [&](const float* const* in, float* const* out, size_t count) {
          std::vector<float> room(scratch_floats_ + 4);  // aligned to 16 below
          auto* scratch = reinterpret_cast<uint8_t*>((reinterpret_cast<uintptr_t>(room.data()) + 15) & ~uintptr_t{15});
          uint32_t high = 0;
          uint32_t low = fs_wasm_call(id_, in, out, static_cast<int>(count), scratch, &arrays, &high);
          uint64_t code = uint64_t{high} << 32 | low;
          return backends::jit_status(code, arrays, budgets_, err);
        });
  }
  bool eval(const float* inputs, float* outputs, backends::RuntimeError& err) const override {
    std::vector<const float*> in(inputs_);
    std::vector<float*> out(outputs_);
    for (size_t k = 0; k < inputs_; ++k) in[k] = inputs + k;
    for (size_t k = 0; k < outputs_; ++k) out[k] = outputs + k;
    return eval_batch(in.data(), out.data(), 1, err);
  }

 private:
  int id_;
  size_t inputs_, outputs_, scratch_floats_;
  backends::Budgets budgets_;
  std::vector<std::string> arrays_;  // names by slot
};

}  // namespace

std::unique_ptr<backends::Kernel> WasmBackend::compile(const ir::Module& m, const backends::Budgets& budgets,
                                                       std::string& error) const {
  CompiledModule c;
  if (!compile_module(m, budgets, c, error)) {
    error = "the wasm backend does not compile this kernel yet: " + error;
    return nullptr;
  }
  std::vector<uint32_t> imports;
  for (const void* f : c.imports) imports.push_back(static_cast<uint32_t>(reinterpret_cast<uintptr_t>(f)));
  int id = fs_wasm_instantiate(c.bytes.data(), static_cast<int>(c.bytes.size()), imports.data(),
                               static_cast<int>(imports.size()));
  if (id == 0) {
    error = "the browser refused the wasm backend's module (WebAssembly.Module)";
    return nullptr;
  }
  return std::make_unique<WasmKernel>(id, c, budgets);
}

}  // namespace fscript::wasm
