#pragma once
// The language server: JSON-RPC 2.0 requests and notifications of LSP 3.17 in, responses and
// notifications out. Transport-free (main.cpp frames the messages), so tests drive it directly.
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "lsp/documents.h"
#include "lsp/features/features.h"
#include "lsp/preview.h"

namespace fscript::lsp {

using json = nlohmann::json;

class Server {
 public:
  // One message's text in; the messages to send back (responses, diagnostics) out.
  std::vector<json> handle_text(const std::string& text);
  std::vector<json> handle(const json& message);
  bool exited() const { return exited_; }
  int exit_code() const { return shutdown_ ? 0 : 1; }

 private:
  json request(const std::string& method, const json& params, std::vector<json>& out);
  void notification(const std::string& method, const json& params, std::vector<json>& out);
  json initialize_result() const;
  static std::string params_error(const std::string& method, const json::exception& e);
  void publish(const Document& d, std::vector<json>& out);
  json in_embedded_script(const Document& scene, const std::string& method, const json& params);
  json execute_command(const json& params, std::vector<json>& out);

  Documents docs_;
  Previews previews_;  // fscript.preview's fvrml-run --serve children
  std::map<std::string, ProfileLenses> profiles_;  // fscript.profile's, by URI
  bool lens_refresh_ = false;  // the client takes workspace/codeLens/refresh
  uint64_t requests_ = 0;      // requests sent to the client
  bool initialized_ = false, shutdown_ = false, exited_ = false;
};

json response(const json& id, const json& result);
json error_response(const json& id, int code, const std::string& message);

}  // namespace fscript::lsp
