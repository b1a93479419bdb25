// The node oracle's inputs (oracle_points.h).
#include "tests/oracle/oracle_points.h"

#include <cmath>
#include <cstring>

#include "ir/ir.h"

namespace fscript::oracle {
namespace {

const float kInf = INFINITY, kNan = NAN;
// Zeros of both signs, infinities, NaN, ties at .5 (round), the float just below .5, the largest
// and smallest floats (denormals too), 2^24 (where +1 is lost), and ordinary values.
const float kSpecial[] = {
    0.0f,        -0.0f,           1.0f,           -1.0f,           0.5f,        -0.5f,   1.5f,  -1.5f, 2.5f,   -2.5f,
    0.49999997f, -0.49999997f,    8388607.5f,     -8388607.5f,     16777216.0f, kInf,    -kInf, kNan,  1e-45f, -1e-45f,
    1e-40f,      1.17549435e-38f, 3.40282347e38f, -3.40282347e38f, 1e30f,       -1e-30f, 0.1f,  3.0f,  -7.25f, 100.0f};

float any_bits(std::mt19937_64& rng) {
  uint32_t u = static_cast<uint32_t>(rng());
  float f;
  std::memcpy(&f, &u, 4);
  return f;
}

float coordinate(std::mt19937_64& rng) {
  switch (rng() % 4) {
    case 0:
    case 1: return kSpecial[rng() % std::size(kSpecial)];
    case 2: return static_cast<float>(static_cast<int>(rng() % 81) - 40) * 0.25f;  // ties and small integers
    default: return any_bits(rng);
  }
}

// Mostly where the functions are interesting: around the unit interval, a few periods, the
// exponent range of exp and pow; sometimes any float at all.
float argument(std::mt19937_64& rng) {
  std::uniform_real_distribution<float> unit(-1.1f, 1.1f), periods(-20.0f, 20.0f), wide(-100.0f, 100.0f);
  switch (rng() % 5) {
    case 0: return unit(rng);
    case 1: return periods(rng);
    case 2: return wide(rng);
    case 3: return std::ldexp(1.0f + unit(rng) / 4, static_cast<int>(rng() % 60) - 30);
    default: return any_bits(rng);
  }
}

}  // namespace

std::vector<float> program_points(std::mt19937_64& rng, int n) {
  std::vector<float> p(4 * static_cast<size_t>(n));
  for (float& v : p) v = coordinate(rng);
  return p;
}

std::vector<BuiltinCheck> builtin_checks() {
  std::vector<BuiltinCheck> out;
#define FS_BUILTIN(N, A, OP, SIG, DOC)                                                   \
  if (ir::has_flag(ir::Op::OP, ir::CallsRuntime) && std::string(N) != "noise") {         \
    std::string args = (A) == 1 ? "x" : "x, y";                                          \
    std::string n = N;                                                                   \
    bool single = n == "sin" || n == "cos" || n == "exp" || n == "log";                  \
    out.push_back({n, "function FRep(x, y, z, t) { return " + n + "(" + args + "); }\n", \
                   "return __f(Math." + n + "(" + args + "));\n", (A), single ? 3 : 1}); \
  }
#include "frontend/fscript/builtins.def"
  return out;
}

std::vector<float> builtin_points(std::mt19937_64& rng, int arity) {
  std::vector<float> p;
  auto add = [&](float x, float y) { p.insert(p.end(), {x, y, 0.0f, 0.0f}); };
  for (float x : kSpecial)
    for (float y : kSpecial) {
      add(x, y);
      if (arity == 1) break;
    }
  for (int i = 0; i < 4000; ++i) add(argument(rng), argument(rng));
  return p;
}

}  // namespace fscript::oracle
