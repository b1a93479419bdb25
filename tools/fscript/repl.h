#pragma once
// The interactive fscript: line editing and history (libedit), definitions that stay, each
// expression's value, commands (:help, :backend, :ir, :asm, :time, :load, :plot, :reset, :quit).
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "tools/fscript/common.h"

namespace fscript::cli {

// The state a REPL session builds up; the loop (repl.cpp) and the commands (repl_commands.cpp)
// share it. Each definition is kept as its own text, so redefining a name replaces it.
class Session {
 public:
  explicit Session(const Options& o) : opts_(o) {
    if (opts_.backend.empty()) opts_.backend = backends::default_backend();  // what the banner says
  }

  // One complete input (brackets balanced): a definition, a command or an expression. Output and
  // errors go to `out`; returns false when the session should end (:quit).
  bool handle(const std::string& input, std::string& out);

  // Names that complete `prefix` (Tab): commands after ':', else definitions, scene scripts,
  // built-ins, keywords and the standard globals; sorted, no repeats.
  std::vector<std::string> completions(const std::string& prefix) const;

  const std::string& backend() const { return opts_.backend; }

  // The text of every accepted definition, then `tail`.
  std::string program(const std::string& tail = "") const;
  // Compiles `body` as the function `name` with `params` against the session; nullptr with the
  // errors rendered into `out` (positions relative to the input `input_text`).
  bool compile(const std::string& name, const std::vector<std::string>& params, const std::string& body,
               const std::string& input_text, Compiled& c, std::string& out) const;

 private:
  bool define(const std::string& input, std::string& out);
  void evaluate(const std::string& expr, std::string& out);
  bool command(const std::string& input, std::string& out);
  void cmd_ir(const std::string& arg, std::string& out);
  void cmd_asm(const std::string& arg, std::string& out);
  void cmd_time(const std::string& arg, std::string& out);
  void cmd_plot(const std::string& arg, std::string& out);
  void cmd_load(const std::string& arg, std::string& out);
  void cmd_probe(const std::string& arg, bool box, std::string& out);
  bool call_scene_script(const std::string& input, std::string& out);

  Options opts_;
  std::vector<std::pair<std::string, std::string>> defs_;  // (name, text)
  struct SceneCallable {
    std::string text, path;  // the script, and the .wrl it is in
    uint32_t line = 1, col = 1;  // where its text starts in the .wrl: diagnostics at the file's own places
    std::shared_ptr<const std::vector<std::string>> lines;  // the .wrl's lines, for carets
  };
  std::map<std::string, SceneCallable> scene_;  // node name -> its script
  std::string probed_;  // the last .fs :load-ed: what :probe and :bound look into
};

// Whether the brackets of `text` are all closed (outside strings and comments) and it does not end
// in an operator waiting for its operand: the REPL keeps reading lines until then.
bool input_complete(const std::string& text);

// Runs `work` in a child process and returns what it wrote; Ctrl-C (SIGINT) in the meantime kills
// it and returns "interrupted". The session survives anything the evaluation does.
std::string run_interruptible(const std::function<std::string()>& work);

// The REPL's words for where the compile driver stopped: `source_errors` (the diagnostics, rendered
// by the caller) for errors in the text, else one "error:" line. True when it did not stop.
bool report_compile(const driver::Outcome& r, const std::string& source_errors, std::string& out);

int run_repl(const Options& o);

}  // namespace fscript::cli
