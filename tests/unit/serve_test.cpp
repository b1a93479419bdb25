// fvrml-run --serve in-process, without a browser: the watcher runs the scene again when the scene
// or a file it Inlines changes, the event stream carries each new state (within 2 s of a save), a
// broken save keeps the last good glTF, animations stream their frames as they are made, shapes a
// save did not change are not polygonized again, and stop() ends the streams.
#include <httplib.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "tests/support/skip.h"
#include "tools/fvrml-run/serve.h"

namespace fs = std::filesystem;
using Json = nlohmann::json;
using fvrml_run::Preview;

namespace {

// A folder of scene files, removed at the end.
struct Folder {
  fs::path dir = fs::temp_directory_path() / ("serve-test-" + std::to_string(getpid()));
  Folder() { fs::create_directories(dir); }
  ~Folder() { fs::remove_all(dir); }
  std::string write(const std::string& name, const std::string& text) const {
    fs::path p = dir / name;
    fs::path tmp = dir / (name + ".tmp");
    std::ofstream(tmp) << text;
    fs::rename(tmp, p);  // as editors save: a new file in place of the old
    return p.string();
  }
};

// Every event of /events, parsed, on its own thread until the stream ends.
class Events {
 public:
  explicit Events(int port) : client_("127.0.0.1", port) {
    client_.set_read_timeout(60, 0);
    thread_ = std::thread([this] {
      client_.Get("/events", [this](const char* data, size_t n) {
        std::lock_guard<std::mutex> hold(lock_);
        buffer_.append(data, n);
        for (size_t end; (end = buffer_.find("\n\n")) != std::string::npos; buffer_.erase(0, end + 2)) {
          std::string block = buffer_.substr(0, end), kind, body;
          for (size_t at = 0; at < block.size();) {
            size_t eol = std::min(block.find('\n', at), block.size());
            std::string line = block.substr(at, eol - at);
            if (line.rfind("event: ", 0) == 0) kind = line.substr(7);
            if (line.rfind("data: ", 0) == 0) body = line.substr(6);
            at = eol + 1;
          }
          if (!kind.empty()) events_.push_back({kind, Json::parse(body)});
        }
        changed_.notify_all();
        return true;
      });
      std::lock_guard<std::mutex> hold(lock_);
      ended_ = true;
      changed_.notify_all();
    });
  }
  ~Events() {
    client_.stop();  // the stream would otherwise wait for the server's next keep-alive
    if (thread_.joinable()) thread_.join();
  }

  // The first state after event `from` that satisfies `pred`, within `seconds`; its index in `at`.
  template <class Pred>
  Json wait(Pred pred, double seconds, size_t from = 0, size_t* at = nullptr) {
    std::unique_lock<std::mutex> hold(lock_);
    Json found;
    changed_.wait_for(hold, std::chrono::duration<double>(seconds), [&] {
      for (size_t i = from; i < events_.size(); ++i)
        if (events_[i].first == "state" && pred(events_[i].second)) {
          found = events_[i].second;
          if (at) *at = i;
          return true;
        }
      return ended_;
    });
    return found;
  }
  size_t size() {
    std::lock_guard<std::mutex> hold(lock_);
    return events_.size();
  }
  std::vector<std::pair<std::string, Json>> all() {
    std::lock_guard<std::mutex> hold(lock_);
    return events_;
  }
  bool ended_within(double seconds) {
    std::unique_lock<std::mutex> hold(lock_);
    return changed_.wait_for(hold, std::chrono::duration<double>(seconds), [&] { return ended_; });
  }

