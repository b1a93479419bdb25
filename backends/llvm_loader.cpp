// Loads the llvm backend's module (libfs_llvm.so) on first use; see llvm_module.h for why.
#include "backends/llvm_module.h"

#include <atomic>
#include <mutex>

#include <dlfcn.h>

namespace fscript::backends {
namespace {

struct Loaded {
  const LlvmModule* module = nullptr;
  std::string error;
};
std::atomic<bool> g_loaded{false};

const Loaded& load() {
  static const Loaded once = [] {
    Loaded l;
#ifdef FS_HAVE_LLVM
    // Found through the executable's run path: the build tree's lib/fvrml, or PREFIX/lib/fvrml
    // next to an installed binary's bin. RTLD_LOCAL: LLVM's symbols stay out of the process's.
    void* handle = ::dlopen("libfs_llvm.so", RTLD_LAZY | RTLD_LOCAL);
    if (!handle) {
      const char* why = ::dlerror();
      l.error = std::string("the llvm backend's module could not be loaded: ") + (why ? why : "unknown error");
      return l;
    }
    auto entry = reinterpret_cast<const LlvmModule* (*)()>(::dlsym(handle, "fs_llvm_module_v1"));
    if (!entry) {
      l.error = "the llvm backend's module is not this version's (no fs_llvm_module_v1)";
      return l;
    }
    l.module = entry();  // the handle stays open for the process: kernels point into the module
    g_loaded = l.module != nullptr;
#else
    l.error = "this binary has no llvm backend (it needs llvm-19-dev when building)";
#endif
    return l;
  }();
  return once;
}

}  // namespace

const LlvmModule* llvm_module(std::string* error) {
  const Loaded& l = load();
  if (!l.module && error) *error = l.error;
  return l.module;
}

bool llvm_module_loaded() { return g_loaded; }

}  // namespace fscript::backends
