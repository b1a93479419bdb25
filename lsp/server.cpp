// Dispatch of LSP messages; every feature lives in features/. Bad input of any kind (malformed
// JSON, wrong types, unknown methods, positions out of range) gets an error response or is
// ignored; nothing escapes as an exception.
#include "lsp/server.h"

#include <algorithm>

#include "lsp/analysis.h"
#include "lsp/features/features.h"

namespace fscript::lsp {

json response(const json& id, const json& result) { return {{"jsonrpc", "2.0"}, {"id", id}, {"result", result}}; }

json error_response(const json& id, int code, const std::string& message) {
  return {{"jsonrpc", "2.0"}, {"id", id}, {"error", {{"code", code}, {"message", message}}}};
}

std::vector<json> Server::handle_text(const std::string& text) {
  json message = json::parse(text, nullptr, false);
  if (message.is_discarded()) return {error_response(nullptr, kParseError, "the message is not JSON")};
  return handle(message);
}

std::vector<json> Server::handle(const json& message) {
  std::vector<json> out;
  if (!message.is_object() || !message.contains("method") || !message["method"].is_string()) {
    if (message.is_object() && (message.contains("result") || message.contains("error"))) return out;  // a reply to us
    json id = message.is_object() && message.contains("id") ? message["id"] : json(nullptr);
    out.push_back(error_response(id, kInvalidRequest, "not a JSON-RPC request or notification"));
    return out;
  }
  std::string method = message["method"];
  json params = message.contains("params") ? message["params"] : json::object();
  bool is_request = message.contains("id");
  try {
    if (!is_request) {
      notification(method, params, out);
      return out;
    }
    const json& id = message["id"];
    if (!id.is_number_integer() && !id.is_string()) {
      out.push_back(error_response(nullptr, kInvalidRequest, "the request id must be a number or a string"));
      return out;
    }
    if (!initialized_ && method != "initialize") {
      out.push_back(error_response(id, kServerNotInitialized, "the server is not initialized yet"));
      return out;
    }
    if (shutdown_) {
      out.push_back(error_response(id, kInvalidRequest, "the server is shutting down"));
      return out;
    }
    json result = request(method, params, out);
    if (result.is_object() && result.contains("__error")) {
      out.push_back(error_response(id, result["__error"].get<int>(), result["message"].get<std::string>()));
    } else {
      out.push_back(response(id, result));
    }
  } catch (const json::exception& e) {  // a field missing or of the wrong type
    if (is_request) out.push_back(error_response(message["id"], kInvalidParams, params_error(method, e)));
  }
  return out;
}

// The editor shows this: what was wrong with the params, in words, without the JSON library's
// "[json.exception.type_error.302]" prefix.
std::string Server::params_error(const std::string& method, const json::exception& e) {
  std::string what = e.what();
  if (size_t close = what.find("] "); what.rfind("[json.exception", 0) == 0 && close != std::string::npos)
    what = what.substr(close + 2);
  if (what.rfind("key '", 0) == 0 && what.find("' not found") != std::string::npos)
    what = "the field " + what.substr(4, what.find("' not found") - 3) + " is missing";
  return "invalid params for " + (method.empty() ? std::string("the request") : method) + ": " + what;
}

json Server::initialize_result() const {
  return {{"capabilities",
           {{"positionEncoding", "utf-16"},
            {"textDocumentSync", {{"openClose", true}, {"change", 2}}},
            {"hoverProvider", true},
            {"completionProvider", {{"triggerCharacters", json::array()}}},
            {"definitionProvider", true},
            {"documentSymbolProvider", true},
            {"documentFormattingProvider", true},
            {"referencesProvider", true},
            {"renameProvider", true},
            {"signatureHelpProvider", {{"triggerCharacters", {"(", ","}}}},
            {"foldingRangeProvider", true},
            {"codeActionProvider", {{"codeActionKinds", {"quickfix"}}}},
            {"semanticTokensProvider", {{"legend", semantic_tokens_legend()}, {"full", true}}},
            {"codeLensProvider", {{"resolveProvider", false}}},
            {"executeCommandProvider", {{"commands", {"fscript.preview", "fscript.profile"}}}}}},
          {"serverInfo", {{"name", "fscript-lsp"}, {"version", "0.1"}}}};
}

json Server::request(const std::string& method, const json& params, std::vector<json>& out) {
  auto doc = [&]() -> Document* { return docs_.find(params.at("textDocument").at("uri").get<std::string>()); };
  auto no_doc = [&] { return json{{"__error", kInvalidParams}, {"message", "the document is not open"}}; };
  if (method == "initialize") {
    initialized_ = true;
    const json caps = params.value("capabilities", json::object());
    if (caps.is_object() && caps.contains("workspace") && caps["workspace"].is_object()) {
      const json& w = caps["workspace"];
      lens_refresh_ =
          w.contains("codeLens") && w["codeLens"].is_object() && w["codeLens"].value("refreshSupport", false) == true;
    }
    return initialize_result();
  }
  if (method == "shutdown") {
    shutdown_ = true;
    return nullptr;
  }
  if (method == "workspace/executeCommand") return execute_command(params, out);
  static const char* const kDocumentMethods[] = {
      "textDocument/hover",          "textDocument/completion",          "textDocument/definition",
      "textDocument/documentSymbol", "textDocument/formatting",          "textDocument/references",
      "textDocument/rename",         "textDocument/signatureHelp",       "textDocument/foldingRange",
      "textDocument/codeAction",     "textDocument/semanticTokens/full", "textDocument/codeLens"};
  if (std::find(std::begin(kDocumentMethods), std::end(kDocumentMethods), method) != std::end(kDocumentMethods)) {
    Document* d = doc();
    if (!d) return no_doc();
    if (d->scene && method == "textDocument/hover") {
      json in_script = in_embedded_script(*d, method, params);
      return in_script.is_null() ? scene_hover(*d, params) : in_script;
    }
    if (d->scene &&
        (method == "textDocument/definition" || method == "textDocument/signatureHelp" ||
         method == "textDocument/references" || method == "textDocument/rename"))
      return in_embedded_script(*d, method, params);
    if (method == "textDocument/hover") return hover(*d, params);
    if (method == "textDocument/completion") return completion(*d, params);
    if (method == "textDocument/definition") return definition(*d, params);
    if (method == "textDocument/documentSymbol") return document_symbols(*d);
    if (method == "textDocument/formatting") return formatting(*d);
    if (method == "textDocument/references") return references(*d, params);
    if (method == "textDocument/rename") return rename(*d, params);
    if (method == "textDocument/signatureHelp") return signature_help(*d, params);
    if (method == "textDocument/foldingRange") return folding_ranges(*d);
    if (method == "textDocument/semanticTokens/full") return semantic_tokens(*d);
    if (method == "textDocument/codeLens") {
      auto last = profiles_.find(d->uri);
      return code_lenses(*d, last == profiles_.end() ? nullptr : &last->second);
    }
    return code_actions(*d, params);
  }
  return {{"__error", kMethodNotFound}, {"message", "unknown method '" + method + "'"}};
}

// fscript.preview URI: the live preview's URL; fscript.profile URI: the document's profile (its
// lenses kept for codeLens, and the client asked to refresh them where it can).
json Server::execute_command(const json& params, std::vector<json>& out) {
  const std::string command = params.at("command").is_string() ? params.at("command").get<std::string>() : "";
  if (command != "fscript.preview" && command != "fscript.profile")
    return {{"__error", kInvalidParams}, {"message", "unknown command " + params.at("command").dump()}};
  const json& args = params.value("arguments", json::array());
  if (!args.is_array() || args.empty() || !(args[0].is_string() || (args[0].is_object() && args[0].contains("uri"))))
    return {{"__error", kInvalidParams}, {"message", command + " wants the document's URI as its argument"}};
  std::string uri = args[0].is_string() ? args[0].get<std::string>() : args[0].at("uri").get<std::string>();
  if (command == "fscript.preview") return previews_.start(uri);
  Document* d = docs_.find(uri);
  if (!d) return {{"__error", kInvalidParams}, {"message", "the document is not open"}};
  json result = run_profile(*d, profiles_[uri]);
  if (lens_refresh_ && !result.contains("__error"))
    out.push_back({{"jsonrpc", "2.0"},
                   {"id", "fscript-lens-refresh-" + std::to_string(++requests_)},
                   {"method", "workspace/codeLens/refresh"}});
  return result;
}

namespace {

// Every "range" in `result`, from positions in `script` (which starts at byte `base` of `scene`)
// to positions in the .wrl.
void map_ranges(json& result, const Document& script, const Document& scene, size_t base) {
  if (result.is_array()) {
    for (json& item : result) map_ranges(item, script, scene, base);
    return;
  }
  if (!result.is_object()) return;
  for (auto& [key, value] : result.items()) {
    if (key != "range") {
      map_ranges(value, script, scene, base);
      continue;
    }
    for (const char* end : {"start", "end"}) {
      Position q{value[end]["line"].get<uint32_t>(), value[end]["character"].get<uint32_t>()};
      Position out = position_of(scene.text, base + offset_of(script.text, q));
      value[end] = {{"line", out.line}, {"character", out.character}};
    }
  }
}

}  // namespace

// Hover, definition, signature help, references and rename on the FScript inside a .wrl: the
// feature runs on the script as a document of its own, and every range comes back in .wrl
// positions.
json Server::in_embedded_script(const Document& scene, const std::string& method, const json& params) {
  Document script;
  size_t base = 0;
  if (!embedded_script_at(scene, offset_of(scene.text, position_param(params)), script, base)) return nullptr;
  Position local = position_of(script.text, offset_of(scene.text, position_param(params)) - base);
  json p = params;
  p["position"] = {{"line", local.line}, {"character", local.character}};
  json result = method == "textDocument/hover" ? hover(script, p)
      : method == "textDocument/definition"    ? definition(script, p)
      : method == "textDocument/references"    ? references(script, p)
      : method == "textDocument/rename"        ? rename(script, p)
                                               : signature_help(script, p);
  if (!result.contains("__error")) map_ranges(result, script, scene, base);
  return result;
}

void Server::notification(const std::string& method, const json& params, std::vector<json>& out) {
  if (method == "exit") {
    exited_ = true;
    return;
  }
  if (!initialized_) return;  // notifications before initialize are dropped, as LSP says
  if (method == "textDocument/didOpen") {
    const json& td = params.at("textDocument");
    publish(docs_.open(td.at("uri"), td.at("text"), td.value("version", 0)), out);
  } else if (method == "textDocument/didChange") {
    Document* d = docs_.find(params.at("textDocument").at("uri").get<std::string>());
    if (!d) return;
    for (const json& change : params.at("contentChanges")) {
      if (!change.contains("range")) {
        d->text = change.at("text").get<std::string>();
        ++d->revision;
        continue;
      }
      const json& r = change.at("range");
      Position from{r.at("start").at("line").get<uint32_t>(), r.at("start").at("character").get<uint32_t>()};
      Position to{r.at("end").at("line").get<uint32_t>(), r.at("end").at("character").get<uint32_t>()};
      Documents::edit(*d, from, to, change.at("text").get<std::string>());
    }
    d->version = params.at("textDocument").value("version", d->version);
    publish(*d, out);
  } else if (method == "textDocument/didClose") {
    std::string uri = params.at("textDocument").at("uri");
    docs_.close(uri);
    profiles_.erase(uri);
    out.push_back({{"jsonrpc", "2.0"},
                   {"method", "textDocument/publishDiagnostics"},
                   {"params", {{"uri", uri}, {"diagnostics", json::array()}}}});
  }
  // initialized, $/cancelRequest (requests are answered in order, each at once), $/setTrace and
  // other notifications need nothing.
}

void Server::publish(const Document& d, std::vector<json>& out) {
  out.push_back({{"jsonrpc", "2.0"}, {"method", "textDocument/publishDiagnostics"}, {"params", diagnostics(d)}});
}

}  // namespace fscript::lsp
