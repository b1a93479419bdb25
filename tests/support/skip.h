#pragma once
// Skips that cannot hide, for the Catch2 tests (as tests/support/skip.sh for the shell tests): a skip
// prints a warning and is appended to $FS_SKIP_LOG; one because something is missing fails under CI.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace fscript::test {

enum class SkipKind { Missing, Machine };

inline bool ci_mode() {
  const char* ci = std::getenv("CI");
  if (!ci) return false;
  for (const char* no : {"", "0", "false", "no"})
    if (std::strcmp(ci, no) == 0) return false;
  return true;
}

inline void log_skip(const std::string& line) {
  if (const char* log = std::getenv("FS_SKIP_LOG"))
    if (std::FILE* f = std::fopen(log, "a")) {
      std::fprintf(f, "%s\n", line.c_str());
      std::fclose(f);
    }
}

// Call, then return from the test case: fails it under CI when `kind` is Missing.
inline void skip(SkipKind kind, const std::string& what) {
  if (kind == SkipKind::Missing && ci_mode()) {
    log_skip("FAILED (not skipped under CI) " + Catch::getResultCapture().getCurrentTestName() + ": " + what);
    FAIL(what << " (CI is set: a check may not be skipped because something is missing)");
  }
  log_skip("skipped " + Catch::getResultCapture().getCurrentTestName() + ": " + what);
  WARN("SKIP: " << what);
}

}  // namespace fscript::test
