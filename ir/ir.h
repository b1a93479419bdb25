#pragma once
// The SSA IR: modules of functions of basic blocks of instructions, every value a float32.
// Instructions are owned by their Function's pool; blocks list them in order, phis first and
// exactly one terminator last. Memory (globals, arrays) is explicit, so passes see all effects.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace fscript::ir {

enum class Op : uint8_t {
#define FS_OP(N, M, A, F, FN, HOW) N,
#include "ir/opcodes.def"
};

enum OpFlag : uint32_t {
  Pure = 1u << 0,
  Commutative = 1u << 1,
  Terminator = 1u << 2,
  CallsRuntime = 1u << 3,
  Traps = 1u << 4,
  Memory = 1u << 5,
  NoValue = 1u << 6,
};

// How backends run an op's runtime/math function (ir/opcodes.def's last column).
enum class MathHow : uint8_t { None, Lane, Batch, Trig };
constexpr uint32_t how_flags(MathHow how) {
  return how == MathHow::Batch || how == MathHow::Trig ? uint32_t{CallsRuntime} : 0u;
}

struct OpInfo {
  const char* mnemonic;
  int arity;  // -1: variadic
  uint32_t flags;
};

extern const OpInfo kOpInfo[];
constexpr int kNumOps = 0
#define FS_OP(N, M, A, F, FN, HOW) +1
#include "ir/opcodes.def"
    ;
inline const OpInfo& op_info(Op op) { return kOpInfo[static_cast<int>(op)]; }
inline bool has_flag(Op op, OpFlag f) { return (op_info(op).flags & f) != 0; }
inline const char* mnemonic(Op op) { return op_info(op).mnemonic; }

struct Block;
struct Function;

// The parameter bounds the value-range analysis tries (ir/ranges.h): the backends' bounded code
// assumes every parameter finite with |p| <= one of these.
constexpr double kParamBounds[] = {65536.0, 1024.0, 16.0};
constexpr size_t kNumParamBounds = 3;
// What a row parameter is known to hold: floats in [lo, hi], NaN only if `nan`.
struct ParamRange {
  float lo, hi;
  bool nan;
};

// One instruction; it defines value v<id> unless it is a store, tick or terminator.
struct Inst {
  Op op = Op::Const;
  uint32_t id = 0;
  float imm = 0;              // Const
  int32_t aux = 0;            // Param index, global/array slot, callee index
  bool array_global = false;  // array ops: aux indexes Module::arrays (else Function::arrays)
  uint32_t line = 0;          // source line and column, for runtime errors (0: none)
  uint32_t col = 0;
  std::vector<Inst*> args;
  std::vector<Block*> targets;  // Jump/Branch successors; Phi: the predecessor of each arg
  Block* block = nullptr;

  bool defines_value() const;
};

struct Block {
  uint32_t id = 0;
  std::vector<Inst*> insts;
  std::vector<Block*> preds;  // kept in sync by the builder and passes; phis follow this order
  Function* fn = nullptr;

  Inst* terminator() const { return insts.empty() ? nullptr : insts.back(); }
  std::vector<Block*> succs() const;
  size_t first_non_phi() const;
};

struct Function {
  std::string name;
  uint32_t num_params = 0;
  uint32_t num_results = 1;
  bool recursive = false;           // part of a call-graph cycle: never inlined
  bool kernel = false;              // the entry: globals start as NaN and die at its return
  // A kernel's parameters from this index on are per row, not per point (the body of a row split,
  // ir/passes/row_split.h): a batch holds rows of one length, and param k of point i is
  // inputs[k][i / row length] (Kernel::eval_rows). 0: every parameter is per point.
  uint32_t row_params_from = 0;
  // For each of kParamBounds, the range of each row parameter when the inputs it was computed from
  // lie within that bound ([bound * K + k], K row parameters; empty: nothing known). The backends'
  // bounded code assumes it, and checks it on each row's values at run time.
  std::vector<ParamRange> row_param_ranges;
  std::vector<std::string> arrays;  // local array slots
  std::vector<std::unique_ptr<Block>> blocks;  // blocks[0] is the entry
  std::vector<std::unique_ptr<Inst>> pool;
  uint32_t next_value = 0;
  uint32_t next_block = 0;

  Block* entry() const { return blocks.front().get(); }
  Inst* make(Op op);  // a new detached instruction with a fresh value id
  Block* add_block();
  void remove_unreachable_blocks();
  void renumber();  // dense value and block ids in layout order (stable printing)
};

struct Module {
  std::vector<std::string> globals;
  std::vector<std::string> arrays;  // global array slots
  std::vector<std::unique_ptr<Function>> functions;

  int find_function(const std::string& name) const;
  const Function& kernel_function() const;  // the entry (the first function if none is marked)
  int global_slot(const std::string& name);  // find or add
  size_t instruction_count() const;  // over every function: the size that compile costs scale with
  std::unique_ptr<Module> clone() const;
};

// A function with src's name, signature and attributes, and no blocks.
std::unique_ptr<Function> shell_of(const Function& src);
// Replace every use of each key by its value (chains resolved), in one sweep of `fn`.
void replace_uses(Function& fn, std::vector<Inst*>& replacement_by_id);
// Removes `inst` from its block (the pool keeps its memory).
void erase(Inst* inst);
// Redirects the edge pred->old_succ to pred->new_succ, fixing preds lists (phis untouched).
void retarget(Block* pred, Block* old_succ, Block* new_succ);
// Removes the phi operands coming from `pred` in `b`, and pred from b->preds.
void remove_pred(Block* b, Block* pred);

}  // namespace fscript::ir
