// The language server's layers: framing on good and bad streams, UTF-16 positions and edits, and
// the server on a 5 MB document and on messages of every wrong shape (never an exception).
#include <catch2/catch.hpp>
#include <set>
#include <sstream>

#include "lsp/documents.h"
#include "lsp/server.h"
#include "lsp/transport.h"

using namespace fscript::lsp;

TEST_CASE("lsp transport: Content-Length framing, bad headers, truncation") {
  std::istringstream in(
      "Content-Length: 2\r\n\r\n{}Content-Type: x\r\nContent-Length: 3\r\n\r\n[1]"
      "Content-Length: x\r\n\r\nno length\r\n\r\nContent-Length: 10\r\n\r\nshort");
  std::string body, error;
  CHECK(read_message(in, body, error) == ReadStatus::Message);
  CHECK(body == "{}");
  CHECK(read_message(in, body, error) == ReadStatus::Message);
  CHECK(body == "[1]");
  CHECK(read_message(in, body, error) == ReadStatus::BadHeader);
  CHECK(error == "Content-Length is not a number");
  CHECK(read_message(in, body, error) == ReadStatus::BadHeader);  // "no length"
  CHECK(read_message(in, body, error) == ReadStatus::End);        // 10 bytes promised, 5 sent
  std::ostringstream out;
  write_message(out, "{\"a\":1}");
  CHECK(out.str() == "Content-Length: 7\r\n\r\n{\"a\":1}");
}

TEST_CASE("lsp documents: UTF-16 positions and edits") {
  std::string text =
      "a\xC3\xA9"
      "b\n\xF0\x9F\x98\x80x\n";  // "aéb", then an emoji (two UTF-16 units) and x
  CHECK(offset_of(text, {0, 2}) == 3);  // after "aé"
  CHECK(offset_of(text, {1, 2}) == 9);  // after the emoji
  CHECK(offset_of(text, {1, 99}) == 10);  // clamped to the line's end
  CHECK(offset_of(text, {9, 0}) == text.size());
  Position p = position_of(text, 10);
  CHECK(p.line == 1);
  CHECK(p.character == 3);
  Document d;
  d.text = text;
  Documents::edit(d, {1, 2}, {1, 3}, "yz");
  CHECK(d.text ==
        "a\xC3\xA9"
        "b\n\xF0\x9F\x98\x80yz\n");
}

