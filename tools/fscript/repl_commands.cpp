// The REPL's commands: :help, :backend, :ir, :asm, :time, :plot, :load, :reset, :quit, and calls
// of the scripts a loaded .wrl scene brought in (by node name).
#include <chrono>
#include <cmath>
#include <regex>
#include <sstream>

#include "frontend/fscript/embedded.h"
#include "frontend/fscript/script.h"
#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"
#include "ir/text.h"
#include "tools/fscript/probe.h"
#include "tools/fscript/repl.h"
#include "runtime/support/files.h"

namespace fscript::cli {

namespace {

// The commands, for :help and Tab completion (the dispatch is Session::command).
struct CommandInfo {
  const char* name;
  const char* usage;
  const char* help;
};
constexpr CommandInfo kCommands[] = {
    {":help", "", "this text"},
    {":backend", "auto|vm|sse|llvm", "the backend that compiles what follows (no argument: the current one)"},
    {":ir", "NAME", "the optimised IR of function NAME"},
    {":asm", "NAME", "the generated code of NAME on the current backend"},
    {":time", "EXPR", "evaluations per second of EXPR"},
    {":plot", "EXPR [from A to B]", "EXPR of x as a chart, or of x and y as a picture (default -1 to 1)"},
    {":load", "FILE", "a .fs script's definitions, or every script of a .wrl scene, listed with a callable name"},
    {":probe", "X Y Z [T]",
     "every variable of the last :load-ed script at the point, each if's branch, each min's and max's side"},
    {":bound", "X0 X1 Y0 Y1 Z0 Z1 [T0 T1]",
     "every variable's interval over the box, and what each if, min and max does there"},
    {":reset", "", "forget every definition"},
    {":quit", "", "leave (also Ctrl-D); Ctrl-C stops a long evaluation"},
};

std::string help_text() {
  std::string s =
      "Type a definition (function f(x) { ... }, var a = 1;) and it stays; type an expression and\n"
      "its value prints. Input continues on the next line while brackets are open or a line ends in\n"
      "an operator. Tab completes names and commands.\n";
  for (const CommandInfo& c : kCommands) {
    std::string head = std::string("  ") + c.name + (*c.usage ? std::string(" ") + c.usage : "");
    s += head + std::string(head.size() < 22 ? 22 - head.size() : 1, ' ') + c.help + "\n";
  }
  return s;
}

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// Top-level comma split (brackets nest).
std::vector<std::string> split_args(const std::string& s) {
  std::vector<std::string> out;
  int depth = 0;
  std::string cur;
  for (char c : s) {
    if (c == '(' || c == '[' || c == '{') ++depth;
    if (c == ')' || c == ']' || c == '}') --depth;
    if (c == ',' && depth == 0) {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  if (!trim(cur).empty()) out.push_back(trim(cur));
  return out;
}

bool uses_identifier(const std::string& expr, const std::string& name) {
  return std::regex_search(expr, std::regex("(^|[^A-Za-z0-9_$.])" + name + "([^A-Za-z0-9_$]|$)"));
}

std::string chart(const std::vector<float>& ys, float a, float b) {
  float lo = INFINITY, hi = -INFINITY;
  for (float y : ys)
    if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
  if (!(lo <= hi)) return "no finite value on [" + format_number(a) + ", " + format_number(b) + "]\n";
  if (hi == lo) hi = lo + 1;
  const int rows = 16;
  std::vector<std::string> grid(rows, std::string(ys.size(), ' '));
  if (lo < 0 && hi > 0) {  // the x axis
    int r = static_cast<int>(std::lround((hi - 0) / (hi - lo) * (rows - 1)));
    grid[static_cast<size_t>(r)].assign(ys.size(), '-');
  }
  for (size_t i = 0; i < ys.size(); ++i) {
    if (!std::isfinite(ys[i])) continue;
    int r = static_cast<int>(std::lround((hi - ys[i]) / (hi - lo) * (rows - 1)));
    grid[static_cast<size_t>(r)][i] = '*';
  }
  std::ostringstream out;
  for (int r = 0; r < rows; ++r) {
    std::string label = r == 0 ? format_number(hi) : r == rows - 1 ? format_number(lo) : "";
    out << std::string(12 - std::min<size_t>(12, label.size()), ' ') << label << " |" << grid[static_cast<size_t>(r)]
        << "\n";
  }
  out << std::string(13, ' ') << "x from " << format_number(a) << " to " << format_number(b) << "\n";
  return out.str();
}

// Whether the sample r, c lies on the zero contour: inside (f >= 0) while its right or lower
// neighbour is not, or the other way round.
bool on_contour(const std::vector<float>& v, int w, int h, int r, int c) {
  auto inside = [&](int rr, int cc) { return v[static_cast<size_t>(rr * w + cc)] >= 0; };
  bool here = inside(r, c);
  return (c + 1 < w && inside(r, c + 1) != here) || (r + 1 < h && inside(r + 1, c) != here);
}

bool has_contour(const std::vector<float>& v, int w, int h) {
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c)
      if (on_contour(v, w, h, r, c)) return true;
  return false;
}

// A heat map of f(x, y) with the zero contour (the shape's outline) drawn over it in 'o'.
std::string picture(const std::vector<float>& v, int w, int h, float a, float b) {
  static const char* kShades = " .:-=+*#%@";
  float lo = INFINITY, hi = -INFINITY;
  for (float y : v)
    if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
  if (!(lo <= hi)) return "no finite value\n";
  std::ostringstream out;
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      float y = v[static_cast<size_t>(r * w + c)];
      int s = std::isfinite(y) && hi > lo ? static_cast<int>((y - lo) / (hi - lo) * 9.0f + 0.5f) : 0;
      out << (on_contour(v, w, h, r, c) ? 'o' : kShades[std::clamp(s, 0, 9)]);
    }
    out << "\n";
  }
  out << "x, y from " << format_number(a) << " to " << format_number(b) << " (y up); ' ' is " << format_number(lo)
      << ", '@' is " << format_number(hi) << "; 'o' is the outline, f = 0\n";
  return out.str();
}

}  // namespace

