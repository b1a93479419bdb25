// Fuzz target: bytes as a .wrl file (inflated first when they start with gzip's magic) through
// the VRML97 parser, PROTO/EXTERNPROTO expansion, the scene model (every script compiled) and the
// time model. Also: a scene the parser accepts is written and read back to the same graph.
// Inline files are not followed (the fuzzer would name files of this machine; the file size cap
// of the scene reader covers them, tested in tests/cli/limits_test.sh).
#include <cstddef>
#include <cstdint>
#include <memory>

#include "frontend/vrml/scene_file.h"
#include "frontend/vrml/vrml_parser.h"
#include "frontend/vrml/writer.h"
#include "engine/scene/scene_model.h"
#include "runtime/support/big_stack.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fscript;

namespace {

void model(const vrml::Scene& scene, std::optional<double> fraction, double now) {
  scene::ModelOptions mo;
  mo.compile.backend = "vm";
  mo.compile.budgets = fuzz::small_budgets();
  mo.fraction = fraction;
  mo.now = now;
  frontend::DiagnosticSink diag;
  scene::SceneModel m;
  scene::build_scene_model(scene, mo, diag, m);
  frontend::render_all(diag);
}

void one_input(const std::string& bytes) {
  std::string text = bytes, error;
  if (bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
      static_cast<unsigned char>(bytes[1]) == 0x8b) {
    if (!vrml::gunzip(bytes, text, error)) {
      if (error.empty()) fuzz::finding("gunzip refused without a reason", bytes);
      return;
    }
  }
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  bool ok = vrml::parse_scene(std::make_unique<frontend::SourceFile>("fuzz.wrl", text), diag, scene);
  frontend::render_all(diag);
  if (!ok) {
    if (!diag.has_errors()) fuzz::finding("the scene was refused without an error", text);
    return;
  }
  std::string written = vrml::write_scene(scene);
  frontend::DiagnosticSink diag2;
  vrml::Scene again;
  if (!vrml::parse_scene(std::make_unique<frontend::SourceFile>("written.wrl", written), diag2, again))
    fuzz::finding("the writer wrote what the parser refuses:\n" + frontend::render_all(diag2) + written, text);
  std::string diff = vrml::compare_scenes(scene, again);
  if (!diff.empty()) fuzz::finding("write then read changes the scene: " + diff + "\n" + written, text);
  model(scene, std::nullopt, 0);
  model(scene, 0.5, 2.5);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  fuzz::run_deep([&] { one_input(bytes); });
  return 0;
}
