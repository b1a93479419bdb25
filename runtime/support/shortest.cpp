// Shortest round-trip decimal text (shortest.h): std::to_chars where the library has it, else the
// fewest of printf's correctly rounded digits that read back, laid out as to_chars lays them out.
#include "runtime/support/shortest.h"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace fscript::support {
namespace {

template <typename T>
T read_back(const char* text) {
  if constexpr (sizeof(T) == sizeof(float)) return std::strtof(text, nullptr);
  else return std::strtod(text, nullptr);
}

// A finite non-zero value: the fewest significant digits that read back (printf rounds correctly,
// so the nearest such text), then fixed or scientific, whichever is shorter.
template <typename T>
std::string finite(T v) {
  // More correctly rounded digits are nearer, so reading back holds from some precision on: the
  // least one by bisection (9 digits always do for a float, 17 for a double).
  char sci[48];
  int lo = 0, hi = sizeof(T) == sizeof(float) ? 8 : 16;
  while (lo < hi) {
    int mid = (lo + hi) / 2;
    std::snprintf(sci, sizeof sci, "%.*e", mid, static_cast<double>(v));
    if (read_back<T>(sci) == v) hi = mid;
    else lo = mid + 1;
  }
  std::snprintf(sci, sizeof sci, "%.*e", lo, static_cast<double>(v));
  const char* s = sci;
  std::string sign, digits;
  if (*s == '-') sign = "-", ++s;
  for (; *s && *s != 'e'; ++s)
    if (*s != '.') digits += *s;
  const int e = std::atoi(s + 1), n = static_cast<int>(digits.size());
  std::string scientific = sign + digits.substr(0, 1) + (n > 1 ? "." + digits.substr(1) : "") + (e < 0 ? "e-" : "e+") +
      (std::abs(e) < 10 ? "0" : "") + std::to_string(std::abs(e));
  std::string fixed = sign;
  if (e >= n - 1) {  // an integer: its exact digits (as long as the padded ones, and nearer)
    char exact[400];
    std::snprintf(exact, sizeof exact, "%.0f", std::fabs(static_cast<double>(v)));
    fixed += exact;
  } else if (e >= 0) {
    fixed += digits.substr(0, static_cast<size_t>(e + 1)) + "." + digits.substr(static_cast<size_t>(e + 1));
  } else {
    fixed += "0." + std::string(static_cast<size_t>(-e - 1), '0') + digits;
  }
  return fixed.size() <= scientific.size() ? fixed : scientific;
}

template <typename T>
char* by_printf(char* buf, size_t size, T v) {
  std::string out = std::isnan(v) ? (std::signbit(v) ? "-nan" : "nan")
      : std::isinf(v)             ? (v < 0 ? "-inf" : "inf")
      : v == 0                    ? (std::signbit(v) ? "-0" : "0")
                                  : finite(v);
  if (out.size() > size) return nullptr;
  std::memcpy(buf, out.data(), out.size());
  return buf + out.size();
}

template <typename T>
char* shortest(char* buf, size_t size, T v) {
#if defined(__cpp_lib_to_chars) && __cpp_lib_to_chars >= 201611L
  auto r = std::to_chars(buf, buf + size, v);
  return r.ec == std::errc() ? r.ptr : nullptr;
#else
  return by_printf(buf, size, v);
#endif
}

}  // namespace

char* shortest_text(char* buf, size_t size, double v) { return shortest(buf, size, v); }
char* shortest_text(char* buf, size_t size, float v) { return shortest(buf, size, v); }
char* shortest_text_by_printf(char* buf, size_t size, double v) { return by_printf(buf, size, v); }
char* shortest_text_by_printf(char* buf, size_t size, float v) { return by_printf(buf, size, v); }

}  // namespace fscript::support
