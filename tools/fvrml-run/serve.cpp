// fvrml-run --serve: the live preview. An HTTP server (Debian's cpp-httplib) on 127.0.0.1 serves one
// page (preview/index.html, preview.js and web/viewer.js, compiled in), three.js from Debian's libjs-three, and the
// scene as our own glTF; a watcher re-runs the scene when the scene or a file it pulls in changes and
// pushes the new state to every open page as a Server-Sent Event, with the scene so far while an
// animation's frames are made. A save that breaks the scene keeps the last good glTF and sends the
// diagnostics instead. Only those paths exist: anything else is 404.
#include <httplib.h>
#include <signal.h>
#include <spawn.h>

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <condition_variable>
#include <filesystem>
#include <iostream>
#include <mutex>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "runtime/support/cancel.h"
#include "runtime/support/files.h"
#include "runtime/support/progress.h"
#include "tools/fvrml-run/memo.h"
#include "tools/fvrml-run/serve.h"

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
const char kViewerJs[] =  // web/viewer.js: the browser page's view, the same file
#include "viewer_js.inc"
    ;

constexpr int kMaxStreams = 4;  // open pages at once (each holds a server thread)
int stop_pipe[2] = {-1, -1};    // the signal handler's way to the thread that stops the server

// The served three.js files (classic scripts, as the browser page loads them): URL path to the
// file under FS_THREE_DIR.
const std::pair<const char*, const char*> kThreeFiles[] = {
    {"/three/three.min.js", "three.min.js"},
    {"/three/examples/js/loaders/GLTFLoader.js", "examples/js/loaders/GLTFLoader.js"},
    {"/three/examples/js/controls/OrbitControls.js", "examples/js/controls/OrbitControls.js"},
};

// What the page sees: the last good glTF, and the state of the last run.
struct State {
  std::mutex lock;
  std::condition_variable changed;
  uint64_t version = 0;
  bool ok = false, stopping = false;
  std::string glb;          // what the page shows: the last good scene, or the scene so far
  std::string good;         // the last good scene (a run that fails after partial scenes goes back to it)
  nlohmann::json partial;   // null, or the frames so far of the animation being made: {frames, of}
  std::string diagnostics;  // of the last run, as a compiler prints them (warnings too)
  nlohmann::json stats;     // of the last good run
  double scale = 1;         // the resolution scale the page asked for
  int streams = 0;                     // slots taken: open streams less those of closed pages
  std::map<std::string, int> live_pages;  // the open streams by page name
  std::set<std::string> closed_pages;  // pages that said they closed (/closed): their streams end now
  bool running = false;     // a run is under way (its progress goes to the pages)
  std::string printed;      // the diagnostics last printed on the terminal (the watcher's thread only)
};