 private:
  httplib::Client client_;
  std::thread thread_;
  std::mutex lock_;
  std::condition_variable changed_;
  std::string buffer_;
  std::vector<std::pair<std::string, Json>> events_;
  bool ended_ = false;
};

fvrml_run::Options options(const std::string& path, int frames = 0) {
  fvrml_run::Options o;
  o.path = path;
  o.frames = frames;
  o.threads = 2;
  return o;
}

std::unique_ptr<Preview> started(const fvrml_run::Options& o) {
  fvrml_run::ServeOptions s;
  s.on = true;
  s.port = 0;
  s.poll_ms = 50;
  auto p = std::make_unique<Preview>(o, s);
  std::string error;
  REQUIRE(p->start(error));
  CHECK(error.empty());
  return p;
}

std::string get(int port, const std::string& path, int* status = nullptr) {
  httplib::Client c("127.0.0.1", port);
  auto r = c.Get(path);
  if (status) *status = r ? r->status : 0;
  return r ? r->body : "";
}

Json glb_json(const std::string& glb) {
  REQUIRE(glb.size() > 20);
  REQUIRE(glb.compare(0, 4, "glTF") == 0);
  uint32_t n = 0;
  std::memcpy(&n, glb.data() + 12, 4);
  return Json::parse(glb.substr(20, n));
}

auto done = [](const Json& s) { return s["ok"] == true && s["partial"].is_null(); };

std::string ball(const std::string& radius, const std::string& extra = "") {
  return "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"" + radius +
      "^2 - x^2 - y^2 - z^2\" bboxSize 2 2 2 resolution [16] } }\n" + extra;
}

}  // namespace

TEST_CASE("preview: saves reach the event stream; a broken save keeps the last good scene") {
  Folder f;
  std::string scene = f.write("scene.wrl", ball("0.5", "Inline { url \"part.wrl\" }\n"));
  f.write("part.wrl", ball("0.2"));
  auto p = started(options(scene));
  Events ev(p->port());
  Json first = ev.wait(done, 30);
  REQUIRE(first["version"].get<int>() >= 1);
  std::string glb1 = get(p->port(), "/scene.glb");
  CHECK(glb_json(glb1)["meshes"].size() == 1);  // the scene's shape and the Inlined one, merged

  auto t0 = std::chrono::steady_clock::now();
  f.write("scene.wrl", ball("0.7", "Inline { url \"part.wrl\" }\n"));
  Json edited = ev.wait([&](const Json& s) { return s["version"] > first["version"] && done(s); }, 10);
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  REQUIRE(!edited.is_null());
  CHECK(seconds < 2);
  std::string glb2 = get(p->port(), "/scene.glb");
  CHECK(glb2 != glb1);

  f.write("part.wrl", ball("0.3"));  // a file the scene pulls in
  Json inlined = ev.wait([&](const Json& s) { return s["version"] > edited["version"] && done(s); }, 10);
  REQUIRE(!inlined.is_null());
  std::string glb3 = get(p->port(), "/scene.glb");
  CHECK(glb3 != glb2);

  f.write("scene.wrl", ball("0.7 +", "Inline { url \"part.wrl\" }\n"));
  Json broken = ev.wait([&](const Json& s) { return s["version"] > inlined["version"]; }, 10);
  REQUIRE(!broken.is_null());
  CHECK(broken["ok"] == false);
  std::string diagnostics = broken["diagnostics"];
  CHECK(diagnostics.find("scene.wrl:2:") != std::string::npos);
  CHECK(diagnostics.find("error:") != std::string::npos);
  CHECK(diagnostics.find('^') != std::string::npos);
  CHECK(get(p->port(), "/scene.glb") == glb3);  // the last good scene stays on screen

  f.write("scene.wrl", ball("0.6", "Inline { url \"part.wrl\" }\n"));
  Json fixed = ev.wait([&](const Json& s) { return s["version"] > broken["version"]; }, 10);
  REQUIRE(!fixed.is_null());
  CHECK(fixed["ok"] == true);
  CHECK(fixed["diagnostics"] == "");

  p->stop();
  CHECK(ev.ended_within(5));  // the stream ends with the server
}

