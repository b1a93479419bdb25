// A mutation fuzzer in the test suite: every golden case and a few seeds are mutated at random
// (bytes and tokens deleted, duplicated, swapped, truncated) and pushed through the whole compiler
// and the VM with small budgets. Nothing may crash, hang or throw; a refused program has an error
// diagnostic; a program that runs gives the same results with and without optimisation (within the
// language's 4-ulp bound for transcendentals).
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <random>
#include <sstream>

#include "runtime/support/big_stack.h"
#include "ir/verifier.h"
#include "tests/unit/helpers.h"

using namespace fscript;

namespace {

const char* kPieces[] = {"(",      ")",    "{",      "}",         "[",          "]",       ";",     ",",
                         "=",      "+=",   "^",      "-",         "!",          "?",       ":",     "++",
                         "var ",   "let ", "const ", "function ", "return ",    "if ",     "else ", "for ",
                         "while ", "do ",  "break",  "continue",  "new Array(", ".length", "x",     "a",
                         "f(",     "0",    "1e9",    "nan",       "\n",         "/*",      "*/",    "//",
                         "\"",     "#",    "Math.",  "pi",        "&&",         "||",      "|",     "&"};

std::string mutate(std::string s, std::mt19937& rng) {
  int edits = 1 + static_cast<int>(rng() % 4);
  for (int k = 0; k < edits && !s.empty(); ++k) {
    size_t at = rng() % s.size();
    switch (rng() % 5) {
      case 0: s.erase(at, 1 + rng() % 8); break;
      case 1: s.insert(at, kPieces[rng() % (sizeof kPieces / sizeof kPieces[0])]); break;
      case 2: s.insert(at, s.substr(rng() % s.size(), rng() % 16)); break;
      case 3: s.resize(at); break;
      default: s[at] = static_cast<char>(rng() % 128); break;
    }
  }
  return s;
}

struct Tally {
  int compiled = 0, refused = 0, ran = 0, compared = 0;
};

// The agreement the language definition promises: transcendentals within 4 ulp (constant folding
// calls the scalar definitions, the VM their batch twins, within 2 ulp of them), the sign of a zero
// not significant, NaN payloads not part of the semantics.
bool agree(float a, float b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b);
  if (a == b) return true;
  if (std::isinf(a) || std::isinf(b) || std::signbit(a) != std::signbit(b)) return false;
  int32_t x, y;
  std::memcpy(&x, &a, 4);
  std::memcpy(&y, &b, 4);
  return std::abs(static_cast<int64_t>(x) - y) <= 4;
}

void compile_and_run(const std::string& text, Tally& tally) {
  backends::Budgets small;
  small.max_loop_iterations = 2000;
  small.max_call_depth = 30;
  small.max_array_elements = 1000;
  std::vector<float> results[2];
  bool ran[2] = {false, false};
  for (bool optimize : {false, true}) {
    auto b = test::build(text, "", optimize, small);
    if (b->module) REQUIRE(ir::verify(*b->module) == "");
    if (!b->ok) {
      if (!optimize) ++tally.refused;
      // A refusal always says why: an error, or no entry point to call.
      if (!b->diag.has_errors()) REQUIRE(b->module == nullptr);
      continue;
    }
    if (!optimize) ++tally.compiled;
    std::vector<float>& out = results[optimize];
    for (float v : {0.5f, -1.25f, 3.0f}) {
      std::vector<float> in(b->kernel->num_inputs(), v), o(b->kernel->num_outputs());
      backends::RuntimeError err;
      if (!b->kernel->eval(in.data(), o.data(), err)) {
        REQUIRE(!err.message.empty());
        o.assign(o.size(), -777.0f);  // a runtime error, as a value the comparison sees
      }
      out.insert(out.end(), o.begin(), o.end());
    }
    ran[optimize] = true;
  }
  if (ran[0]) ++tally.ran;
  if (!ran[0] || !ran[1]) return;
  ++tally.compared;
  INFO(text);
  REQUIRE(results[0].size() == results[1].size());
  for (size_t i = 0; i < results[0].size(); ++i) {
    // Budgets count differently once calls are inlined: an error on one side only is allowed.
    if (results[0][i] == -777.0f || results[1][i] == -777.0f) continue;
    INFO("output " << i << ": " << results[0][i] << " unoptimised, " << results[1][i] << " optimised");
    CHECK(agree(results[0][i], results[1][i]));
  }
}

}  // namespace

TEST_CASE("fuzz: mutated programs never crash the compiler or the VM") {
  std::vector<std::string> seeds = {
      "function FRep(x,y,z,t){ var a = [1,2,3]; for (var i = 0; i < 3; i++) a[i] += x; return a[0] - a[2]; }",
      "function f(n){ return n < 2 ? n : f(n-1) + f(n-2); } function FRep(x,y,z){ return f(6) * x; }",
      "x=u; y=v; z=sin(w*pi);", "0.7^2-x^2-y^2-z^2"};
  for (const auto& e : std::filesystem::recursive_directory_iterator(FS_GOLDEN_DIR)) {
    if (e.path().extension() != ".fs" || std::filesystem::file_size(e.path()) > 20000) continue;
    std::ifstream in(e.path());
    std::stringstream ss;
    ss << in.rdbuf();
    seeds.push_back(ss.str());
  }
  // FSCRIPT_FUZZ_ROUNDS and FSCRIPT_FUZZ_SEED allow longer runs by hand.
  const char* rounds_env = std::getenv("FSCRIPT_FUZZ_ROUNDS");
  const char* seed_env = std::getenv("FSCRIPT_FUZZ_SEED");
  int rounds = rounds_env ? std::atoi(rounds_env) : 400;
  std::mt19937 rng(seed_env ? static_cast<unsigned>(std::atoi(seed_env)) : 2026u);
  Tally tally;
  support::run_with_big_stack([&] {
    for (int round = 0; round < rounds; ++round)
      for (const auto& seed : seeds) compile_and_run(mutate(seed, rng), tally);
  });
  // The mutants must reach both sides of the compiler: some refused, and enough accepted and run
  // to compare optimised with unoptimised code (a broken parser or a dead VM shows here).
  INFO(tally.compiled << " compiled, " << tally.refused << " refused, " << tally.compared << " compared");
  CHECK(tally.refused > rounds);
  CHECK(tally.compared > rounds);
}