std::vector<std::string> Session::completions(const std::string& prefix) const {
  static const char* kKeywords[] = {"function", "var",   "let",   "const",    "return", "if",    "else",
                                    "for",      "while", "break", "continue", "true",   "false", "pi"};
  std::vector<std::string> all;
  if (!prefix.empty() && prefix[0] == ':') {
    for (const CommandInfo& c : kCommands) all.push_back(c.name);
  } else {
    for (const auto& d : defs_) all.push_back(d.first);
    for (const auto& [name, callable] : scene_) all.push_back(name);
    for (int b = 0; b < frontend::kNumBuiltins; ++b) all.push_back(frontend::kBuiltins[b].name);
    for (const char* k : kKeywords) all.push_back(k);
    for (const char* g : frontend::kStandardGlobals) all.push_back(g);
  }
  std::vector<std::string> out;
  for (const auto& name : all)
    if (name.compare(0, prefix.size(), prefix) == 0 && std::find(out.begin(), out.end(), name) == out.end())
      out.push_back(name);
  std::sort(out.begin(), out.end());
  return out;
}

bool Session::command(const std::string& input, std::string& out) {
  size_t sp = input.find_first_of(" \t\n");
  std::string cmd = input.substr(0, sp), arg = sp == std::string::npos ? "" : trim(input.substr(sp));
  if (cmd == ":quit" || cmd == ":q") return false;
  if (cmd == ":help") out += help_text();
  else if (cmd == ":reset") defs_.clear(), scene_.clear(), out += "every definition forgotten\n";
  else if (cmd == ":backend") {
    if (!arg.empty() && !backends::make_backend(arg)) out += "error: " + backends::missing_backend_message(arg) + "\n";
    else if (!arg.empty()) opts_.backend = arg;
    if (arg.empty() || backends::make_backend(arg)) out += "backend " + opts_.backend + "\n";
  } else if (cmd == ":ir") cmd_ir(arg, out);
  else if (cmd == ":asm") cmd_asm(arg, out);
  else if (cmd == ":time") cmd_time(arg, out);
  else if (cmd == ":plot") cmd_plot(arg, out);
  else if (cmd == ":load") cmd_load(arg, out);
  else if (cmd == ":probe" || cmd == ":bound") cmd_probe(arg, cmd == ":bound", out);
  else out += "error: unknown command '" + cmd + "' (:help lists them)\n";
  return true;
}

