#pragma once
// Reading a .wrl from disk: plain text, or gzip-compressed as VRML97 allows (.wrl.gz, .wrz).
#include <string>

namespace fscript::vrml {

// Reads `path`, inflating it when it starts with the gzip magic. On failure returns false with
// a message in `error` ("cannot read ...", "corrupt gzip data").
bool read_scene_text(const std::string& path, std::string& text, std::string& error);

// Inflates gzip data (for tests and for files already in memory).
bool gunzip(const std::string& data, std::string& out, std::string& error);

}  // namespace fscript::vrml
