// The Catch2 main shared by every test executable. A run asked for an instruction-set variant
// (FSCRIPT_ISA) that this CPU lacks is skipped out loud (exit 77), never run on a narrower variant.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>
#include <cstdlib>
#include <string>

#include "runtime/math/isa.h"
#include "tests/support/skip.h"

int main(int argc, char* argv[]) {
  if (const char* want = std::getenv("FSCRIPT_ISA")) {
    std::string got = fscript::math::isa_name(fscript::math::active_isa());
    if (got != want) {
      std::string why = std::string("this CPU cannot run the ") + want + " variant (it runs " + got + ")";
      std::printf("SKIP: %s\n", why.c_str());
      fscript::test::log_skip(std::string("skipped ") + argv[0] + " with FSCRIPT_ISA=" + want + ": " + why);
      return 77;
    }
  }
  return Catch::Session().run(argc, argv);
}
