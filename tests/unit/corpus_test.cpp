// Every FScript text in every .wrl of the shared corpus compiles with no error and evaluates
// without a runtime error at a few points, on every backend with the VM's bits (the corpus lives in the shared folder: a skip when it is
// absent, a failure under CI).
#include <catch2/catch.hpp>
#include <filesystem>

#include "engine/driver/driver.h"
#include "frontend/fscript/embedded.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"
#include "tests/support/skip.h"
#include "tests/unit/backend_cases.h"
#include "tests/unit/helpers.h"
#include "runtime/support/files.h"

using namespace fscript;
namespace fsys = std::filesystem;

TEST_CASE("corpus: every script compiles and runs") {
  if (!fsys::exists(FS_CORPUS_DIR)) {
    test::skip(test::SkipKind::Missing, "the shared corpus folder is absent: " FS_CORPUS_DIR);
    return;
  }
  size_t scripts = 0;
  for (const auto& e : fsys::recursive_directory_iterator(FS_CORPUS_DIR)) {
    if (e.path().extension() != ".wrl") continue;
    std::string text, err;
    REQUIRE(support::read_file(e.path().string(), text, err));
    std::vector<std::string> lines = frontend::split_lines(text);
    frontend::DiagnosticSink vdiag;
    vrml::Scene scene;
    bool parsed = vrml::parse_scene(std::make_unique<frontend::SourceFile>(e.path().string(), text), vdiag, scene);
    INFO(frontend::render_all(vdiag));
    if (text.rfind("BSCRYPT", 0) == 0) {  // the one encrypted course file: refused clearly
      CHECK(!parsed);
      CHECK(frontend::render_all(vdiag).find("encrypted") != std::string::npos);
      continue;
    }
    CHECK(parsed);
    for (const auto& ss : vrml::scene_scripts(scene)) {
      const frontend::EmbeddedScript& s = ss.script;
      if (s.field == "operation") continue;  // set-operation keywords: the scene layer's business
      ++scripts;
      auto file = std::make_unique<frontend::SourceFile>(e.path().string(), s.text, s.line, s.col);
      file->set_outer_lines(lines);
      frontend::DiagnosticSink diag;
      frontend::Script script;
      INFO(e.path().string() << ":" << s.line);
      bool ok = frontend::load_script(std::move(file), diag, script);
      INFO(frontend::render_all(diag));
      REQUIRE(ok);
      frontend::KernelSpec spec;
      REQUIRE(frontend::default_spec(script.sema, spec, err));
      auto m = driver::build_module(script, spec, diag, {}, err);
      REQUIRE(m);
      // On every backend this build has, each giving the VM's bits (NaN for NaN) at each point.
      std::vector<float> reference;
      for (const std::string& name : backends::available_backends()) {
        INFO("backend " << name);
        auto kernel = backends::make_backend(name)->compile(*m, {}, err);
        REQUIRE(kernel);
        std::vector<float> results;
        for (float p : {0.0f, 0.25f, 0.5f, 1.0f}) {
          std::vector<float> in(kernel->num_inputs(), p), out(kernel->num_outputs());
          backends::RuntimeError rerr;
          bool ok = kernel->eval(in.data(), out.data(), rerr);
          INFO("at " << p << ": " << rerr.message);
          CHECK(ok);
          results.insert(results.end(), out.begin(), out.end());
        }
        if (reference.empty()) reference = results;
        REQUIRE(results.size() == reference.size());
        for (size_t i = 0; i < results.size(); ++i) CHECK(test::same(results[i], reference[i]));
      }
    }
  }
  CHECK(scripts > 50);
}
