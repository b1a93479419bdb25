#pragma once
// FScript semantic analysis: scopes (var per function, let/const per block), implicit globals
// (assignment to an undeclared name), the letter-case-slip rule, arity and array checks, and
// entry-point discovery. Annotates the AST with symbol ids; lowering reads only those.
#include <string>
#include <vector>

#include "frontend/diagnostics.h"
#include "frontend/fscript/ast.h"

namespace fscript::frontend {

enum class SymKind : uint8_t { Local, Global, Constant, Function, Builtin };

struct Symbol {
  std::string name;
  SymKind kind = SymKind::Local;
  Span decl;             // where it was declared (or first assigned, for an implicit global)
  int owner = -1;        // function index for locals, -1 otherwise
  int slot = -1;  // Global: global slot (array slot if is_array); Function: function index; Builtin: table index
  bool is_array = false;
  bool is_const = false;
  bool is_param = false;
};

struct FunctionInfo {
  Stmt* decl = nullptr;
  std::string name;
  std::vector<int> params;  // symbol ids
  int symbol = -1;
  bool recursive = false;  // in a call-graph cycle
  std::vector<int> callees;
};

enum class ScriptForm : uint8_t {
  Script,  // declares functions
  Expression,  // one expression: its value is the result
  Assignments,  // statements assigning outputs (x=u; y=v; ...)
};

// What the script defines, by the rules of the language spec (names matched without case).
struct EntryPoints {
  int frep = -1;  // function index
  int parametric[3] = {-1, -1, -1};  // parametric_x/y/z
  int colour[3] = {-1, -1, -1};  // parametric_r/g/b
};

struct BuiltinInfo {
  const char* name;
  int arity;
  const char* signature;
  const char* doc;
};
extern const BuiltinInfo kBuiltins[];
extern const int kNumBuiltins;
int find_builtin(const std::string& name);  // -1 if none

// Globals every program has: the inputs and outputs of the scene model.
constexpr const char* kStandardGlobals[] = {"x", "y", "z", "u", "v", "w", "t", "r", "g", "b"};
constexpr const char* kValueGlobal = "$value";  // the result of an expression-form script

struct SemaResult {
  std::vector<Symbol> symbols;
  std::vector<FunctionInfo> functions;
  std::vector<std::string> globals;  // scalar global slots
  std::vector<std::string> global_arrays;  // array global slots
  std::vector<std::vector<std::string>> local_arrays;  // per function: array slot names
  std::vector<std::string> assigned_globals;  // globals assigned anywhere, in first-seen order
  ScriptForm form = ScriptForm::Script;
  EntryPoints entry;

  int function_index(const std::string& name, bool ignore_case) const;
  int global_slot(const std::string& name) const;
};

// `extra_globals`: more predefined input names (an FTransform operation sees f, g, f1, ...).
SemaResult analyze(Program& prog, const SourceFile& file, DiagnosticSink& diag,
                   const std::vector<std::string>& extra_globals = {});

}  // namespace fscript::frontend
