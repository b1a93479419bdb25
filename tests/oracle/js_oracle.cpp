// The language checked against JavaScript itself: programs from the fuzzers' generator run on
// every backend and, written as JavaScript rounded to float32 (program_gen's second text), under
// node. Exact operations must agree bit for bit (zero signs and NaN included), the transcendental
// built-ins within the accuracy statement of docs/language.md. docs/testing.md, "The node oracle".
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "backends/backend.h"
#include "engine/driver/driver.h"
#include "tests/fuzz/program_gen.h"
#include "tests/oracle/oracle_points.h"

using namespace fscript;

namespace {

struct Options {
  std::string node = "node", prelude, keep;
  uint64_t seed = 1;
  int programs = 2000;
  double seconds = 0;  // > 0: fresh seeds, batch after batch, for that long
  int points = 48;
  int show = 5;
};

// One evaluation of one point: a value, a runtime error the language defines (an index out of
// range, an array used before it is created), or a budget (JavaScript has none: not compared).
struct Result {
  enum Kind { Value, Error, Budget } kind = Value;
  float value = 0;
  std::string message;
};

bool is_budget(const std::string& m) {
  return m.find("budget") != std::string::npos || m.rfind("recursion too deep", 0) == 0 ||
      m.find("sizes must be whole numbers") != std::string::npos;
}

std::vector<Result> evaluate(const backends::Kernel& k, const std::vector<float>& points) {
  size_t n = points.size() / 4;
  std::vector<Result> out(n);
  for (size_t p = 0; p < n; ++p) {
    float result = 0;
    float* outs[] = {&result};
    const float* in[] = {&points[4 * p], &points[4 * p + 1], &points[4 * p + 2], &points[4 * p + 3]};
    backends::RuntimeError err;
    if (k.eval_batch(in, outs, 1, err)) {
      out[p].value = result;
    } else {
      out[p].kind = is_budget(err.message) ? Result::Budget : Result::Error;
      out[p].message = err.message;
    }
  }
  return out;
}

bool same_result(const Result& a, const Result& b) {
  if (a.kind != b.kind) return false;
  if (a.kind != Result::Value) return a.message == b.message;
  return std::memcmp(&a.value, &b.value, 4) == 0 || (std::isnan(a.value) && std::isnan(b.value));
}

std::string show_float(float v) {
  char b[64];
  uint32_t u;
  std::memcpy(&u, &v, 4);
  std::snprintf(b, sizeof b, "%.9g (0x%08" PRIx32 ")", static_cast<double>(v), u);
  return b;
}

std::string show_point(const std::vector<float>& points, size_t p) {
  std::string s = "(";
  for (int c = 0; c < 4; ++c) s += (c ? ", " : "") + show_float(points[4 * p + c]);
  return s + ")";
}

std::string show_result(const Result& r) {
  return r.kind == Result::Value ? show_float(r.value) : "error: " + r.message;
}

// A program of the oracle: its two texts, its points, and what each backend gave.
struct Case {
  std::string name, fs, js;
  std::vector<float> points;
  std::vector<Result> ours;  // the VM's (every backend equals it, or the case is a finding)
  int max_ulps = 0;          // 0: bit for bit; else a built-in's accuracy bound
  int seen_ulps = 0;
};

struct Tally {
  int programs = 0, compared = 0, budget = 0, differences = 0, shown = 0;
};

// Compiles `c.fs` and runs it on the VM and on every other backend, which must agree with it.
bool run_ours(Case& c, Tally& t, const Options& o) {
  driver::CompileOptions co;
  co.backend = "vm";
  frontend::DiagnosticSink diag;
  driver::Compiled compiled;
  driver::Outcome r = driver::compile(std::make_unique<frontend::SourceFile>(c.name + ".fs", c.fs),
                                      driver::default_entry(), co, diag, compiled);
  if (!r.ok()) {
    std::cerr << "oracle: " << c.name << " does not compile: " << r.error << "\n" << frontend::render_all(diag) << c.fs;
    return false;
  }
  c.ours = evaluate(*compiled.kernel, c.points);
  for (const std::string& name : backends::available_backends()) {
    if (name == "vm") continue;
    std::string error;
    auto k = backends::make_backend(name)->compile(*compiled.module, co.budgets, error);
    if (!k) {
      std::cerr << "oracle: " << name << " cannot compile " << c.name << ": " << error << "\n";
      return false;
    }
    std::vector<Result> got = evaluate(*k, c.points);
    for (size_t p = 0; p < got.size(); ++p)
      if (!same_result(c.ours[p], got[p])) {
        if (t.shown++ < o.show)
          std::cerr << "oracle: " << c.name << ": " << name << " differs from the VM at " << show_point(c.points, p)
                    << ": " << show_result(got[p]) << " vs " << show_result(c.ours[p]) << "\n"
                    << c.fs;
        ++t.differences;
      }
  }
  return true;
}

// Distance in units in the last place, counting -0 and +0 as neighbours.
int64_t ulps(float a, float b) {
  auto key = [](float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return u & 0x80000000u ? -static_cast<int64_t>(u & 0x7FFFFFFFu) - 1 : static_cast<int64_t>(u);
  };
  return std::llabs(key(a) - key(b));
}

// Whether node's token for a point agrees with our result.
bool agrees(Case& c, const Result& ours, const std::string& token) {
  if (ours.kind == Result::Error) return token == "E";
  if (token.size() != 8 || token.find_first_not_of("0123456789abcdef") != std::string::npos) return false;
  uint32_t u = static_cast<uint32_t>(std::stoul(token, nullptr, 16));
  float js;
  std::memcpy(&js, &u, 4);
  if (std::memcmp(&js, &ours.value, 4) == 0 || (std::isnan(js) && std::isnan(ours.value))) return true;
  // Within the bound, for a built-in, where neither side is NaN, infinite or zero (exact there).
  if (c.max_ulps == 0 || !std::isfinite(js) || !std::isfinite(ours.value) || js == 0 || ours.value == 0) return false;
  int64_t d = ulps(js, ours.value);
  if (d > c.max_ulps) return false;
  c.seen_ulps = std::max(c.seen_ulps, static_cast<int>(d));
  return true;
}

std::string hex_points(const std::vector<float>& points) {
  std::string s = "[";
  char b[16];
  for (size_t i = 0; i < points.size(); ++i) {
    uint32_t u;
    std::memcpy(&u, &points[i], 4);
    std::snprintf(b, sizeof b, "%s\"%08" PRIx32 "\"", i ? "," : "", u);
    s += b;
  }
  return s + "]";
}

// Runs every case under node at once; one line of tokens per case, or empty on failure.
std::vector<std::vector<std::string>> run_node(const std::vector<Case>& cases, const Options& o) {
  std::ifstream prelude_in(o.prelude);
  if (!prelude_in) {
    std::cerr << "oracle: cannot read the prelude " << o.prelude << "\n";
    return {};
  }
  std::stringstream js;
  js << prelude_in.rdbuf() << "\n__run([\n";
  for (const Case& c : cases) js << "[function (x, y, z, t) {\n" << c.js << "}, " << hex_points(c.points) << "],\n";
  js << "]);\n";
  std::string path = o.keep;
  if (path.empty()) {
    char tmpl[] = "/tmp/fscript-oracle-XXXXXX.js";
    int fd = mkstemps(tmpl, 3);
    if (fd < 0) return {};
    close(fd);
    path = tmpl;
  }
  std::ofstream(path) << js.str();
  std::string command = "'" + o.node + "' '" + path + "'";
  FILE* pipe = popen(command.c_str(), "r");
  std::vector<std::vector<std::string>> lines;
  if (pipe) {
    std::string text;
    char buf[65536];
    for (size_t got; (got = std::fread(buf, 1, sizeof buf, pipe)) > 0;) text.append(buf, got);
    int status = pclose(pipe);
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
      std::istringstream words(line);
      lines.emplace_back();
      for (std::string w; words >> w;) lines.back().push_back(w);
    }
    if (status != 0) std::cerr << "oracle: node failed (status " << status << ")\n";
  }
  if (o.keep.empty()) std::remove(path.c_str());
  if (lines.size() != cases.size()) {
    std::cerr << "oracle: node gave " << lines.size() << " lines for " << cases.size() << " programs\n";
    return {};
  }
  return lines;
}

