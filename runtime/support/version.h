#pragma once
// The toolchain's version, one for every tool (`--version`), from the top CMakeLists.txt.
#include <string>

namespace fscript::support {

// "NAME VERSION (FVRML toolchain)".
std::string version_line(const std::string& tool);

}  // namespace fscript::support
