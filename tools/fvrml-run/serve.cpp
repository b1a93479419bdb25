// fvrml-run --serve: the live preview. An HTTP server (Debian's cpp-httplib) on 127.0.0.1 serves one
// page (preview/index.html and preview.js, compiled in), three.js from Debian's libjs-three, and the
// scene as our own glTF; a watcher re-runs the scene when the scene or a file it pulls in changes and
// pushes the new state to every open page as a Server-Sent Event. A save that breaks the scene keeps
// the last good glTF and sends the diagnostics instead. Only those paths exist: anything else is 404.
#include <httplib.h>
#include <signal.h>
#include <spawn.h>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <condition_variable>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "tools/fvrml-run/run.h"

extern char** environ;

namespace fvrml_run {
namespace {

namespace fs = std::filesystem;

const char kIndexHtml[] =
#include "preview_index.inc"
    ;
const char kPreviewJs[] =
#include "preview_js.inc"
    ;

constexpr int kMaxStreams = 4;  // open pages at once (each holds a server thread)
constexpr int kPreviewFrames = 24;  // frames of an animated shape's cycle, unless --frames says
int stop_pipe[2] = {-1, -1};    // the signal handler's way to the thread that stops the server

// The served three.js files: URL path to the file under FS_THREE_DIR (the jsm modules import
// ../../../build/three.module.js, so the tree keeps its shape).
const std::pair<const char*, const char*> kThreeFiles[] = {
    {"/three/build/three.module.js", "build/three.module.js"},
    {"/three/examples/jsm/loaders/GLTFLoader.js", "examples/jsm/loaders/GLTFLoader.js"},
    {"/three/examples/jsm/controls/OrbitControls.js", "examples/jsm/controls/OrbitControls.js"},
};

// What the page sees: the last good glTF, and the state of the last run.
struct State {
  std::mutex lock;
  std::condition_variable changed;
  uint64_t version = 0;
  bool ok = false, stopping = false;
  std::string glb;          // the last good scene
  std::string diagnostics;  // of the last run, as a compiler prints them (warnings too)
  nlohmann::json stats;     // of the last good run
  double scale = 1;         // the resolution scale the page asked for
  int streams = 0;
  bool running = false;     // a run is under way (its progress goes to the pages)
};

nlohmann::json state_json(const State& s) {
  return {{"version", s.version}, {"ok", s.ok}, {"diagnostics", s.diagnostics}, {"stats", s.stats}, {"scale", s.scale}};
}

// The files a run read, with their modification times: a change of any is a reason to run again.
using Stamps = std::vector<std::pair<std::string, fs::file_time_type>>;
Stamps stamp(const std::vector<std::string>& files) {
  Stamps out;
  for (const auto& f : files) {
    std::error_code ec;
    auto t = fs::last_write_time(f, ec);
    out.push_back({f, ec ? fs::file_time_type::min() : t});
  }
  return out;
}

// Runs the scene into a glTF in `dir`, its diagnostics captured; returns the files it read.
std::vector<std::string> run_into(const Options& base, const std::string& dir, State& st) {
  Options o = base;
  o.output = (fs::path(dir) / "scene.glb").string();
  o.format = "glb";
  if (o.frames == 0) o.frames = kPreviewFrames;  // time-dependent shapes play as an animation
  o.stats = true;
  o.view_json = true;
  {
    std::lock_guard<std::mutex> hold(st.lock);
    o.model.resolution_scale = base.model.resolution_scale * st.scale;
  }
  std::vector<std::string> files = {o.path};
  nlohmann::json stats;
  fscript::support::progress_reset();
  {
    std::lock_guard<std::mutex> hold(st.lock);
    st.running = true;
  }
  st.changed.notify_all();  // the streams switch to sending progress
  std::ostringstream captured;
  std::streambuf* saved = std::cerr.rdbuf(captured.rdbuf());
  auto t0 = Clock::now();
  int rc = run_scene(o, stats, &files);
  std::cerr.rdbuf(saved);
  stats["total_ms"] = ms_since(t0);
  stats["backend"] = o.model.compile.backend;
  stats["resolution_scale"] = o.model.resolution_scale;
  std::string glb, error;
  bool ok = rc == 0 && fscript::support::read_file(o.output, glb, error);
  {
    std::lock_guard<std::mutex> hold(st.lock);
    st.ok = ok;
    st.diagnostics = captured.str() + (rc == 0 && !ok ? "error: " + error + "\n" : "");
    if (ok) st.glb = std::move(glb), st.stats = stats;
    ++st.version;
    st.running = false;
  }
  st.changed.notify_all();
  return files;
}

// Re-runs the scene whenever a file it read changes (polled four times a second: editors save by
// rename as often as in place, which file-system events see differently), or the page asks.
void watch(const Options& o, const std::string& dir, State& st, std::atomic<bool>& rerun) {
  Stamps seen = stamp(run_into(o, dir, st));
  for (;;) {
    {
      std::unique_lock<std::mutex> hold(st.lock);
      st.changed.wait_for(hold, std::chrono::milliseconds(250), [&] { return st.stopping; });
      if (st.stopping) return;
    }
    std::vector<std::string> files;
    for (const auto& [f, t] : seen) files.push_back(f);
    if (stamp(files) == seen && !rerun.exchange(false)) continue;
    seen = stamp(run_into(o, dir, st));
  }
}

void routes(httplib::Server& svr, State& st, std::atomic<bool>& rerun) {
  svr.Get("/", [](const httplib::Request&, httplib::Response& res) { res.set_content(kIndexHtml, "text/html; charset=utf-8"); });
  svr.Get(R"(/favicon\.ico)", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  svr.Get(R"(/preview\.js)", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kPreviewJs, "text/javascript; charset=utf-8");
  });
  for (const auto& [url, file] : kThreeFiles) {
    std::string path = std::string(FS_THREE_DIR) + "/" + file, pattern;
    for (const char* c = url; *c; ++c) pattern += *c == '.' ? std::string("\\.") : std::string(1, *c);
    svr.Get(pattern, [path](const httplib::Request&, httplib::Response& res) {
      std::string text, error;
      if (!fscript::support::read_file(path, text, error)) {
        res.status = 404;
        res.set_content("three.js is not installed (Debian package libjs-three): " + error, "text/plain");
        return;
      }
      res.set_content(text, "text/javascript; charset=utf-8");
    });
  }
  svr.Get(R"(/scene\.glb)", [&st](const httplib::Request&, httplib::Response& res) {
    std::lock_guard<std::mutex> hold(st.lock);
    if (st.glb.empty()) {
      res.status = 404;
      return;
    }
    res.set_header("Cache-Control", "no-store");
    res.set_content(st.glb, "model/gltf-binary");
  });
  svr.Get(R"(/state\.json)", [&st](const httplib::Request&, httplib::Response& res) {
    std::lock_guard<std::mutex> hold(st.lock);
    res.set_header("Cache-Control", "no-store");
    res.set_content(state_json(st).dump(), "application/json");
  });
  svr.Post("/settings", [&st, &rerun](const httplib::Request& req, httplib::Response& res) {
    double scale = 0;
    if (req.has_param("scale")) scale = std::atof(req.get_param_value("scale").c_str());
    if (!(scale >= 0.1 && scale <= 4)) {
      res.status = 400;
      res.set_content("scale wants a number from 0.1 to 4", "text/plain");
      return;
    }
    {
      std::lock_guard<std::mutex> hold(st.lock);
      st.scale = scale;
    }
    rerun = true;
    res.set_content("{}", "application/json");
  });
  // Server-Sent Events: the state now, then at every change; a comment every 15 s keeps it open.
  svr.Get("/events", [&st](const httplib::Request&, httplib::Response& res) {
    {
      std::lock_guard<std::mutex> hold(st.lock);
      if (st.streams >= kMaxStreams) {
        res.status = 503;
        res.set_content("too many open pages", "text/plain");
        return;
      }
      ++st.streams;
    }
    res.set_header("Cache-Control", "no-store");
    auto sent = std::make_shared<uint64_t>(~uint64_t{0});
    res.set_chunked_content_provider(
        "text/event-stream",
        [&st, sent](size_t, httplib::DataSink& sink) {
          std::string out;
          {
            std::unique_lock<std::mutex> hold(st.lock);
            // While a run is under way, its progress four times a second; else wait for the next state.
            if (st.running)
              st.changed.wait_for(hold, std::chrono::milliseconds(250), [&] { return st.stopping || st.version != *sent; });
            else  // idle: until a state, a run starting, or the keep-alive
              st.changed.wait_for(hold, std::chrono::seconds(15), [&] { return st.stopping || st.version != *sent || st.running; });
            if (st.stopping) return false;
            if (st.version != *sent) {
              *sent = st.version;
              out = "event: state\ndata: " + state_json(st).dump() + "\n\n";
            } else if (st.running) {
              fscript::support::ProgressState p = fscript::support::progress_state();
              nlohmann::json j = {{"fraction", p.fraction}, {"done", p.done}, {"jobs", p.jobs}, {"what", p.what}};
              out = "event: progress\ndata: " + j.dump() + "\n\n";
            } else {
              out = ": keep-alive\n\n";
            }
          }
          return sink.write(out.data(), out.size());
        },
        [&st](bool) {
          std::lock_guard<std::mutex> hold(st.lock);
          --st.streams;
        });
  });
}

// xdg-open URL, without waiting for it; a note when there is no desktop to ask.
void open_page(const std::string& url) {
  pid_t pid;
  const char* argv[] = {"xdg-open", url.c_str(), nullptr};
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0)
    std::cerr << "fvrml-run: --open: no xdg-open here; open " << url << " yourself\n";
}

}  // namespace