bool compare_with_node(std::vector<Case>& cases, Tally& t, const Options& o) {
  auto lines = run_node(cases, o);
  if (lines.empty()) return false;
  for (size_t i = 0; i < cases.size(); ++i) {
    Case& c = cases[i];
    for (size_t p = 0; p < c.ours.size(); ++p) {
      const Result& ours = c.ours[p];
      if (ours.kind == Result::Budget) {
        ++t.budget;
        continue;
      }
      ++t.compared;
      std::string token = p < lines[i].size() ? lines[i][p] : "(none)";
      if (agrees(c, ours, token)) continue;
      ++t.differences;
      if (t.shown++ < o.show)
        std::cerr << "oracle: " << c.name << " differs from node at " << show_point(c.points, p) << ": ours "
                  << show_result(ours) << ", node " << token << "\n---- FScript ----\n"
                  << c.fs << "---- JavaScript ----\n"
                  << c.js << "----\n";
    }
  }
  return true;
}

// Programs from seeds first .. first + count - 1.
bool run_programs(uint64_t first, int count, Tally& t, const Options& o) {
  std::vector<Case> cases;
  for (int k = 0; k < count; ++k) {
    uint64_t seed = first + static_cast<uint64_t>(k);
    std::mt19937_64 rng(seed);
    std::vector<uint8_t> bytes(64 + rng() % 1500);
    for (auto& b : bytes) b = static_cast<uint8_t>(rng());
    FuzzedDataProvider in(bytes.data(), bytes.size());
    fuzz::GenOptions go;
    go.straight_line = seed % 3 == 0;
    go.exact_only = true;
    fuzz::GeneratedProgram prog = fuzz::generate_program(in, go);
    Case c{"seed " + std::to_string(seed), prog.text, prog.js, oracle::program_points(rng, o.points), {}, 0, 0};
    if (!run_ours(c, t, o)) return false;
    cases.push_back(std::move(c));
  }
  t.programs += count;
  return compare_with_node(cases, t, o);
}

