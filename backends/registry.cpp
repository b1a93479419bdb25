// Which backends this binary has, and how to make one by name.
#include "backends/backend.h"
#include "backends/sse/sse_backend.h"
#include "backends/tiered/tiered.h"
#include "backends/vm/vm_backend.h"
#ifdef FS_HAVE_LLVM
#include "backends/llvm/llvm_backend.h"
#endif

namespace fscript::backends {

std::string default_backend() { return "auto"; }

std::vector<std::string> available_backends() {
#ifdef FS_HAVE_LLVM
  return {"vm", "sse", "llvm"};
#else
  return {"vm", "sse"};
#endif
}

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "vm") return std::make_unique<vm::VmBackend>();
  if (name == "sse") return std::make_unique<sse::SseBackend>();
  if (name == "auto") return std::make_unique<TieredBackend>();
#ifdef FS_HAVE_LLVM
  if (name == "llvm") return std::make_unique<llvmjit::LlvmBackend>();
#endif
  return nullptr;
}

std::string missing_backend_message(const std::string& name) {
  std::string avail;
  for (const auto& a : available_backends()) avail += (avail.empty() ? "" : ", ") + a;
  if (name == "llvm")
    return "backend 'llvm' is not built in this binary (it needs llvm-19-dev when building; available: " + avail + ")";
  return "unknown backend '" + name + "' (available: auto, " + avail + ")";
}

bool enable_llvm_disk_cache(std::string& message) {
#ifdef FS_HAVE_LLVM
  message = llvmjit::set_disk_cache_enabled(true);
  if (!message.empty()) return true;
  message = "--llvm-disk-cache: no cache directory (set XDG_CACHE_HOME or HOME to a writable place)";
#else
  message = "--llvm-disk-cache: this binary has no llvm backend";
#endif
  return false;
}

bool native_code_cached(const ir::Module& m, const Budgets& budgets) {
#ifdef FS_HAVE_LLVM
  return llvmjit::code_cached(m, llvmjit::host_width(), budgets);
#else
  (void)m, (void)budgets;
  return false;
#endif
}

}  // namespace fscript::backends