// The session as one program with NAME as the kernel.
static bool compile_named(const Session& s, const std::string& name, const Options& o, Compiled& c, std::string& out,
                          bool want_kernel) {
  auto entry = [&](const frontend::SemaResult& sema, frontend::KernelSpec& spec, std::string& error) {
    if (name.empty()) error = "which function? (:ir NAME, :asm NAME)";
    return !name.empty() && frontend::function_spec(sema, name, spec, error);
  };
  Options with = o;
  with.want_kernel = want_kernel;
  frontend::DiagnosticSink diag;
  driver::Outcome r =
      driver::compile(std::make_unique<frontend::SourceFile>("<session>", s.program()), entry, with, diag, c);
  return report_compile(r, frontend::render_all(diag), out);
}

// The optimised IR of what NAME uses: the globals and global arrays its code touches, and its
// functions (the session's others, and the standard globals it never reads, are left out).
static std::string used_ir(const ir::Module& m) {
  std::vector<char> global(m.globals.size(), 0), array(m.arrays.size(), 0);
  for (const auto& f : m.functions)
    for (const auto& b : f->blocks)
      for (const ir::Inst* i : b->insts) {
        bool memory = ir::has_flag(i->op, ir::Memory) && i->aux >= 0;
        if (memory && (i->op == ir::Op::GLoad || i->op == ir::Op::GStore) && size_t(i->aux) < global.size())
          global[static_cast<size_t>(i->aux)] = 1;
        else if (memory && i->array_global && size_t(i->aux) < array.size()) array[static_cast<size_t>(i->aux)] = 1;
      }
  std::string out;
  for (size_t g = 0; g < global.size(); ++g)
    if (global[g]) out += "global @" + m.globals[g] + "\n";
  for (size_t a = 0; a < array.size(); ++a)
    if (array[a]) out += "garray @" + m.arrays[a] + "\n";
  for (const auto& f : m.functions) out += ir::print(m, *f);
  return out;
}

void Session::cmd_ir(const std::string& arg, std::string& out) {
  Compiled c;
  if (compile_named(*this, arg, opts_, c, out, false)) out += used_ir(*c.module);
}

void Session::cmd_asm(const std::string& arg, std::string& out) {
  Compiled c;
  if (!compile_named(*this, arg, opts_, c, out, true)) return;
  std::string error, text = backend_listing(opts_.backend, *c.module, c.kernel.get(), opts_.budgets, error);
  out += text.empty() ? "error: " + error + "\n" : text;
}

// Whether the kernel only returns constants (the optimiser computed the expression).
static bool folded_to_constant(const ir::Module& m) {
  for (const auto& f : m.functions) {
    if (!f->kernel) continue;
    if (f->blocks.size() != 1) return false;
    const ir::Inst* ret = f->entry()->terminator();
    if (!ret || ret->op != ir::Op::Ret) return false;
    for (const ir::Inst* a : ret->args)
      if (a->op != ir::Op::Const) return false;
    return true;
  }
  return false;
}

