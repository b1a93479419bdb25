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

// FScript's keywords and what each does (frontend/fscript/tokens.def): completion, hover, rename.
struct Keyword {
  const char* word;
  const char* doc;
};
inline constexpr Keyword kKeywords[] = {
#define FS_KEYWORD(N, S, D) {S, D},
#include "frontend/fscript/tokens.def"
};

// The identifier around byte `offset` ([begin, end)); false when there is none.
bool word_at(const std::string& text, size_t offset, size_t& begin, size_t& end);

// In a .wrl: whether byte `at` is inside a string (where FScript lives); outside strings, `node`
// gets the type of the node whose braces enclose `at` ("" at the top level).
bool scene_context(const std::string& text, size_t at, std::string& node);

// What the name under a position stands for: the one answer hover, definition, references and
// rename all build on. Words are found by word_at (a cursor just after a name is on it); names
// are exact (FScript is case-sensitive) except where sema resolved a call by letter case (`Sin`
// calls `sin`, with a warning); a variable occurrence sema resolved wins over a function of the
// same name, then a user function, then a built-in.
struct SymbolRef {
  enum class Kind { None, Function, Variable, Builtin };
  Kind kind = Kind::None;
  int index = -1;          // sema.functions, sema.symbols or kBuiltins
  frontend::Span name{};   // the word under the cursor
  std::string word;
};
SymbolRef symbol_at(const Analysis& a, const std::string& text, size_t offset);

// The FScript string of a .wrl document that holds byte `offset`: a document of its own (same
// uri) and the byte offset in the .wrl where its text starts. False outside every script, or for
// a string with escapes (its text and the .wrl bytes would not line up).
bool embedded_script_at(const Document& scene, size_t offset, Document& script, size_t& base);

// Every place the name at byte `offset` stands for the same thing (symbol_at): a user function
// (its declaration and calls) or a variable (its declaration, parameters and uses). Empty when the
// position is on no such name.
std::vector<frontend::Span> occurrences(const Analysis& a, const std::string& text, size_t offset);

}  // namespace fscript::lsp