TEST_CASE("preview: the watcher follows the files of EXTERNPROTOs") {
  Folder f;
  auto lib = [&](const std::string& radius) {
    f.write("lib.wrl",
            "#VRML V2.0 utf8\nPROTO Ball [ ] { FShape { geometry FGeometry { definition \"" + radius +
                "^2 - x^2 - y^2 - z^2\" bboxSize 2 2 2 resolution [16] } } }\n");
  };
  lib("0.5");
  std::string scene = f.write("scene.wrl", "#VRML V2.0 utf8\nEXTERNPROTO Ball [ ] \"lib.wrl#Ball\"\nBall { }\n");
  auto p = started(options(scene));
  Events ev(p->port());
  Json first = ev.wait(done, 30);
  REQUIRE(!first.is_null());
  std::string glb1 = get(p->port(), "/scene.glb");
  lib("0.6");
  Json edited = ev.wait([&](const Json& s) { return s["version"] > first["version"] && done(s); }, 10);
  REQUIRE(!edited.is_null());
  CHECK(get(p->port(), "/scene.glb") != glb1);
  lib("0.6 +");  // a broken PROTO file: its diagnostics, in its own file
  Json broken = ev.wait([&](const Json& s) { return s["version"] > edited["version"]; }, 10);
  REQUIRE(!broken.is_null());
  CHECK(broken["ok"] == false);
  CHECK(broken["diagnostics"].get<std::string>().find("lib.wrl:2:") != std::string::npos);
}

TEST_CASE("preview: a save polygonizes only the shapes it changed") {
  Folder f;
  auto two = [](const std::string& second, const std::string& extra = "") {
    return ball("0.5") + "Transform { translation 2 0 0 children FShape { geometry FGeometry { definition \"" + second +
        "\" bboxSize 2 2 2 resolution [16] } } }\n" + extra;
  };
  std::string scene = f.write("scene.wrl", two("0.4^2 - x^2 - y^2 - z^2"));
  auto p = started(options(scene));
  Events ev(p->port());
  Json first = ev.wait(done, 30);
  REQUIRE(!first.is_null());
  CHECK(first["stats"]["memo"] == Json({{"made", 2}, {"reused", 0}}));

  f.write("scene.wrl", two("0.3^2 - x^2 - y^2 - z^2"));
  Json one = ev.wait([&](const Json& s) { return s["version"] > first["version"] && done(s); }, 10);
  REQUIRE(!one.is_null());
  CHECK(one["stats"]["memo"] == Json({{"made", 1}, {"reused", 1}}));

  // A Viewpoint and a comment change no shape; the same glTF but for the view.
  f.write("scene.wrl", two("0.3^2 - x^2 - y^2 - z^2", "# a comment\nViewpoint { position 0 0 6 }\n"));
  Json none = ev.wait([&](const Json& s) { return s["version"] > one["version"] && done(s); }, 10);
  REQUIRE(!none.is_null());
  CHECK(none["stats"]["memo"] == Json({{"made", 0}, {"reused", 2}}));
  CHECK(none["stats"]["view"]["camera"]["position"] == Json({0, 0, 6}));

  // The same shape moved by its Transform is a different mesh in world coordinates.
  std::string moved = two("0.3^2 - x^2 - y^2 - z^2");
  moved.replace(moved.find("translation 2 0 0"), 17, "translation 3 0 0");
  f.write("scene.wrl", moved);
  Json shifted = ev.wait([&](const Json& s) { return s["version"] > none["version"] && done(s); }, 10);
  REQUIRE(!shifted.is_null());
  CHECK(shifted["stats"]["memo"] == Json({{"made", 1}, {"reused", 1}}));
}

