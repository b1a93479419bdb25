#pragma once
// Files: whole-file reads and atomic writes (a failed write never leaves half a file behind).
#include <string>

namespace fscript::support {

// Reads a whole file; false on failure with errno text in `error`.
bool read_file(const std::string& path, std::string& out, std::string& error);

// `s` with every %XX (two hex digits) replaced by its byte: the path of a file: URL.
std::string percent_decoded(const std::string& s);

// Writes `bytes` to a temporary file beside `path` and renames it over `path`, so a failure never
// leaves half a file. False with "cannot write 'path': reason" in `error`.
bool write_file_atomic(const std::string& path, const std::string& bytes, std::string& error);

}  // namespace fscript::support