TEST_CASE("lsp server: a 5 MB document, and messages of every wrong shape") {
  Server s;
  CHECK(s.handle_text("{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"initialize\",\"params\":{}}").size() == 1);
  std::string big;
  for (int i = 0; big.size() < (5u << 20); ++i)
    big += "function f" + std::to_string(i) + "(x) { return x * " + std::to_string(i) + "; }\n";
  json open = {{"jsonrpc", "2.0"},
               {"method", "textDocument/didOpen"},
               {"params", {{"textDocument", {{"uri", "file:///big.fs"}, {"version", 1}, {"text", big}}}}}};
  auto out = s.handle(open);
  REQUIRE(out.size() == 1);
  CHECK(out[0]["params"]["diagnostics"].empty());
  // Each wrong message gets the JSON-RPC answer it calls for: a parse error (-32700) for what is
  // not JSON, an invalid request (-32600) for what is not a request, invalid params (-32602) for a
  // request with wrong params, an unknown method (-32601); a bad notification gets no answer.
  struct Bad {
    const char* text;
    int code;  // 0: no answer at all
    json id;
  };
  const Bad bads[] = {
      {"", -32700, nullptr},
      {"{\"id\":3,", -32700, nullptr},
      {"null", -32600, nullptr},
      {"42", -32600, nullptr},
      {"\"x\"", -32600, nullptr},
      {"{}", -32600, nullptr},
      {"{\"method\":7}", -32600, nullptr},
      {"{\"id\":[1],\"method\":\"textDocument/hover\"}", -32600, nullptr},
      {"{\"id\":1,\"method\":\"textDocument/hover\"}", -32602, 1},
      {"{\"id\":\"h\",\"method\":\"textDocument/hover\",\"params\":{\"textDocument\":{\"uri\":5}}}", -32602, "h"},
      {"{\"id\":2,\"method\":\"textDocument/frobnicate\",\"params\":{}}", -32601, 2},
      {"{\"method\":\"textDocument/didChange\",\"params\":{\"textDocument\":{\"uri\":\"file:///big.fs\"},"
       "\"contentChanges\":[{\"range\":{\"start\":{\"line\":-1}}}]}}",
       0, nullptr},
      {"{\"method\":\"textDocument/didOpen\",\"params\":{\"textDocument\":{}}}", 0, nullptr},
      {"{\"method\":\"$/unknownNotification\"}", 0, nullptr}};
  for (const Bad& bad : bads) {
    INFO(bad.text);
    std::vector<json> replies;
    REQUIRE_NOTHROW(replies = s.handle_text(bad.text));
    if (bad.code == 0) {
      CHECK(replies.empty());
      continue;
    }
    REQUIRE(replies.size() == 1);
    CHECK(replies[0]["jsonrpc"] == "2.0");
    CHECK(replies[0]["id"] == bad.id);
    CHECK(replies[0]["error"]["code"] == bad.code);
    CHECK_FALSE(replies[0]["error"]["message"].get<std::string>().empty());
  }
  // The document survived the bad edits, and requests still work.
  auto hover = s.handle(
      {{"jsonrpc", "2.0"},
       {"id", 9},
       {"method", "textDocument/hover"},
       {"params", {{"textDocument", {{"uri", "file:///big.fs"}}}, {"position", {{"line", 0}, {"character", 10}}}}}});
  REQUIRE(hover.size() == 1);
  CHECK(hover[0]["id"] == 9);
  CHECK(hover[0]["result"]["contents"]["value"].get<std::string>().find("f0(x)") != std::string::npos);
  CHECK_FALSE(s.exited());
}

TEST_CASE("lsp fuzz: random and mutated byte streams through the transport and the server") {
  // Valid messages cut, spliced and bit-flipped, and plain noise: every byte stream must end in
  // End, with no exception and no hang; every request (an object with an id and a method) gets
  // exactly one answer with its id, and what is not JSON gets a parse error.
  std::vector<std::string> seeds = {
      "{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"initialize\",\"params\":{}}",
      "{\"jsonrpc\":\"2.0\",\"method\":\"textDocument/didOpen\",\"params\":{\"textDocument\":{\"uri\":\"file:///f.fs\","
      "\"version\":1,\"text\":\"function FRep(x,y,z,t){return x*x-1;}\"}}}",
      "{\"jsonrpc\":\"2.0\",\"id\":2,\"method\":\"textDocument/hover\",\"params\":{\"textDocument\":{\"uri\":\"file:///"
      "f.fs\"},"
      "\"position\":{\"line\":0,\"character\":30}}}",
      "{\"jsonrpc\":\"2.0\",\"method\":\"textDocument/didChange\",\"params\":{\"textDocument\":{\"uri\":\"file:///"
      "f.fs\","
      "\"version\":2},\"contentChanges\":[{\"range\":{\"start\":{\"line\":0,\"character\":5},\"end\":{\"line\":0,"
      "\"character\":9}},\"text\":\"(\"}]}}",
      "{\"jsonrpc\":\"2.0\",\"id\":3,\"method\":\"textDocument/"
      "completion\",\"params\":{\"textDocument\":{\"uri\":\"file:///f.fs\"},"
      "\"position\":{\"line\":0,\"character\":3}}}"};
  uint64_t rng = 0x9E3779B97F4A7C15ull;
  auto next = [&] {
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
  };
  int requests = 0;
  for (int round = 0; round < 400; ++round) {
    std::string stream;
    for (int m = 0; m < 6; ++m) {
      std::string body = seeds[next() % seeds.size()];
      int how = static_cast<int>(next() % 5);
      if (how == 1 && !body.empty()) body.resize(next() % body.size());                       // cut
      if (how == 2)
        for (int k = 0; k < 3; ++k) body[next() % body.size()] ^= static_cast<char>(1 << (next() % 8));  // flip
      if (how == 3) body = std::string(next() % 40, static_cast<char>(next() % 256));          // noise
      size_t claimed = how == 4 ? body.size() + next() % 20 : body.size();                      // a lying length
      stream += (next() % 7 ? "Content-Length: " + std::to_string(claimed) : std::string("Content-Lenght: 3")) +
          "\r\n\r\n" + body;
    }
    std::istringstream in(stream);
    Server s;
    std::string body, error;
    int guard = 0;
    for (;;) {
      ReadStatus st = read_message(in, body, error);
      if (st == ReadStatus::End) break;
      if (st == ReadStatus::Message) {
        std::vector<json> replies;
        REQUIRE_NOTHROW(replies = s.handle_text(body));
        json parsed = json::parse(body, nullptr, false);
        if (parsed.is_discarded()) {
          REQUIRE(replies.size() == 1);
          CHECK(replies[0]["error"]["code"] == -32700);
        } else if (parsed.is_object() && parsed.contains("method") && parsed["method"].is_string() &&
                   parsed.contains("id") && (parsed["id"].is_number_integer() || parsed["id"].is_string())) {
          INFO(body);
          int answers = 0;
          for (const json& r : replies)
            if (r.contains("id") && r["id"] == parsed["id"] && (r.contains("result") != r.contains("error"))) ++answers;
          CHECK(answers == 1);
          ++requests;
        }
      }
      REQUIRE(++guard < 100);
    }
  }
  CHECK(requests > 100);  // enough requests come through whole to be checked
}

