#pragma once
// Reading a .wrl from disk: plain text, or gzip-compressed as VRML97 allows (.wrl.gz, .wrz).
#include <cstddef>
#include <string>

namespace fscript::vrml {

// Gzip bombs: past the first MiB, inflating more than this many times the compressed bytes read so
// far is refused (text VRML inflates 3 to 20 times; deflate's ceiling is about 1032). Scenes are also
// capped at support::kMaxInputBytes before and after inflating.
constexpr size_t kMaxGzipRatio = 250;
constexpr size_t kGzipRatioFloor = size_t{1} << 20;

// Reads `path`, inflating it when it starts with the gzip magic. On failure returns false with
// a message in `error` ("cannot read ...", "corrupt gzip data", a size or
// ratio limit).
bool read_scene_text(const std::string& path, std::string& text, std::string& error);

// Inflates gzip data (for tests and for files already in memory).
bool gunzip(const std::string& data, std::string& out, std::string& error);

}  // namespace fscript::vrml
