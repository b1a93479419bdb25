// The golden runner: walks tests/golden/**.fs, each a script whose comments hold expectations:
//   // error: TEXT          on the offending line (an error whose message contains TEXT);
//   // error@COL: TEXT      the same with a column;   // warning: TEXT   likewise for warnings
//   // run: f(1, 2) == 3    call f (`$` = the script's entry) on every backend, before and after
//                           optimisation, alone and as lanes of a batch with f's other runs and
//                           other points; `~=` allows 4 ulp; `== a, b` for several outputs;
//                           `error: TEXT` expects a runtime error;  nan, inf, -inf, -0 allowed
//   // ir-after: fold,dce   then `//   ` lines: the IR after those passes, exactly
//   // flags: max-loop=N max-depth=N max-array=N
// Every case also round-trips its IR through the printer and reader. FSCRIPT_BLESS=1 rewrites
// ir-after blocks.
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "backends/backend.h"
#include "runtime/support/big_stack.h"
#include "engine/driver/driver.h"
#include "ir/passes/passes.h"
#include "ir/text.h"
#include "ir/verifier.h"
#include "runtime/math/math.h"

namespace fs = std::filesystem;
using namespace fscript;

namespace {

struct Expect {
  uint32_t line;
  int col;  // -1: any
  std::string text;
  frontend::Severity sev;
};

struct RunLine {
  uint32_t line;
  std::string fn;
  std::vector<float> args;
  bool approx = false;
  std::vector<float> want;
  std::string error;  // expected runtime error text
};

struct IrBlock {
  uint32_t line;  // line of "// ir-after:"
  std::string passes;
  std::string want;
  size_t first_line, end_line;  // 0-based lines of the expected text in the file
};

struct Case {
  std::string path, text;
  std::vector<std::string> lines;
  std::vector<Expect> diags;
  std::vector<RunLine> runs;
  std::vector<IrBlock> irs;
  backends::Budgets budgets;
};

bool parse_float(std::string t, float& v) {
  t = std::regex_replace(t, std::regex("^\\s+|\\s+$"), "");
  char* end;
  v = std::strtof(t.c_str(), &end);
  return !t.empty() && *end == '\0';
}

std::vector<float> parse_list(const std::string& s, bool& ok) {
  std::vector<float> out;
  std::stringstream ss(s);
  std::string cell;
  ok = true;
  while (std::getline(ss, cell, ',')) {
    if (cell.find_first_not_of(" \t") == std::string::npos) continue;
    float v;
    ok &= parse_float(cell, v);
    out.push_back(v);
  }
  return out;
}

void parse_run(Case& c, uint32_t line, const std::string& spec) {
  static const std::regex re(R"(^\s*([$\w]+)\s*\(([^)]*)\)\s*(==|~=|error:)\s*(.*)$)");
  std::smatch m;
  INFO(c.path << ":" << line << ": bad run line: " << spec);
  REQUIRE(std::regex_match(spec, m, re));
  RunLine r;
  r.line = line;
  r.fn = m[1];
  bool ok;
  r.args = parse_list(m[2], ok);
  REQUIRE(ok);
  if (m[3] == "error:") {
    r.error = std::regex_replace(std::string(m[4]), std::regex("\\s+$"), "");
  } else {
    r.approx = m[3] == "~=";
    r.want = parse_list(m[4], ok);
    REQUIRE(ok);
  }
  c.runs.push_back(r);
}

Case load(const fs::path& p) {
  Case c;
  c.path = p.string();
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  c.text = ss.str();
  std::string l;
  std::istringstream ls(c.text);
  while (std::getline(ls, l)) c.lines.push_back(l);
  static const std::regex diag_re(R"(//\s*(error|warning)(@(\d+))?:\s*(.*?)\s*$)");
  for (size_t i = 0; i < c.lines.size(); ++i) {
    const std::string& s = c.lines[i];
    uint32_t line = static_cast<uint32_t>(i + 1);
    std::smatch m;
    size_t at;
    if ((at = s.find("// run:")) != std::string::npos) {
      parse_run(c, line, s.substr(at + 7));
    } else if ((at = s.find("// ir-after:")) != std::string::npos) {
      IrBlock b{line, std::regex_replace(s.substr(at + 12), std::regex("\\s"), ""), "", i + 1, i + 1};
      size_t k = i + 1;
      for (; k < c.lines.size() && c.lines[k].rfind("//   ", 0) == 0; ++k) b.want += c.lines[k].substr(5) + "\n";
      b.end_line = k;
      c.irs.push_back(b);
      i = k - 1;
    } else if ((at = s.find("// flags:")) != std::string::npos) {
      std::smatch f;
      std::string rest = s.substr(at);
      static const std::regex flag_re(R"((max-loop|max-depth|max-array)=(\d+))");
      for (auto it = std::sregex_iterator(rest.begin(), rest.end(), flag_re); it != std::sregex_iterator(); ++it) {
        uint64_t v = std::stoull((*it)[2]);
        if ((*it)[1] == "max-loop") c.budgets.max_loop_iterations = v;
        if ((*it)[1] == "max-depth") c.budgets.max_call_depth = static_cast<uint32_t>(v);
        if ((*it)[1] == "max-array") c.budgets.max_array_elements = v;
      }
    } else if (std::regex_search(s, m, diag_re)) {
      c.diags.push_back({line, m[3].matched ? std::stoi(m[3]) : -1, m[4],
                         m[1] == "error" ? frontend::Severity::Error : frontend::Severity::Warning});
    }
  }
  return c;
}

uint32_t ulp_distance(float a, float b) {
  if (a == b) return 0;
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0 : UINT32_MAX;
  auto key = [](float f) {
    int32_t i;
    std::memcpy(&i, &f, 4);
    return i < 0 ? static_cast<int64_t>(INT32_MIN) - i : static_cast<int64_t>(i);
  };
  int64_t d = key(a) - key(b);
  return static_cast<uint32_t>(std::min<int64_t>(d < 0 ? -d : d, UINT32_MAX));
}

void check_diagnostics(const Case& c, const frontend::DiagnosticSink& sink) {
  std::vector<bool> used(c.diags.size(), false);
  for (const auto& d : sink.all()) {
    if (d.severity == frontend::Severity::Note) continue;
    bool found = false;
    for (size_t k = 0; k < c.diags.size() && !found; ++k) {
      const Expect& e = c.diags[k];
      if (!used[k] && e.sev == d.severity && e.line == d.pos.line && (e.col < 0 || e.col == int(d.pos.col)) &&
          d.message.find(e.text) != std::string::npos)
        used[k] = found = true;
    }
    INFO("unexpected diagnostic:\n" << frontend::render(d));
    CHECK(found);
  }
  for (size_t k = 0; k < c.diags.size(); ++k) {
    INFO(c.path << ":" << c.diags[k].line << ": expected diagnostic not reported: " << c.diags[k].text);
    CHECK(used[k]);
  }
}

void round_trip(const Case& c, const ir::Module& m, const char* stage) {
  std::string text = ir::print(m), err;
  auto back = ir::read(text, err);
  INFO(c.path << ": IR reader failed " << stage << ": " << err << "\n" << text);
  REQUIRE(back);
  CHECK(ir::print(*back) == text);
  CHECK(ir::verify(*back) == "");
}

std::string functions_text(const ir::Module& m) {
  std::string s;
  for (const auto& f : m.functions) s += ir::print(m, *f);
  return s;
}

void check_ir_blocks(Case& c, const frontend::Script& s, const frontend::KernelSpec& spec, bool bless) {
  for (auto& b : c.irs) {
    frontend::DiagnosticSink quiet;
    std::string err;
    driver::BuildOptions bo;
    bo.optimize = false;
    auto m = driver::build_module(s, spec, quiet, bo, err);
    REQUIRE(m);
    ir::PassOptions po;
    po.verify_each = true;
    err = b.passes == "opt" ? ir::optimize(*m, po) : ir::run_passes(*m, b.passes, po);
    INFO(c.path << ":" << b.line << ": " << err);
    REQUIRE(err.empty());
    std::string got = functions_text(*m);
    if (bless) {
      b.want = got;
      continue;
    }
    INFO(c.path << ":" << b.line << ": IR after '" << b.passes << "' differs (FSCRIPT_BLESS=1 rewrites it)\n--- got:\n"
                << got << "--- want:\n"
                << b.want);
    CHECK(got == b.want);
  }
}

void bless_file(Case& c) {
  std::vector<std::string> out;
  size_t next = 0;
  for (size_t i = 0; i <= c.lines.size();) {
    if (next < c.irs.size() && i == c.irs[next].first_line) {
      std::istringstream ss(c.irs[next].want);
      std::string l;
      while (std::getline(ss, l)) out.push_back("//   " + l);
      i = c.irs[next].end_line;
      ++next;
      continue;
    }
    if (i == c.lines.size()) break;
    out.push_back(c.lines[i++]);
  }
  std::ofstream f(c.path);
  for (const auto& l : out) f << l << "\n";
}

// Runs per backend, one-point and batched: the last test case checks every backend the build has
// ran as many as the VM (a backend missing from the count is a failure, never a skip).
std::map<std::string, int> g_ran, g_batched;
size_t g_files_total = 0, g_files_run = 0;  // golden files, and those a filter (-c) let run

// The result of one point on `k` (false with the message on a runtime error).
bool eval_point(const backends::Kernel& k, std::vector<float> in, std::vector<float>& out,
                backends::RuntimeError& err) {
  in.resize(k.num_inputs(), 0.0f);
  out.assign(k.num_outputs(), 0.0f);
  return k.eval(in.data(), out.data(), err);
}

void check_point(const Case& c, const backends::Kernel& k, const RunLine& r) {
  std::vector<float> out;
  backends::RuntimeError rerr;
  bool ok = eval_point(k, r.args, out, rerr);
  if (!r.error.empty()) {
    INFO("message: " << rerr.message);
    CHECK(!ok);
    CHECK(rerr.message.find(r.error) != std::string::npos);
    return;
  }
  INFO("runtime error: " << rerr.message << " at line " << rerr.line);
  REQUIRE(ok);
  REQUIRE(out.size() == r.want.size());
  for (size_t j = 0; j < out.size(); ++j) {
    INFO(c.path << ":" << r.line << ": output " << j << ": got " << out[j] << " want " << r.want[j]);
    CHECK(ulp_distance(out[j], r.want[j]) <= (r.approx ? 4u : 0u));
  }
}

// The function's runs as lanes of one batch, mixed with other points so that lanes take different
// branches, each run at several lane positions (no multiple of 4, 8 or 16 apart). Every lane must
// give what that point gives alone: the run's expectation, or for an extra point its one-point
// result on the same kernel. Extra points that stop with a runtime error alone are left out.
void check_batch(const Case& c, const backends::Kernel& k, const std::vector<const RunLine*>& runs) {
  struct Lane {
    std::vector<float> in, want;
    const RunLine* run;  // nullptr: an extra point
  };
  std::vector<Lane> pool;
  for (const RunLine* r : runs)
    if (r->error.empty()) pool.push_back({r->args, r->want, r});
  if (pool.empty()) return;
  const float extra[] = {0.0f, 1.0f, -1.0f, 2.5f, -3.0f, 7.0f, 0.5f, 12.0f};
  for (int e = 0; e < 5; ++e) {
    std::vector<float> in(k.num_inputs()), out;
    for (size_t a = 0; a < in.size(); ++a) in[a] = extra[(static_cast<size_t>(e) * 3 + a * 5) % 8];
    backends::RuntimeError err;
    if (eval_point(k, in, out, err)) pool.push_back({in, out, nullptr});
  }
  size_t n = pool.size() * 3 + 5;
  std::vector<std::vector<float>> cols(k.num_inputs(), std::vector<float>(n)),
      outs(k.num_outputs(), std::vector<float>(n));
  std::vector<size_t> which(n);
  for (size_t i = 0; i < n; ++i) {
    which[i] = (i * 7 + i / pool.size()) % pool.size();
    for (size_t a = 0; a < cols.size(); ++a) cols[a][i] = a < pool[which[i]].in.size() ? pool[which[i]].in[a] : 0.0f;
  }
  std::vector<const float*> in;
  std::vector<float*> out;
  for (auto& col : cols) in.push_back(col.data());
  for (auto& col : outs) out.push_back(col.data());
  backends::RuntimeError err;
  INFO("batch of " << n << " lanes: " << err.message);
  REQUIRE(k.eval_batch(in.data(), out.data(), n, err));
  for (size_t i = 0; i < n; ++i) {
    const Lane& l = pool[which[i]];
    for (size_t j = 0; j < outs.size() && j < l.want.size(); ++j) {
      INFO(c.path << ":" << (l.run ? l.run->line : 0) << ": lane " << i << " output " << j << ": got " << outs[j][i]
                  << " want " << l.want[j]);
      CHECK(ulp_distance(outs[j][i], l.want[j]) <= (l.run && l.run->approx ? 4u : 0u));
    }
  }
}

// Every run of function `fn`, on every backend, before and after optimisation.
void check_runs(const Case& c, const frontend::Script& s, const std::string& fn,
                const std::vector<const RunLine*>& runs) {
  frontend::KernelSpec spec;
  std::string err;
  bool have = fn == "$" ? frontend::default_spec(s.sema, spec, err) : frontend::function_spec(s.sema, fn, spec, err);
  INFO(c.path << ":" << runs[0]->line << ": " << err);
  REQUIRE(have);
  for (bool optimize : {false, true}) {
    frontend::DiagnosticSink quiet;
    driver::BuildOptions bo;
    bo.optimize = optimize;
    bo.verify_each = true;
    auto m = driver::build_module(s, spec, quiet, bo, err);
    INFO(err);
    REQUIRE(m);
    for (const auto& name : backends::available_backends()) {
      std::unique_ptr<backends::Kernel> kernel;
      driver::Outcome o = driver::compile_kernel(*m, name, c.budgets, kernel);
      INFO("backend " << name << (optimize ? " (optimised)" : " (unoptimised)") << ": " << o.error);
      REQUIRE(o.ok());
      for (const RunLine* r : runs) {
        INFO(c.path << ":" << r->line);
        check_point(c, *kernel, *r);
        ++g_ran[name];
      }
      check_batch(c, *kernel, runs);
      ++g_batched[name];
    }
  }
}

void run_case(const fs::path& p, bool bless) {
  Case c = load(p);
  frontend::DiagnosticSink sink;
  frontend::Script s;
  bool ok = frontend::load_script(std::make_unique<frontend::SourceFile>(c.path, c.text), sink, s);
  frontend::KernelSpec spec;
  std::string err;
  if (!frontend::default_spec(s.sema, spec, err)) spec = {};
  std::unique_ptr<ir::Module> m;
  if (ok) {
    driver::BuildOptions bo;
    bo.optimize = false;
    bo.verify_each = true;
    m = driver::build_module(s, spec, sink, bo, err);
    INFO(c.path << ": " << err);
    REQUIRE(m);
  }
  check_diagnostics(c, sink);
  if (!ok) return;
  round_trip(c, *m, "before optimisation");
  ir::PassOptions po;
  po.verify_each = true;
  err = ir::optimize(*m, po);
  INFO(c.path << ": " << err);
  REQUIRE(err.empty());
  round_trip(c, *m, "after optimisation");
  check_ir_blocks(c, s, spec, bless);
  if (bless && !c.irs.empty()) bless_file(c);
  std::vector<std::string> fns;  // in the order of their first run
  std::map<std::string, std::vector<const RunLine*>> by_fn;
  for (const auto& r : c.runs) {
    if (!by_fn.count(r.fn)) fns.push_back(r.fn);
    by_fn[r.fn].push_back(&r);
  }
  for (const auto& fn : fns) check_runs(c, s, fn, by_fn[fn]);
}

}  // namespace

