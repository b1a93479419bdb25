// Whole-file reading and all-or-nothing writing, for every layer that touches files.
#include "runtime/support/files.h"

#include <cctype>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>

#include <unistd.h>

namespace fscript::support {

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  fs::path ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  fs::path cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

bool read_file(const std::string& path, std::string& out, std::string& error, size_t max_bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    error = std::strerror(errno);
    return false;
  }
  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > max_bytes) {
    error = "the file is " + std::to_string(size >> 20) + " MiB, over the limit of " + std::to_string(max_bytes >> 20) +
        " MiB for one file";
    return false;
  }
  // A regular file straight into a string of its size (a part file of a sharded mesh is hundreds of
  // megabytes); then whatever is left, which is all of a pipe's, a chunk at a time within the limit.
  out.clear();
  if (!ec && size > 0) {
    out.resize(static_cast<size_t>(size));
    in.read(out.data(), static_cast<std::streamsize>(size));
    out.resize(static_cast<size_t>(in.gcount()));
  }
  static thread_local char chunk[1 << 16];
  while (in) {
    in.read(chunk, sizeof chunk);
    out.append(chunk, static_cast<size_t>(in.gcount()));
    if (out.size() > max_bytes) {
      error = "the file is over the limit of " + std::to_string(max_bytes >> 20) + " MiB for one file";
      out.clear();
      return false;
    }
  }
  if (in.bad()) {
    error = "read error";
    return false;
  }
  return true;
}

namespace {
// The temporary files being written now, for remove_pending_writes (a run stopped by a limit).
std::mutex g_pending_mutex;
std::set<std::string> g_pending;

struct Pending {
  explicit Pending(const std::string& tmp) : tmp_(tmp) {
    std::lock_guard<std::mutex> lock(g_pending_mutex);
    g_pending.insert(tmp_);
  }
  ~Pending() {
    std::lock_guard<std::mutex> lock(g_pending_mutex);
    g_pending.erase(tmp_);
  }
  const std::string& tmp_;
};
}  // namespace

bool write_file_atomic(const std::string& path, const std::string& bytes, std::string& error) {
  return write_file_atomic(path, std::vector<std::string_view>{bytes}, error);
}

bool write_file_atomic(const std::string& path, const std::vector<std::string_view>& pieces, std::string& error) {
  return write_file_atomic(
      path,
      [&](std::FILE* f) {
        for (std::string_view p : pieces)
          if (std::fwrite(p.data(), 1, p.size(), f) != p.size()) return false;
        return true;
      },
      error);
}

bool write_file_atomic(const std::string& path, const std::function<bool(std::FILE*)>& fill, std::string& error) {
  std::string tmp = path + ".tmp";
  Pending pending(tmp);
  FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    return false;
  }
  bool ok = fill(f);
  ok = (std::fclose(f) == 0) && ok && std::rename(tmp.c_str(), path.c_str()) == 0;
  if (!ok) {
    error = "cannot write '" + path + "': " + std::strerror(errno);
    std::remove(tmp.c_str());
  }
  return ok;
}

void remove_pending_writes() {
  // try_lock: the caller may be the new-handler of a thread that holds the lock.
  std::unique_lock<std::mutex> lock(g_pending_mutex, std::try_to_lock);
  if (!lock.owns_lock()) return;
  for (const std::string& tmp : g_pending) ::unlink(tmp.c_str());
}

std::string percent_decoded(const std::string& s) {
  auto hex = [](char c) { return std::isxdigit(static_cast<unsigned char>(c)) != 0; };
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && hex(s[i + 1]) && hex(s[i + 2])) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

}  // namespace fscript::support
