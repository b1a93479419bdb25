// IR file tests of the optimiser's passes (tests/golden/passes/*.ir), run by the golden runner:
// IR text in, a line naming the passes, the IR expected after them, one file per pass with the
// cases that matter to it. FSCRIPT_BLESS=1 rewrites the expectations.
//   ; comment lines start with a semicolon
//   ; passes: fold,dce        the passes to run, as `fscript emit-ir --passes` names them, or
//                             row-split: the row split's prologue and body (ir/passes/row_split.h),
//                             or tape-simplify [lo,hi] ...: the kernel's interval tape simplified
//                             for the region of those input intervals (ir/interval_eval.h)
//   <the module as the printer writes it: it must read back to exactly this text>
//   ; expect:
//   <the module after the passes>
#include <catch2/catch.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "ir/passes/passes.h"
#include "ir/interval_eval.h"
#include "ir/passes/row_split.h"
#include "ir/tape.h"
#include "ir/text.h"
#include "ir/verifier.h"

namespace fs = std::filesystem;
using namespace fscript;

namespace {

struct PassFile {
  std::vector<std::string> head;  // every line up to and with "; expect:"
  std::string passes, input, want;
  bool has_expect = false;
};

PassFile parse(const fs::path& p) {
  PassFile f;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);) {
    if (f.has_expect) {
      f.want += line + "\n";
      continue;
    }
    f.head.push_back(line);
    if (line.rfind("; passes:", 0) == 0) {
      f.passes = line.substr(9);
      f.passes.erase(0, f.passes.find_first_not_of(' '));
    } else if (line == "; expect:") {
      f.has_expect = true;
    } else if (line.empty() || line[0] != ';') {
      f.input += line + "\n";
    }
  }
  return f;
}

// The first line where two texts differ, for the failure message.
std::string first_difference(const std::string& got, const std::string& want) {
  std::istringstream a(got), b(want);
  std::string la, lb;
  for (int n = 1;; ++n) {
    bool more_a = static_cast<bool>(std::getline(a, la)), more_b = static_cast<bool>(std::getline(b, lb));
    if (!more_a && !more_b) return "none";
    if (!more_a || !more_b || la != lb)
      return "line " + std::to_string(n) + ": got '" + (more_a ? la : "(end)") + "', want '" + (more_b ? lb : "(end)") +
          "'";
  }
}

// The kernel's tape simplified for the region given as "[lo,hi] [lo,hi] ..." (one per input), as
// IR, after a line with the number of choices decided.
std::string simplified_tape(const ir::Module& m, const std::string& region) {
  std::vector<math::Interval> inputs;
  std::istringstream in(region);
  for (std::string word; in >> word;) {
    float lo = 0, hi = 0;
    REQUIRE(std::sscanf(word.c_str(), "[%f,%f]", &lo, &hi) == 2);
    inputs.push_back(math::Interval{lo, hi, 0});
  }
  ir::IntervalTape tape(m.kernel_function());
  REQUIRE(inputs.size() == tape.num_params());
  ir::IntervalEval ev;
  tape.eval(inputs, ev);
  size_t collapsed = 0;
  ir::IntervalTape simple = tape.simplified(ev, &collapsed);
  auto module = ir::tape_module(simple);
  REQUIRE(ir::verify(*module) == "");
  return "; " + std::to_string(collapsed) + " choices decided, " + std::to_string(tape.length()) + " -> " +
      std::to_string(simple.length()) + " steps\n" + ir::print(*module);
}

void run_pass_file(const fs::path& p, bool bless) {
  PassFile f = parse(p);
  INFO(p.string());
  REQUIRE(!f.passes.empty());
  REQUIRE(f.has_expect);
  std::string err;
  auto m = ir::read(f.input, err);
  INFO("read: " << err);
  REQUIRE(m);
  {
    INFO("the input is not in the printer's form, " << first_difference(ir::print(*m), f.input)
                                                    << "; it reads back as:\n"
                                                    << ir::print(*m));
    CHECK(ir::print(*m) == f.input);
  }
  REQUIRE(ir::verify(*m) == "");
  std::string got;
  if (f.passes.rfind("tape-simplify", 0) == 0) {
    got = simplified_tape(*m, f.passes.substr(13));
  } else if (f.passes == "row-split") {
    ir::RowSplit rs;
    if (ir::split_rows(*m, rs)) {
      REQUIRE(ir::verify(*rs.prologue) == "");
      REQUIRE(ir::verify(*rs.body) == "");
      got = "; prologue\n" + ir::print(*rs.prologue) + "; body\n" + ir::print(*rs.body);
    } else {
      got = "; no split\n";
    }
  } else {
    ir::PassOptions po;
    po.verify_each = true;
    err = ir::run_passes(*m, f.passes, po);
    INFO("passes: " << err);
    REQUIRE(err.empty());
    got = ir::print(*m);
  }
  if (bless) {
    std::ofstream out(p);
    for (const auto& l : f.head) out << l << "\n";
    out << got;
    return;
  }
  INFO("IR after '" << f.passes << "' differs at " << first_difference(got, f.want)
                    << " (FSCRIPT_BLESS=1 rewrites it)\n--- got:\n"
                    << got << "--- want:\n"
                    << f.want);
  CHECK(got == f.want);
}

}  // namespace

TEST_CASE("pass file tests") {
  bool bless = std::getenv("FSCRIPT_BLESS") != nullptr;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(fs::path(FS_GOLDEN_DIR) / "passes"))
    if (e.path().extension() == ".ir") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  REQUIRE(!files.empty());
  for (const auto& p : files) {
    DYNAMIC_SECTION("passes/" << p.filename().string()) { run_pass_file(p, bless); }
  }
}