void Session::cmd_time(const std::string& arg, std::string& out) {
  Compiled c;
  if (arg.empty()) {
    out += "error: :time EXPR\n";
    return;
  }
  if (!compile("__repl__", {}, "return (\n" + arg + "\n);", arg, c, out)) return;
  if (folded_to_constant(*c.module))
    out +=
        "note: the expression was folded to a constant when compiled: this times returning that constant, "
        "not computing it\n";
  const backends::Kernel& k = *c.kernel;
  std::string name = opts_.backend;
  out += run_interruptible([&k, name] {
    using Clock = std::chrono::steady_clock;
    // Batches of 1, 2, 4... points until 0.3 s have passed: an expensive expression is timed in
    // about the time of one evaluation, a cheap one over many.
    std::vector<float> result(4096);
    float* outs[1] = {result.data()};
    backends::RuntimeError err;
    size_t done = 0, n = 1;
    auto start = Clock::now();
    double secs = 0;
    while (secs < 0.3) {
      if (!k.eval_batch(nullptr, outs, n, err)) return "error: " + err.message + "\n";
      done += n;
      n = std::min<size_t>(n * 2, result.size());
      secs = std::chrono::duration<double>(Clock::now() - start).count();
    }
    char line[128];
    std::snprintf(line, sizeof line, "%.3g evaluations/s (%.3g ns each, backend %s)\n", done / secs, secs * 1e9 / done,
                  name.c_str());
    return std::string(line);
  });
}

void Session::cmd_plot(const std::string& raw, std::string& out) {
  std::smatch m;
  std::string expr = raw;
  float a = -1, b = 1;
  static const std::regex range(R"(^(.*)\s+from\s+(\S+)\s+to\s+(\S+)\s*$)");
  if (std::regex_match(raw, m, range)) {
    expr = m[1];
    if (!parse_number(m[2], a) || !parse_number(m[3], b) || !(a < b)) {
      out += "error: :plot EXPR from A to B wants numbers with A < B\n";
      return;
    }
  }
  if (trim(expr).empty()) {
    out += "error: :plot EXPR\n";
    return;
  }
  bool two_d = uses_identifier(expr, "y"), chosen = m.empty();
  Compiled c;
  std::vector<std::string> params = two_d ? std::vector<std::string>{"x", "y"} : std::vector<std::string>{"x"};
  if (!compile("__plot__", params, "return (\n" + expr + "\n);", expr, c, out)) return;
  const backends::Kernel& k = *c.kernel;
  out += run_interruptible([&k, two_d, a, b, chosen] {
    int w = two_d ? 64 : 72, h = two_d ? 32 : 1;
    std::vector<float> v(static_cast<size_t>(w * h));
    auto sample = [&](float lo, float hi, backends::RuntimeError& err) {
      std::vector<float> xs, ys;
      for (int r = 0; r < h; ++r)
        for (int col = 0; col < w; ++col) {
          xs.push_back(lo + (hi - lo) * static_cast<float>(col) / static_cast<float>(w - 1));
          ys.push_back(h > 1 ? hi - (hi - lo) * static_cast<float>(r) / static_cast<float>(h - 1) : 0.0f);
        }
      const float* in[2] = {xs.data(), ys.data()};
      float* outs[1] = {v.data()};
      return k.eval_batch(in, outs, v.size(), err);
    };
    backends::RuntimeError err;
    if (!sample(a, b, err)) return "error: " + err.message + "\n";
    if (!two_d) return chart(v, a, b);
    if (!chosen || has_contour(v, w, h)) return picture(v, w, h, a, b);
    // No outline in -1..1: the shape is larger or smaller than that; look wider, then closer.
    for (float scale : {2.0f, 0.5f, 4.0f, 0.25f, 8.0f, 0.125f, 16.0f, 1 / 16.0f, 64.0f, 1 / 64.0f}) {
      if (!sample(-scale, scale, err)) return "error: " + err.message + "\n";
      if (has_contour(v, w, h))
        return picture(v, w, h, -scale, scale) + "(range chosen to show the outline; :plot EXPR from A to B sets it)\n";
    }
    if (!sample(a, b, err)) return "error: " + err.message + "\n";
    return picture(v, w, h, a, b) + "no outline (f = 0) from -64 to 64 either; :plot EXPR from A to B sets the range\n";
  });
}

