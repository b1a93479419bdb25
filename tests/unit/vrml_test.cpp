// The VRML97 reader: field syntax, defaults, DEF/USE, PROTO/EXTERNPROTO/IS, ROUTE checks, the
// FVRML nodes, and every kind of bad input (one run, exact positions, never a crash).
#include <catch2/catch.hpp>

#include "runtime/support/big_stack.h"
#include "frontend/vrml/scene_scripts.h"
#include "frontend/vrml/vrml_parser.h"

using namespace fscript;

namespace {

struct Parsed {
  frontend::DiagnosticSink diag;
  vrml::Scene scene;
  bool ok = false;
  std::string text() const { return frontend::render_all(diag); }
};

std::unique_ptr<Parsed> parse(const std::string& body, bool with_header = true) {
  auto p = std::make_unique<Parsed>();
  std::string text = (with_header ? "#VRML V2.0 utf8\n" : "") + body;
  support::run_with_big_stack(
      [&] { p->ok = vrml::parse_scene(std::make_unique<frontend::SourceFile>("t.wrl", text), p->diag, p->scene); });
  return p;
}

}  // namespace

TEST_CASE("vrml: every field type with its syntax") {
  auto p = parse(R"(
    DEF T Transform { translation 1 2 3 rotation 0 1 0 1.57 scale 2,2,2
      children [
        Shape { geometry IndexedFaceSet { coordIndex [0 1 2 -1, 0x2 1 0 -1] solid FALSE creaseAngle .5
                                         coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } }
                appearance Appearance { material Material { diffuseColor 1 0 0 } } }
        Shape { geometry Text { string ["a \"quoted\"
two lines" "b"] } }
      ] }
    PixelTexture { image 2 1 3 0xFF0000 0x00FF00 }
    Switch { whichChoice -1 choice USE T }
    WorldInfo { info "single value for an MF field" }
    TimeSensor { cycleInterval 2.5e0 loop TRUE }
  )");
  INFO(p->text());
  REQUIRE(p->ok);
  REQUIRE(p->scene.roots.size() == 5);
  const vrml::Node& t = *p->scene.roots[0];
  CHECK(t.get("translation")->nums == std::vector<double>{1, 2, 3});
  CHECK(t.get("center")->nums == std::vector<double>{0, 0, 0});  // default
  CHECK(t.get("children")->nodes.size() == 2);
  const vrml::Node& ifs = *t.get("children")->nodes[0]->get("geometry")->nodes[0];
  CHECK(ifs.get("coordIndex")->nums.size() == 8);
  CHECK(ifs.get("coordIndex")->nums[4] == 2);
  const vrml::Node& text = *t.get("children")->nodes[1]->get("geometry")->nodes[0];
  CHECK(text.get("string")->strs[0] == "a \"quoted\"\ntwo lines");
  CHECK(p->scene.roots[1]->get("image")->nums.size() == 5);
  CHECK(p->scene.roots[2]->get("choice")->nodes[0].get() == &t);  // USE shares the node
  CHECK(p->scene.roots[3]->get("info")->strs.size() == 1);
}

TEST_CASE("vrml: the FVRML nodes are built in, with the plug-in's defaults") {
  auto p = parse(R"(FShape { geometry FGeometry { definition "0.7^2-x^2-y^2-z^2" } })");
  INFO(p->text());
  REQUIRE(p->ok);
  const vrml::Node& shape = *p->scene.roots[0];
  CHECK(shape.fvrml);
  CHECK(shape.get("cycleInterval")->nums[0] == 1);
  const vrml::Node& geo = *shape.get("geometry")->nodes[0];
  CHECK(geo.get("resolution")->nums == std::vector<double>{50, 50, 50});
  CHECK(geo.get("bboxSize")->nums == std::vector<double>{10, 10, 10});
  auto scripts = vrml::scene_scripts(p->scene);
  REQUIRE(scripts.size() == 1);
  CHECK(scripts[0].script.line == 2);
  CHECK(scripts[0].script.col == 43);
}

TEST_CASE("vrml: a file's own declaration of an FVRML node fixes its field types") {
  auto p = parse(
      R"(EXTERNPROTO FTransform [ exposedField SFVec3f translation exposedField MFNode children ] "x.wrl#FTransform"
    FTransform { translation 1 2 3 children [] })");
  INFO(p->text());
  REQUIRE(p->ok);
  CHECK(p->scene.roots[0]->fvrml);
  CHECK(p->scene.roots[0]->get("translation")->type == vrml::FieldType::SFVec3f);
}

TEST_CASE("vrml: PROTO with IS, and ROUTE checks") {
  auto p = parse(R"(
    PROTO Ball [ field SFFloat r 1 exposedField SFColor c 1 0 0 ] {
      Shape { geometry Sphere { radius IS r } appearance Appearance { material Material { diffuseColor IS c } } }
    }
    DEF B Ball { r 2 }
    DEF TS TimeSensor { loop TRUE }
    DEF PI PositionInterpolator { key [0 1] keyValue [0 0 0, 1 1 1] }
    DEF T Transform { }
    ROUTE TS.fraction_changed TO PI.set_fraction
    ROUTE PI.value_changed TO T.set_translation
    ROUTE TS.cycleTime TO TS.startTime
  )");
  INFO(p->text());
  REQUIRE(p->ok);
  CHECK(p->scene.roots[0]->proto != nullptr);
  CHECK(p->scene.routes.size() == 3);
}

TEST_CASE("vrml: errors name the field and the expected type, all in one run") {
  auto p = parse("Transform { translation 1 2 }\nTransform { bogus 3 }\nNoSuchNode { }\nSphere { radius TRUE }\n");
  CHECK(!p->ok);
  std::string t = p->text();
  INFO(t);
  CHECK(t.find("t.wrl:2:29: error: expected 3 numbers (SFVec3f) for a field of 'Transform', found '}'") !=
        std::string::npos);
  CHECK(t.find("t.wrl:3:13: error: 'Transform' has no field 'bogus'") != std::string::npos);
  CHECK(t.find("t.wrl:4:1: error: unknown node type 'NoSuchNode'") != std::string::npos);
  CHECK(t.find("t.wrl:5:17: error: expected a number (SFFloat)") != std::string::npos);
  CHECK(p->diag.error_count() == 4);
}

// The fuzzer's finding: a Script field declared twice (one name, two types) was kept twice, so the
// writer wrote an IS the parser refuses on reading it back.
TEST_CASE("vrml: a Script's fields are declared once each, and not over its own") {
  auto p = parse(
      "PROTO P [ field SFInt32 frames 0 field SFString center \"\" ] {\n"
      "  Script { field SFString frames IS center\n    field SFInt32 frames IS frames }\n}\n"
      "Script { eventIn SFFloat go field SFTime go 0 }\n"
      "Script { field MFString url [] }\n"
      "Script { field SFInt32 n 1 eventOut SFInt32 m }\n");
  CHECK(!p->ok);
  std::string t = p->text();
  INFO(t);
  CHECK(t.find("t.wrl:4:5: error: 'frames' is declared twice in 'Script'") != std::string::npos);
  CHECK(t.find("t.wrl:6:29: error: 'go' is declared twice in 'Script'") != std::string::npos);
  CHECK(t.find("t.wrl:7:10: error: 'url' is a field of every Script: declare another name") != std::string::npos);
  CHECK(p->diag.error_count() == 3);
}

TEST_CASE("vrml: bad routes") {
  auto p = parse(R"(DEF A TimeSensor { } DEF B Transform { }
    ROUTE A.fraction_changed TO B.set_translation
    ROUTE A.nothing TO B.set_translation
    ROUTE C.time TO B.set_translation
  )");
  std::string t = p->text();
  INFO(t);
  CHECK(t.find("ROUTE connects SFFloat 'fraction_changed' to SFVec3f 'set_translation'") != std::string::npos);
  CHECK(t.find("has no eventOut 'nothing'") != std::string::npos);
  CHECK(t.find("ROUTE from 'C', which no DEF names") != std::string::npos);
}

TEST_CASE("vrml: hostile input never crashes") {
  CHECK(!parse("Group { children [ Shape { } ", true)->ok);                      // truncated
  CHECK(!parse("Group { children [ Shape { } ] ] }")->ok);                        // unbalanced
  CHECK(!parse("Shape {", false)->ok);                                            // no header
  auto deep = parse(std::string(100000, 'x').replace(0, 100000, "") + [] {
    std::string s;
    for (int i = 0; i < 100000; ++i) s += "Group { children [ ";
    return s;
  }());
  CHECK(!deep->ok);
  CHECK(deep->text().find("nested deeper than") != std::string::npos);
  auto self = parse("PROTO P [ ] { P { } }\nP { }");
  CHECK(!self->ok);
  CHECK(self->text().find("unknown node type 'P'") != std::string::npos);
  auto cyc = parse("DEF A Group { children [ USE A ] }");
  CHECK(!cyc->ok);
  CHECK(cyc->text().find("USE of 'A', which no DEF before it names") != std::string::npos);
  auto huge = parse("Sphere { radius 1e999999 } Transform { translation 1e400 -1e400 0 }");
  CHECK(huge->ok);  // out-of-range numbers read as infinities, as strtod does
  auto utf = parse("WorldInfo { title \"bad \xff\xfe here\" }");
  CHECK(!utf->ok);
  CHECK(utf->text().find("invalid UTF-8") != std::string::npos);
  auto enc = parse("BSCRYPT0@\x01\x02", false);
  CHECK(enc->text().find("encrypted") != std::string::npos);
}

#include <filesystem>

#include "frontend/vrml/writer.h"
#include "tests/support/skip.h"
#include "runtime/support/files.h"

TEST_CASE("vrml: write -> read gives the same graph, on a rich file and on every corpus file") {
  std::vector<std::pair<std::string, std::string>> files = {{"inline", R"(#VRML V2.0 utf8
PROTO Ball [ field SFFloat r 1 exposedField MFColor c [1 0 0, 0 1 0] eventIn SFBool go ] {
  DEF S Script { field SFFloat k IS r eventIn SFBool go IS go url "javascript:" }
  Shape { geometry Sphere { radius IS r } }
}
EXTERNPROTO Far [ field SFFloat r ] ["far.wrl#Far", "http://x/far.wrl"]
DEF T Transform { translation 1 2 3.25 children [ DEF B Ball { r 2 } USE B Shape { geometry Text { string ["a\"b", "c\\d"] } } ] }
PixelTexture { image 2 1 3 0xFF0000 0x00FF00 }
DEF TS TimeSensor { cycleInterval 0.1 startTime 1e9 }
ROUTE TS.cycleTime TO TS.set_startTime
)"}};
  std::string corpus = FS_CORPUS_DIR;
  if (!std::filesystem::exists(corpus))
    test::skip(test::SkipKind::Missing, "the shared corpus folder is absent: " + corpus);
  else
    for (const auto& e : std::filesystem::recursive_directory_iterator(corpus)) {
      if (e.path().extension() != ".wrl") continue;
      std::string text, err;
      REQUIRE(support::read_file(e.path().string(), text, err));
      if (text.rfind("BSCRYPT", 0) == 0) continue;
      files.push_back({e.path().string(), text});
    }
  for (const auto& [name, text] : files) {
    INFO(name);
    frontend::DiagnosticSink d1, d2;
    vrml::Scene a, b;
    REQUIRE(vrml::parse_scene(std::make_unique<frontend::SourceFile>(name, text), d1, a));
    std::string written = vrml::write_scene(a);
    INFO(frontend::render_all(d2) << written);
    REQUIRE(vrml::parse_scene(std::make_unique<frontend::SourceFile>("written.wrl", written), d2, b));
    CHECK(vrml::compare_scenes(a, b) == "");
    CHECK(vrml::write_scene(b) == written);
  }
}

TEST_CASE("vrml: exposedField events by their set_ and _changed names, and field value rules") {
  auto ok = parse(R"(DEF A Transform { } DEF B Transform { } DEF C Transform { }
    ROUTE A.translation_changed TO B.set_translation
    ROUTE A.translation TO C.translation
    ROUTE B.rotation_changed TO C.set_rotation
    PixelTexture { image 1 1 4 0xFF0000FF }
    PixelTexture { image 0 0 0 }
    DEF S Switch { whichChoice -1 }
  )");
  INFO(ok->text());
  CHECK(ok->ok);
  CHECK(ok->scene.routes.size() == 3);
  auto bad = parse(R"(DEF A Transform { } DEF B Transform { }
    ROUTE A.translation_change TO B.set_translation
    ROUTE A.translation_changed TO B.sett_translation
    PixelTexture { image 1 1 5 0 }
    Switch { whichChoice 1.5 }
    Switch { whichChoice 20011100000000000000000000000000000000000000000000000000000000000000000000 }
    IndexedFaceSet { coordIndex [ 0 1 2 -2147483649 ] }
    PixelTexture { image 1 2 4 0xFF0000FF 4294967295 }
  )");
  std::string t = bad->text();
  INFO(t);
  CHECK(t.find("has no eventOut 'translation_change'") != std::string::npos);
  CHECK(t.find("has no eventIn 'sett_translation'") != std::string::npos);
  CHECK(t.find("t.wrl:5:32: error: expected a valid image size (SFImage)") != std::string::npos);  // 5 components
  CHECK(t.find("t.wrl:6:26: error: expected an integer from -2147483648 to 2147483647 (SFInt32)") != std::string::npos);
  // Found by the vrml_reader fuzzer: an integer past 32 bits reached a cast to long long (UB) in the
  // writer. Every integer field now fits 32 bits (an image's pixels: unsigned, 0xRRGGBBAA).
  CHECK(t.find("t.wrl:7:26: error: expected an integer from -2147483648 to 2147483647 (SFInt32)") != std::string::npos);
  CHECK(t.find("t.wrl:8:41: error: expected an integer from -2147483648 to 2147483647 (SFInt32)") != std::string::npos);
  CHECK(bad->diag.error_count() == 6);
}

TEST_CASE("vrml: every FVRML node and field is documented in the node table") {
  int nodes = 0;
  for (const std::string& type : vrml::standard_node_types()) {
    if (!vrml::is_fvrml_node(type)) continue;
    ++nodes;
    const vrml::Interface* iface = vrml::standard_interface(type);
    REQUIRE(iface);
    INFO(type);
    CHECK(iface->doc.size() > 20);
    for (const auto& f : iface->fields) {
      INFO(f.name);
      CHECK(f.doc.size() > 10);
    }
  }
  CHECK(nodes == 6);
  // Each "##" block goes to the declaration right after it, and only to it.
  const vrml::Interface* g = vrml::standard_interface("FGeometry");
  CHECK(g->find("definition")->doc.rfind("FScript: an expression in x, y, z, t", 0) == 0);
  CHECK(g->find("resolution")->doc.rfind("Implicit: grid cells per axis", 0) == 0);
  CHECK(vrml::standard_interface("FShape")->find("frames")->doc.rfind("N > 0: N frames per cycle", 0) == 0);
  CHECK(vrml::standard_interface("Transform")->doc == "");
}

TEST_CASE("vrml: declarations print as the standard writes them") {
  auto decl = [](const char* node, const char* field) {
    return vrml::declaration_text(*vrml::standard_interface(node)->find(field));
  };
  CHECK(decl("FGeometry", "bboxSize") == "exposedField SFVec3f bboxSize 10 10 10");
  CHECK(decl("FGeometry", "resolution") == "exposedField MFInt32 resolution [50 50 50]");
  CHECK(decl("FGeometry", "definition") == "exposedField SFString definition \"\"");
  CHECK(decl("FShape", "loop") == "exposedField SFBool loop FALSE");
  CHECK(decl("FShape", "geometry") == "exposedField SFNode geometry NULL");
  CHECK(decl("FShape", "set_fraction") == "eventIn SFFloat set_fraction");
  CHECK(decl("FTransform", "children") == "exposedField MFNode children []");
  CHECK(decl("FMaterial", "bboxSize") == "exposedField SFVec3f bboxSize -1 -1 -1");
  CHECK(decl("Viewpoint", "fieldOfView") == "exposedField SFFloat fieldOfView 0.785398");
}

#include <bit>
#include <charconv>
#include <random>

#include "runtime/support/shortest.h"

// The browser build writes numbers the printf way (its libc++ has no floating to_chars): the same
// text as std::to_chars, so its VRML97 and glTF files are the native build's bytes.
TEST_CASE("vrml: numbers' shortest text the printf way is std::to_chars's, for doubles and floats") {
  std::mt19937_64 rng(2003);
  auto same = [](auto v) {
    char a[400], b[400];
    auto r = std::to_chars(a, a + sizeof a, v);
    char* e = support::shortest_text_by_printf(b, sizeof b, v);
    REQUIRE(e);
    return std::string(a, r.ptr) == std::string(b, e);
  };
  int bad = 0;
  for (int i = 0; i < 200000; ++i) {
    uint64_t bits = rng();
    double d = i % 3 == 0 ? std::bit_cast<double>(bits)
        : i % 3 == 1      ? std::ldexp(static_cast<double>(bits >> 11), static_cast<int>(rng() % 80) - 113)
                          : static_cast<double>(static_cast<int>(bits % 100000)) / 1000.0;
    float f = i % 2 ? std::bit_cast<float>(static_cast<uint32_t>(bits)) : static_cast<float>(d);
    bad += !same(d) + !same(f);
  }
  CHECK(bad == 0);
  for (double d : {0.0, -0.0, 1e20, 1e21, 1e-4, 1e-5, 0.1, 123456789012345680000.0, 5e-324, 1.7976931348623157e308})
    CHECK(same(d));
  for (float f : {0.0f, -0.0f, 1e-45f, 3.4028235e38f, 0.3f, 16777216.0f, 1e10f}) CHECK(same(f));
}
