// The version line; FS_VERSION comes from project(VERSION) in the top CMakeLists.txt, defined for
// this file only so a version bump recompiles one file.
#include "runtime/support/version.h"

namespace fscript::support {

std::string version_line(const std::string& tool) { return tool + " " FS_VERSION " (FVRML toolchain)"; }

}  // namespace fscript::support