TEST_CASE("preview: an animation's frames stream as they are made, coarse to fine") {
  Folder f;
  std::string scene =
      f.write("grow.wrl",
              "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"(0.3 + 0.5 * t)^2 - x^2 - y^2 - "
              "z^2\" bboxSize 2 2 2 resolution [24] } }\n"
              "FShape { geometry FGeometry { definition \"0.2^2 - (x - 1.5)^2 - y^2 - z^2\" bboxSize 4 2 2 "
              "resolution [12] } }\n");
  auto p = started(options(scene, 8));
  Events ev(p->port());
  Json last = ev.wait(done, 60);
  REQUIRE(!last.is_null());
  std::vector<size_t> partial_frames;
  for (const auto& [kind, s] : ev.all())
    if (kind == "state" && !s["partial"].is_null()) {
      CHECK(s["partial"]["of"] == 8);
      partial_frames.push_back(s["partial"]["frames"]);
    }
  // The stream sends the newest state when it wakes: some of the scenes after about 1, 2, 4 of 8
  // frames, in order (the other thread may have made more meanwhile, so two can hold as many).
  for (size_t k = 0; k < partial_frames.size(); ++k) {
    CHECK((partial_frames[k] >= 1 && partial_frames[k] < 8));
    if (k) CHECK(partial_frames[k] >= partial_frames[k - 1]);
  }
  Json anims = glb_json(get(p->port(), "/scene.glb"))["animations"];
  REQUIRE(anims.size() == 1);
  CHECK(anims[0]["channels"].size() == 8);
  CHECK(last["stats"]["memo"] == Json({{"made", 9}, {"reused", 0}}));  // the still shape once

  // A save that touches only the still shape: the growing one's frames come from the memo, and the
  // page gets no partial scenes (nothing is made frame by frame).
  size_t before = ev.size();
  f.write("grow.wrl",
          "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"(0.3 + 0.5 * t)^2 - x^2 - y^2 - "
          "z^2\" bboxSize 2 2 2 resolution [24] } }\n"
          "FShape { geometry FGeometry { definition \"0.25^2 - (x - 1.5)^2 - y^2 - z^2\" bboxSize 4 2 2 "
          "resolution [12] } }\n");
  size_t at = 0;
  Json again = ev.wait([&](const Json& s) { return s["version"] > last["version"] && done(s); }, 30, before, &at);
  REQUIRE(!again.is_null());
  CHECK(again["stats"]["memo"] == Json({{"made", 1}, {"reused", 8}}));
  auto events = ev.all();
  for (size_t i = before; i < at; ++i) CHECK((events[i].first != "state" || events[i].second["partial"].is_null()));
}

TEST_CASE("preview: a run hands over the scene after 1, 2, 4 ... frames of an animation") {
  Folder f;
  fvrml_run::Options o =
      options(f.write("grow.wrl",
                      "#VRML V2.0 utf8\nFShape { geometry FGeometry { definition \"(0.3 + 0.5 * t)^2 - "
                      "x^2 - y^2 - z^2\" bboxSize 2 2 2 resolution [16] } }\n"),
              8);
  o.threads = 1;  // exactly 1, 2 and 4 frames (with more threads, more may be made meanwhile)
  o.output = (f.dir / "grow.glb").string();
  o.format = "glb";
  std::vector<std::pair<size_t, Json>> seen;
  o.on_partial = [&](const std::string& glb, size_t frames, size_t of) {
    CHECK(of == 8);
    seen.push_back({frames, glb_json(glb)});
  };
  Json stats;
  REQUIRE(fvrml_run::run_scene(o, stats, nullptr) == 0);
  REQUIRE(seen.size() == 3);
  for (size_t k = 0; k < seen.size(); ++k) {
    CHECK(seen[k].first == (size_t{1} << k));
    CHECK(seen[k].second["animations"][0]["channels"].size() == seen[k].first);  // the frames made so far
  }
}