// The labels the server offers for completion at (line, ch) of the open document `uri`.
static std::set<std::string> completion_labels(Server& s, const std::string& uri, uint32_t line, uint32_t ch) {
  json position = {{"line", line}, {"character", ch}};
  json params = {{"textDocument", {{"uri", uri}}}, {"position", position}};
  auto out = s.handle({{"jsonrpc", "2.0"}, {"id", 2}, {"method", "textDocument/completion"}, {"params", params}});
  std::set<std::string> labels;
  for (const auto& item : out.at(0)["result"]["items"]) labels.insert(item["label"].get<std::string>());
  return labels;
}

TEST_CASE("lsp completion: the locals in scope are those of the function the cursor is in") {
  Server s;
  s.handle_text("{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"initialize\",\"params\":{}}");
  std::string text =
      "function f(alpha) {\n  var beta = alpha;\n  return beta;\n}\nfunction g(gamma) {\n  return gamma;\n}\n";
  s.handle({{"jsonrpc", "2.0"},
            {"method", "textDocument/didOpen"},
            {"params", {{"textDocument", {{"uri", "file:///s.fs"}, {"version", 1}, {"text", text}}}}}});
  auto labels_at = [&](uint32_t line, uint32_t ch) { return completion_labels(s, "file:///s.fs", line, ch); };
  auto in_f = labels_at(2, 2), in_g = labels_at(5, 2);
  CHECK(in_f.count("alpha"));
  CHECK(in_f.count("beta"));
  CHECK_FALSE(in_f.count("gamma"));
  CHECK(in_g.count("gamma"));
  CHECK_FALSE(in_g.count("beta"));
  CHECK(in_g.count("f"));  // functions everywhere
}

TEST_CASE("lsp completion in a .wrl: the enclosing node's fields, whatever the space before its brace") {
  Server s;
  s.handle_text("{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"initialize\",\"params\":{}}");
  std::string text = "#VRML V2.0 utf8\nFShape   {\n  geo\n  geometry FGeometry\n\n   {\n    res\n  }\n}\n";
  s.handle({{"jsonrpc", "2.0"},
            {"method", "textDocument/didOpen"},
            {"params", {{"textDocument", {{"uri", "file:///w.wrl"}, {"version", 1}, {"text", text}}}}}});
  auto labels_at = [&](uint32_t line, uint32_t ch) { return completion_labels(s, "file:///w.wrl", line, ch); };
  CHECK(labels_at(2, 5) == std::set<std::string>{"geometry"});       // FShape's field, three spaces before '{'
  CHECK(labels_at(6, 7) == std::set<std::string>{"resolution"});     // FGeometry's, a blank line before '{'
}

