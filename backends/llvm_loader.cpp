// Loads the llvm backend's module (libfs_llvm.so) on first use; see llvm_module.h for why.
#include "backends/llvm_module.h"

#include <atomic>
#include <cstdlib>
#include <string>
#include <vector>

#include <dlfcn.h>
#include <unistd.h>

#include "runtime/support/cancel.h"

namespace fscript::backends {
namespace {

struct Loaded {
  const LlvmModule* module = nullptr;
  std::string error;
};
std::atomic<bool> g_loaded{false};

#ifdef FS_HAVE_LLVM
// By path, not through a run path (under the sanitizers their dlopen interceptor is the caller
// glibc sees, and it has none): FSCRIPT_LLVM_MODULE when set, else beside an installed binary
// (PREFIX/bin/../LIBDIR/fvrml), then the build tree's lib/fvrml.
std::vector<std::string> candidates() {
  if (const char* given = std::getenv("FSCRIPT_LLVM_MODULE"); given && *given) return {given};  // tests, odd layouts
  std::vector<std::string> out;
  char exe[4096];
  ssize_t n = ::readlink("/proc/self/exe", exe, sizeof exe - 1);
  if (n > 0) {
    std::string dir(exe, static_cast<size_t>(n));
    dir.erase(dir.find_last_of('/') + 1);
    out.push_back(dir + "../" FS_INSTALL_LIBDIR "/fvrml/libfs_llvm.so");
  }
  out.push_back(FS_BUILD_MODULE_DIR "/libfs_llvm.so");
  return out;
}
#endif

const Loaded& load() {
  static const Loaded once = [] {
    Loaded l;
#ifdef FS_HAVE_LLVM
    // RTLD_LAZY: LLVM's thousands of functions are bound as called; RTLD_LOCAL: its symbols stay
    // out of the process's.
    void* handle = nullptr;
    std::string first_error;
    for (const std::string& path : candidates()) {
      handle = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
      if (handle) break;
      const char* why = ::dlerror();
      if (first_error.empty() && (::access(path.c_str(), F_OK) == 0 || std::getenv("FSCRIPT_LLVM_MODULE")))
        first_error = why ? why : path;
    }
    if (!handle) {
      l.error = "the llvm backend's module could not be loaded: " +
          (first_error.empty() ? std::string("libfs_llvm.so is neither beside this binary (../" FS_INSTALL_LIBDIR
                                             "/fvrml) nor in its build tree")
                               : first_error);
      return l;
    }
    auto entry = reinterpret_cast<const LlvmModule* (*)()>(::dlsym(handle, "fs_llvm_module_v1"));
    if (!entry) {
      l.error = "the llvm backend's module is not this version's (no fs_llvm_module_v1)";
      return l;
    }
    l.module = entry();  // the handle stays open for the process: kernels point into the module
    if (l.module) l.module->set_cancel_slot(support::cancel_slot());
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
