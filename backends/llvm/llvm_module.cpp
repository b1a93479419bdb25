// The llvm backend's module entry (backends/llvm_module.h): the one symbol the loader looks up.
#include "backends/llvm_module.h"

#include "backends/llvm/llvm_backend.h"
#include "backends/llvm/llvm_jit.h"

namespace fscript::llvmjit {
namespace {

class Module final : public backends::LlvmModule {
 public:
  std::unique_ptr<backends::Backend> backend(uint32_t width) const override {
    return std::make_unique<LlvmBackend>(width);
  }
  std::string kernel_text(const ir::Module& m, const backends::Budgets& budgets, bool assembly,
                          std::string& error) const override {
    return llvmjit::kernel_text(m, budgets, assembly, error);
  }
  bool code_cached(const ir::Module& m, const backends::Budgets& budgets) const override {
    return llvmjit::code_cached(m, host_width(), budgets);
  }
  backends::LlvmCacheStats cache_stats() const override {
    CacheStats s = llvmjit::cache_stats();
    return {s.hits, s.compiles, s.disk_hits, s.keys, s.quick_compiles};
  }
  void set_cache_enabled(bool on) const override { llvmjit::set_cache_enabled(on); }
  std::string set_disk_cache_enabled(bool on) const override { return llvmjit::set_disk_cache_enabled(on); }
  void set_cancel_slot(const void* slot) const override { llvmjit::set_cancel_slot(slot); }
};

}  // namespace
}  // namespace fscript::llvmjit

extern "C" __attribute__((visibility("default"))) const fscript::backends::LlvmModule* fs_llvm_module_v1() {
  static const fscript::llvmjit::Module module;
  return &module;
}
