// fscript.preview: fvrml-run --serve as a child process, its URL read from its first line.
#include "lsp/preview.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>

#include "lsp/features/features.h"
#include "runtime/support/files.h"

extern char** environ;

namespace fscript::lsp {
namespace {

namespace fs = std::filesystem;

// fvrml-run: $FVRML_RUN, else beside this server (installed together), else in the build tree
// (build/lsp/ and build/tools/fvrml-run/), else on PATH.
std::string fvrml_run_path() {
  if (const char* env = std::getenv("FVRML_RUN"); env && *env) return env;
  std::error_code ec;
  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (!ec)
    for (fs::path p :
         {self.parent_path() / "fvrml-run", self.parent_path().parent_path() / "tools/fvrml-run/fvrml-run"})
      if (fs::exists(p, ec)) return p.string();
  return "fvrml-run";
}

// The first line the child writes, within `ms` milliseconds.
std::string first_line(int fd, int ms) {
  std::string line;
  char c;
  while (line.size() < 4096) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, ms) <= 0 || read(fd, &c, 1) != 1 || c == '\n') break;
    line += c;
  }
  return line;
}

json failure(const std::string& message) { return {{"__error", kRequestFailed}, {"message", message}}; }

}  // namespace

std::string path_of_uri(const std::string& uri) {
  return uri.rfind("file://", 0) == 0 ? support::percent_decoded(uri.substr(7)) : "";
}

json Previews::start(const std::string& uri) {
  std::string path = path_of_uri(uri);
  if (path.empty()) return failure("fscript.preview needs a file: URI, got '" + uri + "'");
  if (access(path.c_str(), R_OK) != 0)  // fvrml-run --serve refuses a scene that is not there
    return failure("fscript.preview: " + path + " is not on disk yet: save it, then preview it");
  if (auto it = running_.find(path); it != running_.end()) {
    if (waitpid(it->second.pid, nullptr, WNOHANG) == 0) return {{"url", it->second.url}};
    running_.erase(it);  // it ended: start another
  }
  int out[2];
  if (pipe(out) != 0) return failure("fscript.preview: cannot make a pipe");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);  // never into the LSP stream
  std::string run = fvrml_run_path();
  const char* argv[] = {run.c_str(), path.c_str(), "--serve", "--port", "0", nullptr};
  pid_t pid = -1;
  int rc = posix_spawnp(&pid, run.c_str(), &actions, nullptr, const_cast<char* const*>(argv), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  if (rc != 0) {
    close(out[0]);
    return failure("fscript.preview: cannot start " + run + " (set FVRML_RUN to its path)");
  }
  std::string line = first_line(out[0], 10000);
  close(out[0]);  // its later lines ("stopped") go nowhere
  size_t at = line.find("http://");
  if (at == std::string::npos) {
    kill(pid, SIGKILL);
    waitpid(pid, nullptr, 0);
    return failure("fscript.preview: fvrml-run --serve did not start: " + line);
  }
  std::string url = line.substr(at, line.find(' ', at) - at);
  running_[path] = {pid, url};
  return {{"url", url}};
}

Previews::~Previews() {
  for (auto& [path, r] : running_) kill(r.pid, SIGINT);
  for (auto& [path, r] : running_) waitpid(r.pid, nullptr, 0);
}

}  // namespace fscript::lsp
