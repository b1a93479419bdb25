// The REPL's loop (libedit line editing, history, multi-line input), definitions that replace
// their earlier versions, evaluation of expressions in a child process that Ctrl-C can stop, and
// diagnostics with carets under the line the user typed.
#include "tools/fscript/repl.h"

#include <editline/readline.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/select.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <regex>

#include "frontend/fscript/embedded.h"

namespace fscript::cli {

namespace {

uint32_t count_lines(const std::string& s) {
  uint32_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// How many brackets of `input` are open before line `line`, column `col` (1-based).
int depth_at(const std::vector<std::string>& lines, uint32_t line, uint32_t col) {
  int depth = 0;
  for (uint32_t l = 0; l < lines.size() && l < line; ++l)
    for (size_t c = 0; c < lines[l].size() && (l + 1 < line || c + 1 < col); ++c) {
      char ch = lines[l][c];
      depth += (ch == '(' || ch == '[' || ch == '{') - (ch == ')' || ch == ']' || ch == '}');
    }
  return depth;
}

// The REPL evaluates an expression as "return (EXPR);": a parser message about that '(' would
// speak of text the user never typed. At the input's own top level it says what was meant.
void unwrap_message(frontend::Diagnostic& d, const std::vector<std::string>& lines) {
  static const std::string kWrapper = "expected ')' to match the '(' at column ";
  if (d.message.rfind(kWrapper, 0) != 0 || depth_at(lines, d.pos.line, d.pos.col) != 0) return;
  size_t found = d.message.find(", found ");
  d.message = "expected an operator or the end of the expression" +
      (found == std::string::npos ? std::string() : d.message.substr(found));
}

// Diagnostics of a synthesized program, shown against what the user typed: positions inside the
// input (lines [first, first + count)) become "<input>:line:col"; anything after it (an unclosed
// construct found at the end) points at the input's end.
std::string render_mapped(const frontend::DiagnosticSink& diag, uint32_t first, const std::string& input,
                          bool input_only = false) {
  std::vector<std::string> lines = frontend::split_lines(input);
  uint32_t count = static_cast<uint32_t>(std::max<size_t>(lines.size(), 1));
  std::string out;
  for (frontend::Diagnostic d : diag.all()) {
    if (input_only && (d.pos.line < first || d.pos.line >= first + count)) continue;
    if (d.pos.line >= first) {
      d.path = "<input>";
      if (d.pos.line >= first + count) {
        d.pos.line = count;
        d.line_text = lines.empty() ? "" : lines.back();
        d.pos.col = d.caret_col = static_cast<uint32_t>(d.line_text.size() + 1);
        d.length = 1;
      } else {
        d.pos.line -= first - 1;
      }
      unwrap_message(d, lines);
    } else {
      d.path = "<session>";
    }
    out += frontend::render(d);
  }
  return out;
}

// Statements outside brackets: "var a = 1; while (...) ..." is code to run, not a definition.
int top_level_statements(const std::string& input) {
  int depth = 0, n = 1;
  std::string s = input;
  while (!s.empty() && (s.back() == ';' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
  for (char c : s) {
    if (c == '(' || c == '{' || c == '[') ++depth;
    if (c == ')' || c == '}' || c == ']') --depth;
    n += c == ';' && depth == 0;
  }
  return n;
}

// The name a definition binds: function NAME, var NAME, or NAME = (a global assignment). A var or
// an assignment is a definition only as a statement of its own.
bool definition_name(const std::string& input, std::string& name) {
  static const std::regex fn(R"(^\s*function\s+([A-Za-z_$][A-Za-z0-9_$]*))");
  static const std::regex var(R"(^\s*(?:var|let|const)\s+([A-Za-z_$][A-Za-z0-9_$]*))");
  static const std::regex assign(R"(^\s*([A-Za-z_$][A-Za-z0-9_$]*)\s*=[^=])");
  std::smatch m;
  if (std::regex_search(input, m, fn)) {
    name = m[1];
    return true;
  }
  if (top_level_statements(input) == 1 && input.find('{') == std::string::npos &&
      (std::regex_search(input, m, var) || std::regex_search(input, m, assign))) {
    name = m[1];
    return true;
  }
  return false;
}

volatile sig_atomic_t g_interrupted = 0;
void on_sigint(int) { g_interrupted = 1; }

}  // namespace

// Whether `text` ends in an operator that still needs its right operand ("1 +", "a &&", "x ="), so
// the next line continues it; "x++" and "x--" are complete.
bool ends_in_operator(const std::string& text) {
  std::string s = text;
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  size_t comment = s.rfind("//");  // a line comment at the end hides nothing
  if (comment != std::string::npos && s.find('\n', comment) == std::string::npos) {
    s.erase(comment);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
  }
  if (s.empty()) return false;
  if (s.size() >= 2 && (s.compare(s.size() - 2, 2, "++") == 0 || s.compare(s.size() - 2, 2, "--") == 0)) return false;
  return std::string("+-*/%=<>&|^!?:,~").find(s.back()) != std::string::npos;
}

bool input_complete(const std::string& text) {
  if (ends_in_operator(text)) return false;
  int depth = 0;
  char quote = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    char c = text[i];
    if (quote) {
      if (c == '\\') ++i;
      else if (c == quote) quote = 0;
      continue;
    }
    if (c == '"' || c == '\'') quote = c;
    else if (c == '/' && i + 1 < text.size() && text[i + 1] == '/')
      i = text.find('\n', i) == std::string::npos ? text.size() : text.find('\n', i);
    else if (c == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      size_t end = text.find("*/", i + 2);
      if (end == std::string::npos) return false;
      i = end + 1;
    } else if (c == '(' || c == '{' || c == '[') ++depth;
    else if (c == ')' || c == '}' || c == ']') --depth;
  }
  return depth <= 0 && !quote;
}

std::string run_interruptible(const std::function<std::string()>& work) {
  int fds[2];
  if (pipe(fds) != 0) return work();
  std::cout.flush();
  pid_t pid = fork();
  if (pid < 0) {
    close(fds[0]);
    close(fds[1]);
    return work();
  }
  if (pid == 0) {  // the child: compute, write, leave without running the parent's destructors
    close(fds[0]);
    signal(SIGINT, SIG_DFL);
    std::string text = work();
    for (size_t at = 0; at < text.size();) {
      ssize_t n = write(fds[1], text.data() + at, text.size() - at);
      if (n <= 0) break;
      at += static_cast<size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  struct sigaction sa{}, old{};
  sa.sa_handler = on_sigint;  // no SA_RESTART: read() returns on Ctrl-C
  sigemptyset(&sa.sa_mask);
  g_interrupted = 0;
  sigaction(SIGINT, &sa, &old);
  std::string text;
  char buf[4096];
  bool stopped = false;
  for (;;) {
    ssize_t n = read(fds[0], buf, sizeof buf);
    if (n > 0) {
      text.append(buf, static_cast<size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR && g_interrupted) {
      kill(pid, SIGKILL);
      stopped = true;
    }
    if (n == 0 || stopped || errno != EINTR) break;
  }
  close(fds[0]);
  int status = 0;
  waitpid(pid, &status, 0);
  sigaction(SIGINT, &old, nullptr);
  // The terminal sends Ctrl-C to the child too, which may die of it before we kill it.
  if (stopped || g_interrupted || (WIFSIGNALED(status) && WTERMSIG(status) == SIGINT)) return "interrupted\n";
  if (WIFSIGNALED(status)) return "error: the evaluation stopped on signal " + std::to_string(WTERMSIG(status)) + "\n";
  return text;
}

std::string Session::program(const std::string& tail) const {
  std::string text;
  for (const auto& d : defs_) text += d.second + "\n";
  return text + tail;
}

bool Session::compile(const std::string& name, const std::vector<std::string>& params, const std::string& body,
                      const std::string& input_text, Compiled& c, std::string& out) const {
  std::string head = "function " + name + "(";
  for (size_t i = 0; i < params.size(); ++i) head += (i ? ", " : "") + params[i];
  head += ") {\n";
  std::string prefix = program(head);
  // The input sits on its own lines inside `body`; find where.
  size_t at = body.find(input_text);
  uint32_t first = count_lines(prefix) + count_lines(body.substr(0, at == std::string::npos ? 0 : at)) + 1;
  frontend::DiagnosticSink diag;
  auto file = std::make_unique<frontend::SourceFile>("<input>", prefix + body + "\n}\n");
  driver::Outcome r = driver::compile(std::move(file), driver::named_entry(name), opts_, diag, c);
  // Warnings about what was just typed (a letter-case slip, as `check` says it) show with the value.
  if (r.ok()) out += render_mapped(diag, first, input_text, true);
  return report_compile(r, r.stage == driver::Stage::Source ? render_mapped(diag, first, input_text) : "", out);
}

bool report_compile(const driver::Outcome& r, const std::string& source_errors, std::string& out) {
  switch (r.stage) {
    case driver::Stage::Done: return true;
    case driver::Stage::Source: out += source_errors; return false;
    case driver::Stage::Internal: out += "internal error: " + r.error + "\n"; return false;
    case driver::Stage::Entry:
    case driver::Stage::NoBackend:
    case driver::Stage::Backend: out += "error: " + r.error + "\n"; return false;
  }
  return false;
}

bool Session::handle(const std::string& raw, std::string& out) {
  std::string input = trim(raw);
  if (input.empty()) return true;
  if (input[0] == ':') return command(input, out);
  std::string name;
  if (definition_name(input, name)) {
    define(input, out);
    return true;
  }
  if (!call_scene_script(input, out)) evaluate(input, out);
  return true;
}

// A definition replaces the one of the same name; it is kept only when the whole session still
// compiles with it.
bool Session::define(const std::string& input, std::string& out) {
  std::string name;
  definition_name(input, name);
  auto kept = defs_;
  kept.erase(std::remove_if(kept.begin(), kept.end(), [&](const auto& d) { return d.first == name; }), kept.end());
  std::string prefix;
  for (const auto& d : kept) prefix += d.second + "\n";
  frontend::DiagnosticSink diag;
  frontend::Script script;
  bool ok =
      frontend::load_script(std::make_unique<frontend::SourceFile>("<input>", prefix + input + "\n"), diag, script);
  out += render_mapped(diag, count_lines(prefix) + 1, input);
  if (!ok) return false;
  kept.push_back({name, input});
  defs_ = std::move(kept);
  return true;
}

void Session::evaluate(const std::string& raw, std::string& out) {
  std::string expr = raw;
  while (!expr.empty() && (expr.back() == ';' || std::isspace(static_cast<unsigned char>(expr.back()))))
    expr.pop_back();
  Compiled c;
  std::string errors;
  if (!compile("__repl__", {}, "return (\n" + expr + "\n);", expr, c, errors)) {
    // Not an expression: statements, run for their effect and any value they return.
    Compiled s;
    std::string statement_errors;
    bool looks_like_statements = raw.find(';') != std::string::npos || raw.find('{') != std::string::npos;
    if (!looks_like_statements || !compile("__repl__", {}, raw + "\n", raw, s, statement_errors)) {
      out += looks_like_statements ? statement_errors : errors;
      return;
    }
    c = std::move(s);
    errors = statement_errors;
  }
  out += errors;  // the warnings of what compiled
  const backends::Kernel& k = *c.kernel;
  out += run_interruptible([&k] {
    float value = 0;
    backends::RuntimeError err;
    if (!k.eval(nullptr, &value, err)) return "error: " + err.message + "\n";
    return format_number(value) + "\n";
  });
}

namespace {

// libedit's callback interface, with our own getc: Ctrl-C at the prompt (the terminal's SIGINT
// interrupting the read, or the key itself where the terminal does not turn it into a signal) sets
// a flag and ends the editor's read; the loop then drops the line and any continuation.
volatile sig_atomic_t g_prompt_interrupted = 0;
int g_wake[2] = {-1, -1};  // the handler's byte wakes the loop's select(), whichever thread took the signal
void on_prompt_sigint(int) {
  g_prompt_interrupted = 1;
  if (g_wake[1] >= 0) (void)!write(g_wake[1], "", 1);
}

int prompt_getc(FILE*) {
  unsigned char c;
  for (;;) {
    ssize_t n = read(STDIN_FILENO, &c, 1);
    if (n == 1) break;
    if (n < 0 && errno == EINTR && !g_prompt_interrupted) continue;
    // Ctrl-C (the terminal's SIGINT interrupted the read): end the editor's line, which the loop
    // then drops; or the end of input.
    return n < 0 && errno == EINTR ? '\r' : EOF;
  }
  if (c != 0x03) return c;
  g_prompt_interrupted = 1;  // a terminal without ISIG hands Ctrl-C over as a key
  return '\r';
}

struct LineState {
  bool have = false, eof = false;
  std::string text;
};
LineState g_line;

void on_line(char* line) {
  if (!line) {
    g_line.eof = true;
    return;
  }
  g_line.text = line;
  g_line.have = true;
  std::free(line);
}

// Tab: the session's names for the word under the cursor (':' starts a command).
const Session* g_session = nullptr;
std::vector<std::string> g_matches;

char* next_match(const char* text, int state) {
  if (state == 0) g_matches = g_session ? g_session->completions(text) : std::vector<std::string>{};
  size_t k = static_cast<size_t>(state);
  return k < g_matches.size() ? strdup(g_matches[k].c_str()) : nullptr;
}

char** complete(const char* text, int, int) {
  rl_attempted_completion_over = 1;  // names only, never file names
  return rl_completion_matches(text, next_match);
}

void prompt_for(const std::string& buffer) {
  rl_callback_handler_remove();
  rl_callback_handler_install(buffer.empty() ? "fs> " : "... ", on_line);
}

}  // namespace

// Input from a pipe or a file (`printf '1+2\n' | fscript repl`): lines as typed, no editor.
int run_lines(Session& session) {
  std::string buffer, line;
  while (std::getline(std::cin, line)) {
    buffer += line + "\n";
    if (!input_complete(buffer)) continue;
    std::string out;
    bool go = session.handle(buffer, out);
    buffer.clear();
    std::cout << out << std::flush;
    if (!go) return kExitOk;
  }
  if (!trim(buffer).empty()) {  // an unfinished last input still gets its answer (or its error)
    std::string out;
    session.handle(buffer, out);
    std::cout << out << std::flush;
  }
  return kExitOk;
}

int run_repl(const Options& o) {
  Session session(o);
  if (!isatty(STDIN_FILENO)) {
    std::cout << "fscript " << "(backend " << session.backend()
              << "): reading input that is not a terminal, one entry per line\n";
    return run_lines(session);
  }
  std::string history;
  if (const char* h = std::getenv("FSCRIPT_HISTORY")) history = h;
  else if (const char* home = std::getenv("HOME")) history = std::string(home) + "/.fscript_history";
  rl_catch_signals = 0;  // both before anything initialises the line editor
  rl_getc_function = prompt_getc;
  g_session = &session;
  rl_attempted_completion_function = complete;
  rl_completion_append_character = '\0';
  using_history();
  if (!history.empty()) read_history(history.c_str());
  std::cout << "fscript " << "(backend " << session.backend()
            << "): definitions stay, expressions print their value; :help for commands, Ctrl-D to leave\n"
            << std::flush;
  // Ctrl-C at the prompt drops the line being typed and any continuation, as node and Python do;
  // an evaluation in progress takes Ctrl-C itself (run_interruptible).
  struct sigaction at_prompt{};
  at_prompt.sa_handler = on_prompt_sigint;  // no SA_RESTART: select() returns on Ctrl-C
  sigemptyset(&at_prompt.sa_mask);
  sigaction(SIGINT, &at_prompt, nullptr);
  if (pipe(g_wake) == 0) {
    fcntl(g_wake[0], F_SETFL, O_NONBLOCK);
    fcntl(g_wake[1], F_SETFL, O_NONBLOCK);
  }
  std::string buffer;
  prompt_for(buffer);
  for (;;) {
    fd_set in;
    FD_ZERO(&in);
    FD_SET(STDIN_FILENO, &in);
    if (g_wake[0] >= 0) FD_SET(g_wake[0], &in);
    int ready = select(std::max(STDIN_FILENO, g_wake[0]) + 1, &in, nullptr, nullptr, nullptr);
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0 && FD_ISSET(STDIN_FILENO, &in) && !g_prompt_interrupted) rl_callback_read_char();
    if (g_prompt_interrupted) {
      char drain[64];
      while (g_wake[0] >= 0 && read(g_wake[0], drain, sizeof drain) > 0) {}
      g_prompt_interrupted = 0;
      rl_replace_line("", 0);
      g_line.have = false;  // the line Ctrl-C ended
      std::cout << "^C\n" << std::flush;
      buffer.clear();
      prompt_for(buffer);
      continue;
    }
    if (g_line.eof) {  // Ctrl-D
      std::cout << "\n";
      break;
    }
    if (!g_line.have) continue;
    g_line.have = false;
    buffer += g_line.text + "\n";
    if (!input_complete(buffer)) {
      prompt_for(buffer);
      continue;
    }
    std::string entry = trim(buffer);
    if (!entry.empty()) {
      add_history(entry.c_str());
      if (!history.empty()) write_history(history.c_str());
    }
    std::string out;
    rl_callback_handler_remove();  // the evaluation may take the terminal for a while
    bool go = session.handle(buffer, out);
    buffer.clear();
    std::cout << out << std::flush;
    if (!go) break;
    prompt_for(buffer);
  }
  rl_callback_handler_remove();
  signal(SIGINT, SIG_DFL);
  g_session = nullptr;
  for (int& f : g_wake) {
    if (f >= 0) close(f);
    f = -1;
  }
  return kExitOk;
}

}  // namespace fscript::cli
