// Which backends this binary has, and how to make one by name.
#include "backends/backend.h"
#include "backends/llvm_module.h"
#if defined(FS_HAVE_SSE)
#include "backends/sse/sse_backend.h"
#endif
#if defined(FS_HAVE_WASM)
#include "backends/wasm/wasm_backend.h"
#endif
#include "backends/tiered/tiered.h"
#include "backends/vm/vm_backend.h"

namespace fscript::backends {

std::string default_backend() { return "auto"; }

std::vector<std::string> available_backends() {
#if defined(FS_HAVE_LLVM)
  return {"vm", "sse", "llvm"};
#elif defined(FS_HAVE_SSE)
  return {"vm", "sse"};
#elif defined(FS_HAVE_WASM)
  return {"vm", "wasm"};
#else
  return {"vm"};
#endif
}

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "vm") return std::make_unique<vm::VmBackend>();
#if defined(FS_HAVE_SSE)
  if (name == "sse") return std::make_unique<sse::SseBackend>();
#endif
#if defined(FS_HAVE_WASM)
  if (name == "wasm") return std::make_unique<wasm::WasmBackend>();
#endif
  if (name == "auto") return std::make_unique<TieredBackend>();
  if (name == "llvm") {
    const LlvmModule* m = llvm_module();
    return m ? m->backend(0) : nullptr;
  }
  return nullptr;
}

std::string missing_backend_message(const std::string& name) {
  std::string avail;
  for (const auto& a : available_backends()) avail += (avail.empty() ? "" : ", ") + a;
  std::string why;
  if (name == "llvm" && !llvm_module(&why)) {
#ifdef FS_HAVE_LLVM
    return "backend 'llvm' cannot start: " + why;
#else
    return "backend 'llvm' is not built in this binary (it needs llvm-19-dev when building; available: " + avail + ")";
#endif
  }
  return "unknown backend '" + name + "' (available: auto, " + avail + ")";
}

bool enable_llvm_disk_cache(std::string& message) {
  // Asking for LLVM's cache loads LLVM at once (a run that wants its code from the disk wants LLVM).
  std::string why;
  const LlvmModule* m = llvm_module(&why);
  if (!m) {
    message = "--llvm-disk-cache: " + why;
    return false;
  }
  message = m->set_disk_cache_enabled(true);
  if (!message.empty()) return true;
  message = "--llvm-disk-cache: no cache directory (set XDG_CACHE_HOME or HOME to a writable place)";
  return false;
}

bool native_code_cached(const ir::Module& m, const Budgets& budgets) {
  // Not loaded: nothing compiled in this process, and no disk cache asked for (that loads it).
  if (!llvm_module_loaded()) return false;
  return llvm_module()->code_cached(m, budgets);
}

}  // namespace fscript::backends
