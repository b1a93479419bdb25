// Which backends this binary has, and how to make one by name.
#include "backends/backend.h"
#include "backends/sse/sse_backend.h"
#include "backends/vm/vm_backend.h"

namespace fscript::backend {

// The VM stays first (the default) until sse compiles every kernel.
std::vector<std::string> available_backends() { return {"vm", "sse"}; }

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "vm") return std::make_unique<vm::VmBackend>();
  if (name == "sse") return std::make_unique<sse::SseBackend>();
  return nullptr;
}

}  // namespace fscript::backend
