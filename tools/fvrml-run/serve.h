#pragma once
// fvrml-run --serve, the live preview: a server for one scene, its page and its results, with a
// watcher that runs the scene again when a file it read changes. `Preview` is the server without
// the command line around it (signals, the URL printed), so tests can drive it in-process.
#include <functional>
#include <memory>
#include <string>

#include "tools/fvrml-run/run.h"

namespace fvrml_run {

struct ServeOptions {
  bool on = false, open = false;
  std::string host = "127.0.0.1";
  int port = 8800;  // 0: any free port
  int poll_ms = 250;  // how often the watcher looks at the files' modification times
};

// The options of the preview's runs: a glTF to `output`, time-dependent shapes as an animation of
// 24 frames (unless --frames says), the stats with the scene's view.
Options preview_run_options(const Options& base, const std::string& output);

class Preview {
 public:
  Preview(const Options& o, const ServeOptions& s);
  ~Preview();  // stops
  Preview(const Preview&) = delete;
  Preview& operator=(const Preview&) = delete;

  // Listens and starts the first run; false with `error` when it cannot. `ended`, when given, is
  // called on the server's thread if the server stops by itself (not by stop()).
  bool start(std::string& error, std::function<void()> ended = {});
  int port() const;
  std::string url() const;
  // Ends the event streams, the watcher and the server; returns once they have ended. False when
  // the server had failed on its own.
  bool stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fvrml_run
