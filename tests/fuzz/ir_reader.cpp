// Fuzz target: bytes as the IR's text form. The reader refuses with "line N: message" or returns a
// module; a module the verifier accepts prints back to text the reader reads to the same module.
#include <cstddef>
#include <cstdint>

#include "ir/text.h"
#include "ir/verifier.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fscript;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string text(reinterpret_cast<const char*>(data), size), error;
  auto m = ir::read(text, error);
  if (!m) {
    if (error.rfind("line ", 0) != 0) fuzz::finding("a refusal without a line: " + error, text);
    return 0;
  }
  if (!ir::verify(*m).empty()) return 0;
  std::string printed = ir::print(*m);
  auto back = ir::read(printed, error);
  if (!back) fuzz::finding("the printer wrote what the reader refuses: " + error + "\n" + printed, text);
  if (!ir::verify(*back).empty()) fuzz::finding("a verified module reads back unverifiable", text);
  if (ir::print(*back) != printed) fuzz::finding("the IR text does not round-trip:\n" + printed, text);
  return 0;
}
