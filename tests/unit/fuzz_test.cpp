// A mutation fuzzer in the test suite: every golden case and a few seeds are mutated at random
// (bytes and tokens deleted, duplicated, swapped, truncated) and pushed through the whole compiler
// and the VM with small budgets. Nothing may crash, hang or throw; diagnostics are fine.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <random>
#include <sstream>

#include "frontend/big_stack.h"
#include "ir/verifier.h"
#include "tests/unit/helpers.h"

using namespace fscript;

namespace {

const char* kPieces[] = {"(", ")", "{", "}", "[", "]", ";", ",", "=", "+=", "^", "-", "!", "?", ":", "++", "var ",
                         "let ", "const ", "function ", "return ", "if ", "else ", "for ", "while ", "do ", "break",
                         "continue", "new Array(", ".length", "x", "a", "f(", "0", "1e9", "nan", "\n", "/*", "*/",
                         "//", "\"", "#", "Math.", "pi", "&&", "||", "|", "&"};

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

void compile_and_run(const std::string& text) {
  backend::Budgets small;
  small.max_loop_iterations = 2000;
  small.max_call_depth = 30;
  small.max_array_elements = 1000;
  for (bool optimize : {false, true}) {
    auto b = test::build(text, "", optimize, small);
    if (b->module) REQUIRE(ir::verify(*b->module) == "");
    if (!b->ok) continue;
    std::vector<float> in(b->kernel->num_inputs(), 0.5f), out(b->kernel->num_outputs());
    backend::RuntimeError err;
    b->kernel->eval(in.data(), out.data(), err);
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
  int runs = 0;
  frontend::run_with_big_stack([&] {
    for (int round = 0; round < rounds; ++round)
      for (const auto& seed : seeds) {
        compile_and_run(mutate(seed, rng));
        ++runs;
      }
  });
  CHECK(runs > 500);
}