TEST_CASE("preview: a save during a long run cancels it; so does stopping") {
  Folder f;
  std::ifstream in(FS_SOURCE_DIR "/bench/scenes/gyroid-sphere256.wrl");
  std::string gyroid((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::string scene = f.write("scene.wrl", gyroid);  // 8 frames of about half a second each
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  auto t0 = std::chrono::steady_clock::now();
  auto p = started(options(scene, 8));
  Events ev(p->port());
  size_t at = 0;
  Json partial = ev.wait([](const Json& s) { return !s["partial"].is_null(); }, 120, 0, &at);
  REQUIRE(!partial.is_null());
  // The first frame (two at once, on two threads) took this long: the whole run takes about 4x.
  // Cancelled, it ends with the frames under way, whatever the build's speed.
  double frame = since(t0);
  t0 = std::chrono::steady_clock::now();
  f.write("scene.wrl", ball("0.5"));
  size_t ball_at = 0;
  Json next = ev.wait(done, 60, at, &ball_at);
  REQUIRE(!next.is_null());
  CHECK(next["stats"]["shapes"].size() == 1);  // the ball's run, not the gyroid's end
  CHECK(since(t0) < 2.5 * frame);
  auto events = ev.all();
  // Nothing of the gyroid's run after the save but partials and its cancelled end, which puts back
  // the state before it (no run had succeeded: not ok), so it never looks like a finished run.
  for (size_t i = at + 1; i < ball_at; ++i)
    CHECK((events[i].first != "state" || !events[i].second["partial"].is_null() || events[i].second["ok"] != true));

  f.write("scene.wrl", gyroid);
  REQUIRE(!ev.wait([](const Json& s) { return !s["partial"].is_null(); }, 120, ball_at).is_null());
  t0 = std::chrono::steady_clock::now();
  p->stop();  // Ctrl-C in the middle of a long run
  CHECK(since(t0) < 2.5 * frame);
}

TEST_CASE("preview: stopped right after it started, it ends") {
  Folder f;
  std::string scene = f.write("scene.wrl", ball("0.5"));
  for (int k = 0; k < 20; ++k) {  // once hung: httplib ignores a stop before its listen() has begun
    auto p = started(options(scene));
    CHECK(p->stop());
  }
}

TEST_CASE("preview: a port in use is a clear error") {
  Folder f;
  std::string scene = f.write("scene.wrl", ball("0.5"));
  auto p = started(options(scene));
  fvrml_run::ServeOptions s;
  s.port = p->port();
  Preview second(options(scene), s);
  std::string error;
  CHECK(!second.start(error));
  CHECK(error.find("cannot listen") != std::string::npos);
}

// The preview runs every corpus file that fvrml-run runs (at a fifth of the resolution: the same
// code, quicker), and its glTF is the scene's.
TEST_CASE("preview: every corpus file that runs previews") {
  if (!fs::exists(FS_CORPUS_DIR)) {
    fscript::test::skip(fscript::test::SkipKind::Missing, "the shared corpus folder is absent: " FS_CORPUS_DIR);
    return;
  }
  Folder f;
  size_t files = 0, previewed = 0;
  for (const auto& e : fs::recursive_directory_iterator(FS_CORPUS_DIR)) {
    if (e.path().extension() != ".wrl") continue;
    std::ifstream in(e.path());
    char head[8] = {};
    in.read(head, 7);
    if (std::string(head) == "BSCRYPT") continue;  // the encrypted course file
    ++files;
    fvrml_run::Options plain = options(e.path().string());
    plain.model.resolution_scale = 0.2;
    plain.output = (f.dir / "plain.glb").string();
    plain.format = "glb";
    Json stats;
    std::ostringstream quiet;
    std::streambuf* saved = std::cerr.rdbuf(quiet.rdbuf());
    int plain_rc = fvrml_run::run_scene(plain, stats, nullptr);
    fvrml_run::Options o = fvrml_run::preview_run_options(plain, (f.dir / "preview.glb").string());
    int rc = fvrml_run::run_scene(o, stats, nullptr);
    std::cerr.rdbuf(saved);
    INFO(e.path().string() << "\n" << quiet.str());
    CHECK(rc == plain_rc);
    if (plain_rc != 0) continue;
    std::ifstream glb(o.output, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(glb)), std::istreambuf_iterator<char>());
    CHECK(glb_json(bytes)["asset"]["version"] == "2.0");
    CHECK(stats.contains("view"));
    ++previewed;
  }
  CHECK(files > 50);
  CHECK(previewed > files / 2);
}