// One request of `method` at (line, ch) of the open document `uri`.
static json request_at(Server& s, const std::string& method, const std::string& uri, uint32_t line, uint32_t ch) {
  json params = {{"textDocument", {{"uri", uri}}}, {"position", {{"line", line}, {"character", ch}}}};
  if (method == "textDocument/references") params["context"] = {{"includeDeclaration", true}};
  auto out = s.handle({{"jsonrpc", "2.0"}, {"id", 3}, {"method", method}, {"params", params}});
  return out.empty() ? json() : out.at(0)["result"];
}

TEST_CASE("lsp: hover, definition and references agree at every position, edges and case included") {
  Server s;
  s.handle_text("{\"jsonrpc\":\"2.0\",\"id\":1,\"method\":\"initialize\",\"params\":{}}");
  // `frep` (a variable) beside `FRep` (a function): names are exact; `sin` is a built-in.
  std::vector<std::string> lines = {"var frep = 2;",
                                    "function FRep(x, y, z) {",
                                    "  var k = frep * x;",
                                    "  return FRep2(k) + sin(y) - z;",
                                    "}",
                                    "function FRep2(a) { return a * frep; }"};
  std::string text;
  for (const auto& l : lines) text += l + "\n";
  s.handle({{"jsonrpc", "2.0"},
            {"method", "textDocument/didOpen"},
            {"params", {{"textDocument", {{"uri", "file:///a.fs"}, {"version", 1}, {"text", text}}}}}});
  int named = 0;
  for (uint32_t line = 0; line < lines.size(); ++line)
    for (uint32_t ch = 0; ch <= lines[line].size(); ++ch) {
      json hover = request_at(s, "textDocument/hover", "file:///a.fs", line, ch);
      json def = request_at(s, "textDocument/definition", "file:///a.fs", line, ch);
      json refs = request_at(s, "textDocument/references", "file:///a.fs", line, ch);
      INFO("line " << line << " char " << ch << ": hover " << hover.dump() << " definition " << def.dump()
                   << " references " << refs.dump());
      bool builtin = !hover.is_null() &&
          hover["contents"]["value"].get<std::string>().find("user function") == std::string::npos &&
          hover["contents"]["value"].get<std::string>().find("defined at") == std::string::npos;
      // A definition exactly where there are references; hover wherever either is.
      CHECK(def.is_null() == (refs.is_null() || refs.empty()));
      if (!def.is_null()) {
        ++named;
        CHECK_FALSE(hover.is_null());
        CHECK_FALSE(builtin);
        bool listed = false;  // the definition is one of the references
        for (const auto& r : refs) listed |= r["range"]["start"] == def["range"]["start"];
        CHECK(listed);
      }
      // A word's last byte and the position just after it are on the same name.
      if (ch > 0 && !hover.is_null() && ch == hover["range"]["end"]["character"].get<uint32_t>())
        CHECK(request_at(s, "textDocument/hover", "file:///a.fs", line, ch - 1) == hover);
    }
  CHECK(named > 30);
  // `frep` in line 2 is the variable of line 0, never the function FRep of line 1.
  json def = request_at(s, "textDocument/definition", "file:///a.fs", 2, 11);
  CHECK(def["range"]["start"] == json({{"line", 0}, {"character", 4}}));
  CHECK(request_at(s, "textDocument/hover", "file:///a.fs", 2, 11)["contents"]["value"].get<std::string>().find(
            "global variable") != std::string::npos);
  CHECK(request_at(s, "textDocument/references", "file:///a.fs", 1, 10).size() == 1);  // FRep: its declaration only
  CHECK(request_at(s, "textDocument/references", "file:///a.fs", 3, 10).size() == 2);  // FRep2: declaration and call
  CHECK(request_at(s, "textDocument/hover", "file:///a.fs", 3, 22)["contents"]["value"].get<std::string>().find(
            "sin(") != std::string::npos);
}