int serve(const Options& o, const ServeOptions& s) {
  if (!o.output.empty()) {
    std::cerr << "error: --serve writes no file: leave out -o\n";
    return 2;
  }
  std::error_code ec;
  fs::path dir = fs::temp_directory_path(ec) / ("fvrml-serve-" + std::to_string(getpid()));
  if (ec || !fs::create_directories(dir, ec) || ec) {
    std::cerr << "error: --serve: cannot make a scratch folder in " << fs::temp_directory_path(ec) << "\n";
    return 1;
  }
  // Ctrl-C and SIGTERM: the handler (on whichever thread the signal lands) writes a byte that wakes
  // the thread that stops the server, which the handler itself could not do safely.
  if (pipe(stop_pipe) != 0) {
    std::cerr << "error: --serve: " << std::strerror(errno) << "\n";
    return 1;
  }
  struct sigaction on_stop {};
  on_stop.sa_handler = [](int) { [[maybe_unused]] ssize_t k = write(stop_pipe[1], "s", 1); };
  sigemptyset(&on_stop.sa_mask);
  sigaction(SIGINT, &on_stop, nullptr);
  sigaction(SIGTERM, &on_stop, nullptr);
  State st;
  std::atomic<bool> rerun{false};
  httplib::Server svr;
  // SO_REUSEADDR only: the library's default adds SO_REUSEPORT, which lets a second server take a
  // port already in use without an error.
  svr.set_socket_options([](int sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  svr.set_payload_max_length(64 * 1024);
  svr.set_read_timeout(5, 0);
  svr.set_keep_alive_max_count(100);
  routes(svr, st, rerun);
  int port = s.port == 0 ? svr.bind_to_any_port(s.host) : (svr.bind_to_port(s.host, s.port) ? s.port : -1);
  if (port < 0) {
    std::cerr << "error: --serve: cannot listen on " << s.host << ":" << s.port << " (in use? --port N picks another)\n";
    fs::remove_all(dir, ec);
    return 1;
  }
  std::string url = "http://" + (s.host.find(':') != std::string::npos ? "[" + s.host + "]" : s.host) + ":" +
                    std::to_string(port) + "/";
  std::cout << "fvrml-run: serving " << o.path << " at " << url << " (Ctrl-C stops)" << std::endl;
  std::thread watcher([&] { watch(o, dir.string(), st, rerun); });
  std::thread stopper([&] {
    char byte;
    while (read(stop_pipe[0], &byte, 1) < 0 && errno == EINTR) {
    }
    {
      std::lock_guard<std::mutex> hold(st.lock);
      st.stopping = true;
    }
    st.changed.notify_all();
    svr.stop();
  });
  if (s.open) open_page(url);
  bool listened = svr.listen_after_bind();
  {
    std::lock_guard<std::mutex> hold(st.lock);
    st.stopping = true;
  }
  st.changed.notify_all();
  watcher.join();
  [[maybe_unused]] ssize_t k = write(stop_pipe[1], "e", 1);  // when listen ended by itself
  stopper.join();
  signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL);
  fs::remove_all(dir, ec);
  std::cout << "fvrml-run: stopped" << std::endl;
  return listened ? 0 : 1;
}

}  // namespace fvrml_run