namespace {

std::string lowercase_type(const vrml::Node& n) {
  std::string t = n.type;
  if (t.size() > 1 && t[0] == 'F') t.erase(0, 1);  // FGeometry -> geometry
  for (char& c : t) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return t;
}

// What a script does for its shape: "geometry", "texture", or the material field's own name.
std::string role_of(const vrml::Node& n, const std::string& field) {
  if (n.type == "FGeometry") return "geometry";
  if (n.type == "FTexture3D") return "texture";
  return field;
}

// The FGeometry, FMaterial and FTexture3D of every FShape named after it: its DEF name, else
// shapeN (N counting FShapes from 1 in file order); FTransforms likewise (transformN).
std::map<const vrml::Node*, std::string> script_owners(const vrml::Scene& scene) {
  std::map<const vrml::Node*, std::string> owner;
  int shapes = 0, transforms = 0;
  auto child = [](const vrml::Node& n, const char* field) -> const vrml::Node* {
    const vrml::Value* v = n.get(field);
    return v && !v->nodes.empty() ? v->nodes[0].get() : nullptr;
  };
  vrml::for_each_node(scene, [&](const vrml::Node& n) {
    if (n.type == "FTransform") {
      ++transforms;
      owner[&n] = n.def_name.empty() ? "transform" + std::to_string(transforms) : n.def_name;
    }
    if (n.type != "FShape") return;
    std::string name = n.def_name.empty() ? "shape" + std::to_string(++shapes) : (++shapes, n.def_name);
    if (const vrml::Node* g = child(n, "geometry")) owner[g] = name;
    if (const vrml::Node* a = child(n, "appearance")) {
      if (const vrml::Node* m = child(*a, "material")) owner[m] = name;
      if (const vrml::Node* t = child(*a, "texture3D")) owner[t] = name;
    }
  });
  return owner;
}

}  // namespace

void Session::cmd_probe(const std::string& arg, bool box, std::string& out) {
  if (probed_.empty()) {
    out += "error: :load a .fs script first (:probe and :bound look into its entry point)\n";
    return;
  }
  std::vector<float> v;
  std::istringstream words(arg);
  for (std::string w; words >> w;) {
    float x;
    if (!parse_number(w, x)) {
      out += "error: '" + w + "' is not a number\n";
      return;
    }
    v.push_back(x);
  }
  if (v.size() < (box ? 6u : 3u) || (box && v.size() % 2)) {
    out += box ? "error: :bound X0 X1 Y0 Y1 Z0 Z1 [T0 T1]\n" : "error: :probe X Y Z [T]\n";
    return;
  }
  if (box) probe_box(probed_, "", v, out);
  else probe_point(probed_, "", v, out);
}

