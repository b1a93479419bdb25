// Fuzz target: one in-process language server session driven by the bytes: documents opened,
// edited by ranges (in and out of bounds) and closed, every request the server handles at any
// position, raw message texts, and raw byte streams through the Content-Length framing.
// Responses must be JSON-RPC 2.0 with the request's id; nothing may crash or throw.
#include <cstddef>
#include <cstdint>
#include <sstream>

#include <fuzzer/FuzzedDataProvider.h>

#include "lsp/server.h"
#include "lsp/transport.h"
#include "runtime/support/big_stack.h"
#include "tests/fuzz/fuzz_support.h"

using namespace fscript;
using lsp::json;

namespace {

const char* const kUris[] = {"file:///fuzz/a.fs", "file:///fuzz/b.wrl", "file:///fuzz/c.fs"};
const char* const kRequests[] = {"textDocument/hover",
                                 "textDocument/completion",
                                 "textDocument/definition",
                                 "textDocument/documentSymbol",
                                 "textDocument/formatting",
                                 "textDocument/references",
                                 "textDocument/rename",
                                 "textDocument/signatureHelp",
                                 "textDocument/foldingRange",
                                 "textDocument/codeAction",
                                 "textDocument/semanticTokens/full",
                                 "shutdown",
                                 "no/such/method"};

struct Session {
  lsp::Server server;
  std::string transcript;  // what was sent, for the report
  int next_id = 1;

  void send(const json& message) {
    transcript += message.dump() + "\n";
    check(server.handle(message), message);
  }
  void send_text(const std::string& text) {
    // fscript.preview starts fvrml-run children: not something to do a million times.
    if (text.find("executeCommand") != std::string::npos) return;
    transcript += text + "\n";
    check(server.handle_text(text), json());
  }
  void check(const std::vector<json>& replies, const json& sent) {
    for (const json& r : replies) {
      if (!r.is_object() || r.value("jsonrpc", "") != "2.0") fuzz::finding("not JSON-RPC 2.0: " + r.dump(), transcript);
      if (r.contains("id") && !r.contains("result") && !r.contains("error"))
        fuzz::finding("a response without result or error: " + r.dump(), transcript);
    }
    if (sent.is_object() && sent.contains("id")) {
      bool answered = false;
      for (const json& r : replies) answered |= r.contains("id") && r["id"] == sent["id"];
      if (!answered) fuzz::finding("a request without a response", transcript);
    }
  }
};

// Text as a client sends it: JSON strings are UTF-8 (the wire parser refuses anything else), so the
// fuzzer's bytes are made valid UTF-8, multi-byte characters kept: '?' for each invalid byte.
std::string utf8(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size();) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    size_t len = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
    bool ok = len > 0 && i + len <= s.size() && !(c == 0xC0 || c == 0xC1 || c > 0xF4);
    for (size_t k = 1; ok && k < len; ++k) ok = (static_cast<unsigned char>(s[i + k]) >> 6) == 2;
    if (ok && len == 3) {  // no overlong forms, no surrogates
      unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xE0 && d < 0xA0) && !(c == 0xED && d >= 0xA0);
    }
    if (ok && len == 4) {
      unsigned char d = static_cast<unsigned char>(s[i + 1]);
      ok = !(c == 0xF0 && d < 0x90) && !(c == 0xF4 && d >= 0x90);
    }
    if (!ok) {
      out += '?';
      ++i;
      continue;
    }
    out.append(s, i, len);
    i += len;
  }
  return out;
}

json position(FuzzedDataProvider& in) {
  return {{"line", in.ConsumeIntegralInRange<uint32_t>(0, 40)},
          {"character", in.ConsumeIntegralInRange<uint32_t>(0, 90)}};
}

void step(Session& s, FuzzedDataProvider& in) {
  std::string uri = kUris[in.ConsumeIntegralInRange<size_t>(0, std::size(kUris) - 1)];
  json doc = {{"uri", uri}};
  switch (in.ConsumeIntegralInRange(0, 6)) {
    case 0:
      s.send({{"jsonrpc", "2.0"},
              {"method", "textDocument/didOpen"},
              {"params",
               {{"textDocument",
                 {{"uri", uri},
                  {"languageId", uri.back() == 'l' ? "vrml" : "fscript"},
                  {"version", 1},
                  {"text", utf8(in.ConsumeRandomLengthString(4000))}}}}}});
      return;
    case 1:
    case 2: {
      json change = {{"text", utf8(in.ConsumeRandomLengthString(200))}};
      if (in.ConsumeIntegralInRange(0, 7) != 0) change["range"] = {{"start", position(in)}, {"end", position(in)}};
      s.send(
          {{"jsonrpc", "2.0"},
           {"method", "textDocument/didChange"},
           {"params", {{"textDocument", {{"uri", uri}, {"version", 2}}}, {"contentChanges", json::array({change})}}}});
      return;
    }
    case 3:
    case 4: {
      json params = {{"textDocument", doc},
                     {"position", position(in)},
                     {"newName", "q"},
                     {"context", {{"includeDeclaration", in.ConsumeBool()}}},
                     {"range", {{"start", position(in)}, {"end", position(in)}}}};
      s.send({{"jsonrpc", "2.0"},
              {"id", s.next_id++},
              {"method", kRequests[in.ConsumeIntegralInRange<size_t>(0, std::size(kRequests) - 1)]},
              {"params", params}});
      return;
    }
    case 5:
      s.send({{"jsonrpc", "2.0"}, {"method", "textDocument/didClose"}, {"params", {{"textDocument", doc}}}});
      return;
    default: s.send_text(in.ConsumeRandomLengthString(1000)); return;
  }
}

void one_input(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  Session s;
  if (in.ConsumeBool()) {
    // The bytes as a stream: framing first, then each framed message through the server.
    std::istringstream stream(in.ConsumeRemainingBytesAsString());
    std::string body, error;
    for (int n = 0; n < 64; ++n) {
      lsp::ReadStatus st = lsp::read_message(stream, body, error);
      if (st == lsp::ReadStatus::End) break;
      if (st == lsp::ReadStatus::BadHeader) {
        if (error.empty()) fuzz::finding("a bad header without a reason", s.transcript);
        continue;
      }
      s.send_text(body);
    }
    return;
  }
  s.send({{"jsonrpc", "2.0"}, {"id", 0}, {"method", "initialize"}, {"params", {{"capabilities", json::object()}}}});
  s.send({{"jsonrpc", "2.0"}, {"method", "initialized"}, {"params", json::object()}});
  for (int n = 0; n < 32 && in.remaining_bytes() > 0; ++n) step(s, in);
  s.send({{"jsonrpc", "2.0"}, {"id", s.next_id++}, {"method", "shutdown"}});
  s.send({{"jsonrpc", "2.0"}, {"method", "exit"}});
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  fuzz::run_deep([&] { one_input(data, size); });
  return 0;
}