TEST_CASE("golden cases") {
  bool bless = std::getenv("FSCRIPT_BLESS") != nullptr;
  std::vector<fs::path> files;
  for (const auto& e : fs::recursive_directory_iterator(FS_GOLDEN_DIR))
    if (e.path().extension() == ".fs") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE(!files.empty());
  g_files_total = files.size();
  for (const auto& f : files) {
    DYNAMIC_SECTION(f.lexically_relative(FS_GOLDEN_DIR).string()) {
      ++g_files_run;
      // The calling thread waits, so Catch2 sees one thread at a time; failures are rethrown here.
      support::run_with_big_stack([&] { run_case(f, bless); });
    }
  }
}

// After every case (Catch2 runs test cases in declaration order): every backend this build has
// ran every run the VM ran, one point at a time and in batches.
TEST_CASE("golden cases: every backend of the build ran them all") {
  std::vector<std::string> built = {"vm"};
#ifdef FS_HAVE_SSE
  built.push_back("sse");
#endif
#ifdef FS_HAVE_WASM
  built.push_back("wasm");
#endif
#ifdef FS_HAVE_LLVM
  built.push_back("llvm");
#endif
  // The totals only when every file ran: `golden_runner -c "golden cases" -c run/arith.fs` runs one.
  if (g_files_run == g_files_total) {
    CHECK(g_ran["vm"] > 300);
    CHECK(g_batched["vm"] > 200);
  }
  for (const auto& name : built) {
    INFO("backend " << name << ": " << g_ran[name] << " runs, " << g_batched[name] << " batches; the VM " << g_ran["vm"]
                    << " and " << g_batched["vm"]);
    CHECK(g_ran[name] == g_ran["vm"]);
    CHECK(g_batched[name] == g_batched["vm"]);
  }
  CHECK(backends::available_backends().size() == built.size());
}