nlohmann::json state_json(const State& s) {
  return {{"version", s.version}, {"ok", s.ok},       {"diagnostics", s.diagnostics},
          {"stats", s.stats},     {"scale", s.scale}, {"partial", s.partial}};
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
// A cancelled run changes nothing the page sees but the scenes so far it was sent.
std::vector<std::string> run_into(const Options& base, const std::string& dir, State& st, MeshMemo& memo,
                                  const std::atomic<bool>& cancel) {
  Options o = preview_run_options(base, (fs::path(dir) / "scene.glb").string());
  o.memo = &memo;
  o.cancel = &cancel;
  std::ostringstream captured;
  // Called by the run's own thread, which writes `captured`: the warnings so far go with the scene.
  o.on_partial = [&st, &captured](const std::string& glb, size_t frames, size_t of) {
    {
      std::lock_guard<std::mutex> hold(st.lock);
      st.glb = glb, st.ok = true, st.diagnostics = captured.str();
      st.partial = {{"frames", frames}, {"of", of}};
      ++st.version;
    }
    st.changed.notify_all();
  };
  {
    std::lock_guard<std::mutex> hold(st.lock);
    o.model.resolution_scale = base.model.resolution_scale * st.scale;
  }
  std::vector<std::string> files = {o.path};
  nlohmann::json stats;
  fscript::support::progress_reset();
  memo.reset_counts();
  bool ok_before;
  std::string diagnostics_before;  // a partial scene clears them; a cancel puts them back
  {
    std::lock_guard<std::mutex> hold(st.lock);
    st.running = true;
    ok_before = st.ok, diagnostics_before = st.diagnostics;
  }
  st.changed.notify_all();  // the streams switch to sending progress
  std::streambuf* saved = std::cerr.rdbuf(captured.rdbuf());
  auto t0 = Clock::now();
  int rc;
  {
    fscript::support::CancelScope scope(cancel);  // the meshers see the cancel mid-frame too
    rc = run_scene(o, stats, &files);
  }
  std::cerr.rdbuf(saved);
  stats["total_ms"] = ms_since(t0);
  stats["backend"] = o.model.compile.backend;
  stats["resolution_scale"] = o.model.resolution_scale;
  MeshMemo::Counts counts = memo.counts();
  stats["memo"] = {{"reused", counts.reused}, {"made", counts.made}};
  if (cancel) {
    {
      std::lock_guard<std::mutex> hold(st.lock);
      // As before the run: else a cancel after a partial scene looked like a run that succeeded.
      st.glb = st.good, st.ok = ok_before, st.diagnostics = std::move(diagnostics_before);
      st.partial = nullptr;
      st.running = false;
    }
    st.changed.notify_all();
    return files;
  }
  std::string glb, error;
  bool ok = rc == 0 && fscript::support::read_file(o.output, glb, error);
  if (ok) memo.sweep();
  std::string diagnostics = captured.str() + (rc == 0 && !ok ? "error: " + error + "\n" : "");
  // The terminal gets them too (a page may not be open): each new set once, and the word when a
  // broken scene has no errors again (warnings may stay).
  if (diagnostics != st.printed) {
    if (!diagnostics.empty()) std::fprintf(stderr, "%s", diagnostics.c_str());
    if (st.printed.find("error:") != std::string::npos && diagnostics.find("error:") == std::string::npos)
      std::fprintf(stderr, "fvrml-run: %s: no errors now\n", o.path.c_str());
    st.printed = diagnostics;
  }
  {
    std::lock_guard<std::mutex> hold(st.lock);
    st.ok = ok;
    st.diagnostics = std::move(diagnostics);
    if (ok) st.good = std::move(glb), st.stats = stats;
    st.glb = st.good;
    st.partial = nullptr;
    ++st.version;
    st.running = false;
  }
  st.changed.notify_all();
  return files;
}

// Runs the scene on a thread of its own while watching the files the last run read: a save of one
// of them, a new setting from the page or the server stopping makes the run moot, and it is
// cancelled. Returns the stamps of the files the run read, or after a cancel stamps no file has,
// so the next look runs the scene again. A file saved while the run went on may have been read
// before the save: it is stamped as unseen too. (File times come from a coarse kernel clock, hence
// the slack: a save just before the run costs at most one run more, never a missed save.)
Stamps run_and_stamp(const Options& o, int poll_ms, const std::string& dir, State& st, MeshMemo& memo,
                     const std::vector<std::string>& watched, std::atomic<bool>& rerun) {
  auto start = fs::file_time_type::clock::now() - std::chrono::milliseconds(50);
  Stamps at_start = stamp(watched);
  std::atomic<bool> cancel{false}, finished{false};
  bool timed_out = false;
  auto began = std::chrono::steady_clock::now();
  std::vector<std::string> files;
  std::thread worker([&] {
    files = run_into(o, dir, st, memo, cancel);
    finished = true;
    st.changed.notify_all();
  });
  while (!finished) {
    bool stopping;
    {
      std::unique_lock<std::mutex> hold(st.lock);
      st.changed.wait_for(hold, std::chrono::milliseconds(poll_ms), [&] { return st.stopping || finished; });
      stopping = st.stopping;
    }
    if (!finished && (stopping || rerun.load() || stamp(watched) != at_start)) cancel = true;
    std::chrono::duration<double> took = std::chrono::steady_clock::now() - began;
    if (!finished && !cancel && o.max_seconds > 0 && took.count() > o.max_seconds) timed_out = cancel = true;
  }
  worker.join();
  if (timed_out) {  // the page keeps the last good scene and shows why this one is not there
    char message[160];
    std::snprintf(message, sizeof message, "error: the run took longer than %g s (--max-seconds %g); stopped\n",
                  o.max_seconds, o.max_seconds);
    {
      std::lock_guard<std::mutex> hold(st.lock);
      st.ok = false;
      st.diagnostics = message;
      ++st.version;
    }
    st.changed.notify_all();
    return stamp(watched);  // not run again until a file changes
  }
  Stamps seen = stamp(cancel ? watched : files);
  for (auto& [file, time] : seen)
    if (cancel || time >= start) time = fs::file_time_type::min();
  return seen;
}

// Re-runs the scene whenever a file it read changes (polled four times a second: editors save by
// rename as often as in place, which file-system events see differently), or the page asks.
void watch(const Options& o, int poll_ms, const std::string& dir, State& st, std::atomic<bool>& rerun, MeshMemo& memo) {
  Stamps seen = run_and_stamp(o, poll_ms, dir, st, memo, {o.path}, rerun);
  for (;;) {
    {
      std::unique_lock<std::mutex> hold(st.lock);
      st.changed.wait_for(hold, std::chrono::milliseconds(poll_ms), [&] { return st.stopping; });
      if (st.stopping) return;
    }
    std::vector<std::string> files;
    for (const auto& [f, t] : seen) files.push_back(f);
    if (stamp(files) == seen && !rerun.exchange(false)) continue;
    rerun = false;
    seen = run_and_stamp(o, poll_ms, dir, st, memo, files, rerun);
  }
}

void routes(httplib::Server& svr, State& st, std::atomic<bool>& rerun) {
  svr.Get("/", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kIndexHtml, "text/html; charset=utf-8");
  });
  svr.Get(R"(/favicon\.ico)", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  svr.Get(R"(/preview\.js)", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kPreviewJs, "text/javascript; charset=utf-8");
  });
  svr.Get(R"(/viewer\.js)", [](const httplib::Request&, httplib::Response& res) {
    res.set_content(kViewerJs, "text/javascript; charset=utf-8");
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
  // A page going away (reload, close) says so: its stream's slot is free at once, not at the next
  // write that fails (a reload within seconds found every slot taken: 503). The slot is given back
// here, before the answer, not when the stream's thread wakes: a reload right after must find it.
  svr.Post("/closed", [&st](const httplib::Request& req, httplib::Response& res) {
    std::string page = req.get_param_value("page");
    if (!page.empty()) {
      std::lock_guard<std::mutex> hold(st.lock);
      if (st.live_pages.count(page) && st.closed_pages.insert(page).second) --st.streams;
    }
    st.changed.notify_all();
    res.status = 204;
  });
  svr.Get("/events", [&st](const httplib::Request& req, httplib::Response& res) {
    std::string page = req.get_param_value("page");
    {
      std::lock_guard<std::mutex> hold(st.lock);
      if (st.streams >= kMaxStreams) {
        res.status = 503;
        res.set_content("too many open pages", "text/plain");
        return;
      }
      ++st.streams;
      if (!page.empty()) ++st.live_pages[page];
    }
    res.set_header("Cache-Control", "no-store");
    auto sent = std::make_shared<uint64_t>(~uint64_t{0});
    res.set_chunked_content_provider(
        "text/event-stream",
        [&st, sent, page](size_t, httplib::DataSink& sink) {
          std::string out;
          {
            std::unique_lock<std::mutex> hold(st.lock);
            auto gone = [&] { return st.stopping || (!page.empty() && st.closed_pages.count(page)); };
            // While a run is under way, its progress four times a second; else wait for the next state.
            if (st.running)
              st.changed.wait_for(hold, std::chrono::milliseconds(250), [&] { return gone() || st.version != *sent; });
            else  // idle: until a state, a run starting, the page closing, or the keep-alive
              st.changed.wait_for(hold, std::chrono::seconds(15),
                                  [&] { return gone() || st.version != *sent || st.running; });
            if (gone()) return false;
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
        [&st, page](bool) {
          std::lock_guard<std::mutex> hold(st.lock);
          // A closed page's slot was given back by /closed (once for all its streams).
          if (page.empty() || !st.closed_pages.erase(page)) --st.streams;
          if (!page.empty() && --st.live_pages[page] == 0) st.live_pages.erase(page);
        });
  });
}

// xdg-open URL, without waiting for it; a note when there is no desktop to ask.
void open_page(const std::string& url) {
  pid_t pid;
  const char* argv[] = {"xdg-open", url.c_str(), nullptr};
  // Through stdio, not std::cerr: the watcher's run has std::cerr captured for the page meanwhile.
  if (posix_spawnp(&pid, "xdg-open", nullptr, nullptr, const_cast<char* const*>(argv), environ) != 0)
    std::fprintf(stderr, "fvrml-run: --open: no xdg-open here; open %s yourself\n", url.c_str());
}

}  // namespace

Options preview_run_options(const Options& base, const std::string& output) {
  Options o = base;
  o.output = output;
  o.format = "glb";
  o.stats = true;
  o.view_json = true;
  o.print_shape_diagnostics = true;
  return o;
}

struct Preview::Impl {
  Options o;
  ServeOptions s;
  State st;
  std::atomic<bool> rerun{false};
  MeshMemo memo;
  httplib::Server svr;
  fs::path dir;
  int port = -1;
  std::thread watcher, listener;
  std::atomic<bool> listened{true}, listening_ended{false};
  bool started = false;

  void mark_stopping() {
    {
      std::lock_guard<std::mutex> hold(st.lock);
      st.stopping = true;
    }
    st.changed.notify_all();
  }
};

Preview::Preview(const Options& o, const ServeOptions& s) : impl_(std::make_unique<Impl>()) {
  impl_->o = o;
  impl_->s = s;
}

Preview::~Preview() { stop(); }

int Preview::port() const { return impl_->port; }

std::string Preview::url() const {
  const std::string& host = impl_->s.host;
  return "http://" + (host.find(':') != std::string::npos ? "[" + host + "]" : host) + ":" +
      std::to_string(impl_->port) + "/";
}

bool Preview::start(std::string& error, std::function<void()> ended) {
  Impl& p = *impl_;
  std::error_code ec;
  static std::atomic<int> previews{0};  // tests run several in one process
  p.dir = fs::temp_directory_path(ec) / ("fvrml-serve-" + std::to_string(getpid()) + "-" + std::to_string(previews++));
  if (ec || !fs::create_directories(p.dir, ec) || ec) {
    error = "cannot make a scratch folder in " + fs::temp_directory_path(ec).string();
    return false;
  }
  // SO_REUSEADDR only: the library's default adds SO_REUSEPORT, which lets a second server take a
  // port already in use without an error.
  p.svr.set_socket_options([](int sock) {
    int yes = 1;
    setsockopt(sock, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  p.svr.set_payload_max_length(64 * 1024);
  p.svr.set_read_timeout(5, 0);
  p.svr.set_keep_alive_max_count(100);
  routes(p.svr, p.st, p.rerun);
  p.port = p.s.port == 0 ? p.svr.bind_to_any_port(p.s.host) : (p.svr.bind_to_port(p.s.host, p.s.port) ? p.s.port : -1);
  if (p.port < 0) {
    error = "cannot listen on " + p.s.host + ":" + std::to_string(p.s.port) + " (in use? --port N picks another)";
    fs::remove_all(p.dir, ec);
    return false;
  }
  p.started = true;
  p.watcher = std::thread([&p] { watch(p.o, p.s.poll_ms, p.dir.string(), p.st, p.rerun, p.memo); });
  p.listener = std::thread([&p, ended] {
    p.listened = p.svr.listen_after_bind();
    p.listening_ended = true;
    bool stopping;
    {
      std::lock_guard<std::mutex> hold(p.st.lock);
      stopping = p.st.stopping;
    }
    if (!stopping && ended) ended();
  });
  while (!p.svr.is_running() && !p.listening_ended)  // the URL printed next is live
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return true;
}

bool Preview::stop() {
  Impl& p = *impl_;
  if (!p.started) return true;
  p.started = false;
  p.mark_stopping();
  // httplib's stop() does nothing before the listener thread is inside listen(): asked again
  // until that thread has ended (a stop right after start would otherwise wait forever).
  while (!p.listening_ended) {
    p.svr.stop();
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  p.watcher.join();
  p.listener.join();
  std::error_code ec;
  fs::remove_all(p.dir, ec);
  return p.listened;
}

int serve(const Options& o, const ServeOptions& s) {
  if (!o.output.empty()) {
    std::cerr << "error: --serve writes no file: leave out -o\n";
    return 2;
  }
  // Ctrl-C and SIGTERM: the handler (on whichever thread the signal lands) writes a byte that wakes
  // this thread, which stops the server: the handler itself could not do that safely.
  if (pipe(stop_pipe) != 0) {
    std::cerr << "error: --serve: " << std::strerror(errno) << "\n";
    return 1;
  }
  struct sigaction on_stop{};
  on_stop.sa_handler = [](int) { [[maybe_unused]] ssize_t k = write(stop_pipe[1], "s", 1); };
  sigemptyset(&on_stop.sa_mask);
  sigaction(SIGINT, &on_stop, nullptr);
  sigaction(SIGTERM, &on_stop, nullptr);
  // A scene that is not there is an error now; one with errors in it is served (and fixed by a save).
  std::string text, error;
  if (!fscript::support::read_file(o.path, text, error, fscript::support::kMaxInputBytes)) {
    std::cerr << o.path << ":1:1: error: cannot read the file: " << error << "\n";
    return 1;
  }
  Preview preview(o, s);
  if (!preview.start(error, [] { [[maybe_unused]] ssize_t k = write(stop_pipe[1], "e", 1); })) {
    std::cerr << "error: --serve: " << error << "\n";
    return 1;
  }
  std::cout << "fvrml-run: serving " << o.path << " at " << preview.url() << " (Ctrl-C stops)" << std::endl;
  if (s.open) open_page(preview.url());
  char byte;
  while (read(stop_pipe[0], &byte, 1) < 0 && errno == EINTR) {}
  bool listened = preview.stop();
  signal(SIGINT, SIG_DFL), signal(SIGTERM, SIG_DFL);
  std::cout << "fvrml-run: stopped" << std::endl;
  return listened ? 0 : 1;
}

}  // namespace fvrml_run
