#pragma once
// The language features, one file each. Each takes the document and the request's params and
// returns the result (JSON null when there is nothing to say).
#include <nlohmann/json.hpp>

#include "lsp/documents.h"

namespace fscript::vrml {
struct Interface;
struct FieldDecl;
struct Scene;
}  // namespace fscript::vrml
namespace fscript::scene {
struct SceneModel;
}  // namespace fscript::scene

namespace fscript::lsp {

// JSON-RPC and LSP error codes.
constexpr int kParseError = -32700, kInvalidRequest = -32600, kMethodNotFound = -32601, kInvalidParams = -32602,
              kInternalError = -32603, kServerNotInitialized = -32002, kRequestCancelled = -32800,
              kRequestFailed = -32803;  // LSP 3.17: a valid request the server declines; the message says why

using json = nlohmann::json;

json diagnostics(const Document& d);  // the params of textDocument/publishDiagnostics
json hover(const Document& d, const json& params);
json scene_hover(const Document& d, const json& params);  // .wrl outside scripts: node types, fields
// Markdown for a node type of the node table and for one of its fields (hover and completion).
std::string node_doc(const std::string& type, const vrml::Interface& iface);
std::string field_doc(const std::string& type, const vrml::FieldDecl& f);
json completion(const Document& d, const json& params);
json definition(const Document& d, const json& params);
json document_symbols(const Document& d);
json formatting(const Document& d);
json references(const Document& d, const json& params);
json rename(const Document& d, const json& params);
json signature_help(const Document& d, const json& params);
json folding_ranges(const Document& d);
json code_actions(const Document& d, const json& params);
json semantic_tokens(const Document& d);
json semantic_tokens_legend();

// Semantic tokens before their relative encoding: byte offsets in the document, a type (the
// index in the legend) and modifier bits.
enum class SemanticType : uint8_t {
  Keyword,
  Function,
  Parameter,
  Variable,
  Number,
  Comment,
  Operator,
  String,
  Type,
  Property
};
constexpr int kDeclarationModifier = 1, kDefaultLibraryModifier = 2;
struct SemanticToken {
  uint32_t begin, end;
  SemanticType type;
  int modifiers;
};
std::vector<SemanticToken> script_token_list(const Document& d);  // a .fs document (or a scene's script)
std::vector<SemanticToken> scene_token_list(const Document& d);   // a .wrl (lsp/features/scene_outline.cpp)
// The .wrl's outline: nodes, PROTOs and the scripts' functions; and its folding ranges.
json scene_symbols(const Document& d);
json scene_folding(const Document& d);

// The document's scene (a .fs wrapped in one FShape) and its model on the VM; false when it has errors.
bool scene_model_of(const Document& d, vrml::Scene& scene, scene::SceneModel& model);

// fscript.profile and the code lenses (lsp/features/profile.cpp): the lenses of the last profile
// of a document, at the revision it was made for.
struct ProfileLenses {
  uint64_t revision = 0;
  json lenses = json::array();
};
json run_profile(const Document& d, ProfileLenses& out);  // executeCommand's result, or an __error
json code_lenses(const Document& d, const ProfileLenses* last);

// LSP range of frontend positions (1-based line and byte column, then a byte length).
json range_of(const std::string& text, uint32_t line, uint32_t col, uint32_t length);
json range_of_span(const std::string& text, uint32_t begin, uint32_t end);
Position position_param(const json& params);

}  // namespace fscript::lsp