void Session::cmd_load(const std::string& path, std::string& out) {
  if (path.empty()) {
    out += "error: :load FILE\n";
    return;
  }
  std::string text, error;
  if (!is_scene_path(path)) {
    if (!support::read_file(path, text, error, support::kMaxInputBytes)) {
      out += path + ": error: " + error + "\n";
      return;
    }
    frontend::DiagnosticSink diag;
    frontend::Script script;
    if (!frontend::load_script(std::make_unique<frontend::SourceFile>(path, program(text)), diag, script)) {
      out += frontend::render_all(diag);
      return;
    }
    defs_.erase(std::remove_if(defs_.begin(), defs_.end(), [&](const auto& d) { return d.first == "file:" + path; }),
                defs_.end());
    defs_.push_back({"file:" + path, text});
    probed_ = path;
    out += "loaded " + path + "\n";
    return;
  }
  if (!vrml::read_scene_text(path, text, error)) {
    out += path + ": error: " + error + "\n";
    return;
  }
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  if (!vrml::parse_scene(std::make_unique<frontend::SourceFile>(path, text), diag, scene)) {
    out += frontend::render_all(diag);
    return;
  }
  auto scripts = vrml::scene_scripts(scene);
  std::map<const vrml::Node*, std::string> owner = script_owners(scene);
  std::map<const vrml::Node*, int> per_node;
  for (const auto& s : scripts) ++per_node[s.node];
  std::string names;
  int count = 0, broken = 0;
  auto lines = std::make_shared<const std::vector<std::string>>(frontend::split_lines(text));
  for (const auto& s : scripts) {
    if (frontend::is_affine_field(s.script.field) || s.script.field == "operation") continue;
    // Checked now, its errors at the file's own lines; one with errors is left out.
    auto file = std::make_unique<frontend::SourceFile>(path, s.script.text, s.script.line, s.script.col);
    file->set_outer_lines(*lines);
    frontend::Script checked;
    size_t errors = diag.error_count();
    frontend::load_script(std::move(file), diag, checked);
    if (diag.error_count() != errors) {
      ++broken;
      continue;
    }
    // The node's own DEF name (with the field when it has several scripts), else its owner's
    // name and the script's role: shape1_geometry, shape1_diffuseColor, ball_texture.
    std::string name = !s.node->def_name.empty()
        ? (per_node[s.node] > 1 ? s.node->def_name + "_" + s.script.field : s.node->def_name)
        : owner.count(s.node) ? owner[s.node] + "_" + role_of(*s.node, s.script.field)
                              : lowercase_type(*s.node) + "_" + s.script.field;
    scene_[name] = {s.script.text, path, s.script.line, s.script.col, lines};
    names += (count++ % 6 == 0 ? "\n  " : " ") + name;
  }
  out += frontend::render_all(diag);
  std::string left_out = broken == 0
      ? ""
      : "; " + std::to_string(broken) + (broken == 1 ? " script" : " scripts") + " with errors (above) left out";
  out += names.empty() ? (broken ? "no script of " + path + " loaded" + left_out : "no FScript in " + path) + "\n"
                       : "loaded " + std::to_string(count) + (count == 1 ? " script" : " scripts") + " from " + path +
          left_out + ", each callable with its script's inputs (x, y, z, t or u, v, w, t):" + names + "\n";
}

// NAME(args) where NAME came from a loaded scene: the script compiled on its own (its entry
// point), the arguments evaluated in the session.
bool Session::call_scene_script(const std::string& input, std::string& out) {
  static const std::regex call(R"(^\s*([A-Za-z_$][A-Za-z0-9_$]*)\s*\(([\s\S]*)\)\s*;?\s*$)");
  std::smatch m;
  if (!std::regex_match(input, m, call) || !scene_.count(m[1])) return false;
  const SceneCallable& sc = scene_.at(m[1]);
  std::vector<float> args;
  for (const auto& a : split_args(m[2])) {
    Compiled c;
    if (!compile("__repl__", {}, "return (\n" + a + "\n);", a, c, out)) return true;
    float v = 0;
    backends::RuntimeError err;
    if (!c.kernel->eval(nullptr, &v, err)) {
      out += "error: " + err.message + "\n";
      return true;
    }
    args.push_back(v);
  }
  Compiled c;
  frontend::DiagnosticSink diag;
  auto file = std::make_unique<frontend::SourceFile>(sc.path, sc.text, sc.line, sc.col);
  file->set_outer_lines(*sc.lines);
  driver::Outcome r = driver::compile(std::move(file), driver::default_entry(), opts_, diag, c);
  if (!report_compile(r, frontend::render_all(diag), out)) return true;
  args.resize(c.kernel->num_inputs(), 0.0f);
  const backends::Kernel& k = *c.kernel;
  out += run_interruptible([&k, &args] {
    std::vector<float> results(k.num_outputs());
    backends::RuntimeError err;
    if (!k.eval(args.data(), results.data(), err)) return "error: " + err.message + "\n";
    std::string line;
    for (size_t i = 0; i < results.size(); ++i) line += (i ? " " : "") + format_number(results[i]);
    return line + "\n";
  });
  return true;
}

}  // namespace fscript::cli