// Every transcendental built-in against JavaScript's Math, within its bound.
bool run_builtins(const Options& o) {
  std::vector<Case> cases;
  Tally t;
  for (const oracle::BuiltinCheck& b : oracle::builtin_checks()) {
    std::mt19937_64 rng(std::hash<std::string>{}(b.name) ^ o.seed);
    Case c{b.name, b.fs, b.js, oracle::builtin_points(rng, b.arity), {}, b.max_ulps, 0};
    if (!run_ours(c, t, o)) return false;
    cases.push_back(std::move(c));
  }
  if (!compare_with_node(cases, t, o)) return false;
  std::printf("oracle: built-ins against node's Math (ulps seen / bound):");
  for (const Case& c : cases) std::printf(" %s %d/%d", c.name.c_str(), c.seen_ulps, c.max_ulps);
  std::printf("; %d points, %d differences\n", t.compared, t.differences);
  return t.differences == 0;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto value = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if ((a == "--node" || a == "--prelude" || a == "--keep" || a == "--seed" || a == "--programs" || a == "--seconds" ||
         a == "--points" || a == "--show") &&
        !(v = value())) {
      std::cerr << "oracle: " << a << " needs a value\n";
      return false;
    }
    if (a == "--node") o.node = v;
    else if (a == "--prelude") o.prelude = v;
    else if (a == "--keep") o.keep = v;
    else if (a == "--seed") o.seed = std::strtoull(v, nullptr, 10);
    else if (a == "--programs") o.programs = std::atoi(v);
    else if (a == "--seconds") o.seconds = std::atof(v);
    else if (a == "--points") o.points = std::max(1, std::atoi(v));
    else if (a == "--show") o.show = std::atoi(v);
    else {
      std::cerr << "usage: js_oracle --prelude tests/oracle/prelude.js [--node PATH] [--seed N] [--programs N]\n"
                   "                 [--seconds S] [--points N] [--show N] [--keep FILE.js]\n";
      return false;
    }
  }
  if (o.prelude.empty()) std::cerr << "oracle: --prelude is required\n";
  return !o.prelude.empty();
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) return 2;
  if (!run_builtins(o)) return 1;
  Tally t;
  auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  uint64_t seed = o.seed;
  do {
    int count = o.seconds > 0 ? 250 : o.programs;
    if (!run_programs(seed, count, t, o)) return 1;
    seed += static_cast<uint64_t>(count);
  } while (o.seconds > 0 && elapsed() < o.seconds && t.differences == 0);
  std::string backends;
  for (const std::string& b : backends::available_backends()) backends += " " + b;
  std::printf("oracle: %d programs (seeds %" PRIu64 "..%" PRIu64
              "), %d points compared with node bit for bit, %d "
              "left out (budgets), %d differences; backends:%s (%.0f s)\n",
              t.programs, o.seed, seed - 1, t.compared, t.budget, t.differences, backends.c_str(), elapsed());
  return t.differences == 0 ? 0 : 1;
}
