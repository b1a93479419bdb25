// Latency of the language server on a 2,000-line script (or a given .fs or .wrl file: a course
// file, shape diagnostics included), measured in-process on the Server the executable runs:
// diagnostics after an incremental edit, and completion. Prints p50 and p95 over 200 of each.
// usage: lsp_latency [lines | FILE]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lsp/server.h"

using fscript::lsp::json;
using Clock = std::chrono::steady_clock;

namespace {

std::string script(int lines) {
  std::string text;
  int n = 0;
  for (int f = 0; n < lines - 5; ++f) {
    text += "function part" + std::to_string(f) + "(x, y, z) {\n";
    text += "  var a = sin(x * " + std::to_string(f + 1) + ") + cos(y);\n";
    text += "  var b = sqrt(a * a + z * z);\n";
    text += "  for (var i = 0; i < 3; i++) { b = b + i * 0.5; }\n";
    text += "  if (b > 1) return b - 1;\n";
    text += "  return max(a, b) - " + std::to_string(f) + ";\n";
    text += "}\n";
    n += 7;
  }
  text += "function FRep(x, y, z, t) {\n  return part0(x, y, z) + part1(y, z, x);\n}\n";
  return text;
}

double percentile(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  return v[static_cast<size_t>(p * static_cast<double>(v.size() - 1))];
}

}  // namespace

int main(int argc, char** argv) {
  std::string arg = argc > 1 ? argv[1] : "2000", uri = "file:///bench.fs", text;
  if (arg.find_first_not_of("0123456789") == std::string::npos) {
    text = script(std::atoi(arg.c_str()));
  } else {
    std::ifstream in(arg);
    std::stringstream all;
    all << in.rdbuf();
    text = all.str();
    uri = "file://" + arg;
    if (!in || text.empty()) return std::fprintf(stderr, "lsp_latency: cannot read %s\n", arg.c_str()), 2;
  }
  fscript::lsp::Server server;
  server.handle({{"jsonrpc", "2.0"}, {"id", 1}, {"method", "initialize"}, {"params", json::object()}});
  int total_lines = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  server.handle({{"jsonrpc", "2.0"},
                 {"method", "textDocument/didOpen"},
                 {"params", {{"textDocument", {{"uri", uri}, {"version", 1}, {"text", text}}}}}});
  std::vector<double> diag_ms, completion_ms;
  for (int k = 0; k < 200; ++k) {
    int line = 1 + (k * 37) % (total_lines - 4);
    json change = {
        {"jsonrpc", "2.0"},
        {"method", "textDocument/didChange"},
        {"params",
         {{"textDocument", {{"uri", uri}, {"version", k + 2}}},
          {"contentChanges",
           json::array({{{"range",
                          {{"start", {{"line", line}, {"character", 0}}}, {"end", {{"line", line}, {"character", 0}}}}},
                         {"text", k % 2 ? "" : " "}}})}}}};
    auto t = Clock::now();
    auto out = server.handle(change);  // the publishDiagnostics notification is made here
    diag_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count());
    if (out.empty()) return 1;
    json complete = {
        {"jsonrpc", "2.0"},
        {"id", 1000 + k},
        {"method", "textDocument/completion"},
        {"params", {{"textDocument", {{"uri", uri}}}, {"position", {{"line", line + 1}, {"character", 10}}}}}};
    t = Clock::now();
    server.handle(complete);
    completion_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t).count());
  }
  std::printf("%d lines: diagnostics after an edit p50 %.2f ms, p95 %.2f ms; completion p50 %.2f ms, p95 %.2f ms\n",
              total_lines, percentile(diag_ms, 0.5), percentile(diag_ms, 0.95), percentile(completion_ms, 0.5),
              percentile(completion_ms, 0.95));
  return 0;
}
