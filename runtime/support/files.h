#pragma once
// Files: whole-file reads and atomic writes (a failed write never leaves half a file behind).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace fscript::support {

// The largest scene or script file the tools read (and the most a gzipped scene may inflate to):
// far above any hand-written scene, far below what would strain memory (docs/reliability.md).
constexpr size_t kMaxInputBytes = size_t{64} << 20;

// Reads a whole file; false on failure with errno text in `error`, or when the file is larger
// than `max_bytes` (checked before reading, so a huge file costs nothing).
bool read_file(const std::string& path, std::string& out, std::string& error, size_t max_bytes = SIZE_MAX);

// `s` with every %XX (two hex digits) replaced by its byte: the path of a file: URL.
std::string percent_decoded(const std::string& s);

// Writes `bytes` to a temporary file beside `path` and renames it over `path`, so a failure never
// leaves half a file. False with "cannot write 'path': reason" in `error`.
bool write_file_atomic(const std::string& path, const std::string& bytes, std::string& error);
// The same with the file's bytes in pieces, written one after another (no copy into one string).
bool write_file_atomic(const std::string& path, const std::vector<std::string_view>& pieces, std::string& error);
// The same with the bytes written to the open file by `fill` (false on a failed write): a large
// output streamed through a small buffer, never held whole in memory.
bool write_file_atomic(const std::string& path, const std::function<bool(std::FILE*)>& fill, std::string& error);

// Whether two paths name the same file: the same inode where both exist (links, `./`, `..`),
// else the same absolute path once `.`, `..` and symbolic links are resolved.
bool same_file(const std::string& a, const std::string& b);

// Deletes the temporary files of writes in progress in any thread: for a run that a limit ends
// with _exit (runtime/support/limits.h), so it leaves neither the output nor half of it.
void remove_pending_writes();

}  // namespace fscript::support
