// Which backends this binary has, and how to make one by name.
#include "backends/backend.h"
#include "backends/vm/vm_backend.h"

namespace fscript::backend {

std::vector<std::string> available_backends() { return {"vm"}; }

std::unique_ptr<Backend> make_backend(const std::string& name) {
  if (name == "vm") return std::make_unique<vm::VmBackend>();
  return nullptr;
}

}  // namespace fscript::backend
