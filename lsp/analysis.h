#pragma once
// What the language features read: a .fs document parsed and analysed (kept even when it has
// errors: the parser recovers), and the identifier under a position.
#include <memory>
#include <string>
#include <vector>

#include "frontend/fscript/script.h"
#include "lsp/documents.h"

namespace fscript::lsp {

struct Analysis {
  frontend::DiagnosticSink diag;
  frontend::Script script;
};

// The document's analysis, made once per revision of its text and shared by the features.
std::shared_ptr<const Analysis> analyze_document(const Document& d);

// The identifier around byte `offset` ([begin, end)); false when there is none.
bool word_at(const std::string& text, size_t offset, size_t& begin, size_t& end);

// The user function named `name` (exact, then ignoring case), or -1.
int find_function(const frontend::SemaResult& sema, const std::string& name);

// The FScript string of a .wrl document that holds byte `offset`: a document of its own (same
// uri) and the byte offset in the .wrl where its text starts. False outside every script, or for
// a string with escapes (its text and the .wrl bytes would not line up).
bool embedded_script_at(const Document& scene, size_t offset, Document& script, size_t& base);

// Every place the name at byte `offset` stands for the same thing: a user function (its
// declaration and calls) or a variable (its declaration, parameters and uses). Empty when the
// position is on no such name.
std::vector<frontend::Span> occurrences(const Analysis& a, const std::string& text, size_t offset);

}  // namespace fscript::lsp
