#pragma once
// VM bytecode: register code compiled from the optimised SSA IR. Op numbering is ir::Op itself
// (the one table); operands are register numbers or, for binary ops, immediates.
//
//   VInst  | op | kinds | dst | a | b | c | aux | line |
//   kinds: bit 0 = a is the immediate `imm_a`, bit 1 = b is the immediate `imm_b`.
//   Registers are lane vectors in batch mode: register r of lane i is regs[r * lanes + i].
//
// Blocks are laid out in reverse post-order; each ends in a terminator whose edges carry the
// phi moves (a parallel copy) for the lanes that take them. A batch runs a chunk of up to
// kChunkLanes points (kBranchyChunkLanes for a kernel of more than one block: a chunk runs until
// its slowest lane is done): it executes the lowest-numbered block that has waiting lanes, once per
// instruction over all those lanes (masked writes when only some lanes are present), until every
// lane has returned. Straight-line kernels are therefore one pass over the code per chunk.
#include <cstdint>
#include <string>
#include <vector>

#include "ir/ir.h"

namespace fscript::vm {

// Measured (docs/performance.md): with fused pairs 1,024 beats 2,048 and 512 on straight-line
// kernels (prospero 7%, csg8 points 3%), 4,096 is far worse (out of L2); 512
// beats 2,048 on a divergent loop.
constexpr uint32_t kChunkLanes = 1024;
constexpr uint32_t kBranchyChunkLanes = 512;
constexpr uint32_t kNoReg = UINT32_MAX;

// Fused pairs (straight-line functions only, vm_compile.cpp): an instruction whose value is read
// by the next one only, and by nothing else, runs together with it as one instruction, its value
// kept in a vector register instead of a register's lanes in memory: dst = op2(op(a, b), c)
// (kFuseCLast), op2(c, op(a, b)) (kFuseCFirst), with unary ops ignoring their second operand.
// a is a register, b a register or the immediate imm_b (kinds bit 1), c a register or the
// immediate imm_c (kinds bit 2). The ops that fuse:
#define FS_VM_FUSE_FIRST(X) X(Add) X(Sub) X(Mul) X(Max) X(Abs) X(Neg) X(Sqrt)
#define FS_VM_FUSE_SECOND(X) X(Add) X(Sub) X(Mul) X(Div) X(Max) X(Abs) X(Neg) X(Sqrt)
// A pair's first op may also square its value before the second op (dst = op2(op(a, b)^2, c), the
// `squared` flag): x - cx, its square, a sum is how every distance starts. The ops that may:
#define FS_VM_FUSE_SQUARED(X) X(Add) X(Sub)
constexpr uint8_t kFuseNone = 0, kFuseCLast = 1, kFuseCFirst = 2;
#define FS_VM_FUSE_COUNT(N) +1
constexpr int kFuseFirstOps = 0 FS_VM_FUSE_FIRST(FS_VM_FUSE_COUNT),
              kFuseSecondOps = 0 FS_VM_FUSE_SECOND(FS_VM_FUSE_COUNT),
              kFuseSquaredOps = 0 FS_VM_FUSE_SQUARED(FS_VM_FUSE_COUNT);
#undef FS_VM_FUSE_COUNT
// The op's place in each list, or -1.
constexpr int fuse_first_index(ir::Op op) {
  int k = 0;
#define FS_VM_FUSE_AT(N)         \
  if (op == ir::Op::N) return k; \
  ++k;
  FS_VM_FUSE_FIRST(FS_VM_FUSE_AT)
  return -1;
}
constexpr int fuse_second_index(ir::Op op) {
  int k = 0;
  FS_VM_FUSE_SECOND(FS_VM_FUSE_AT)
  return -1;
}
constexpr int fuse_squared_index(ir::Op op) {
  int k = 0;
  FS_VM_FUSE_SQUARED(FS_VM_FUSE_AT)
#undef FS_VM_FUSE_AT
  return -1;
}

struct VInst {
  ir::Op op = ir::Op::Const;
  ir::Op op2 = ir::Op::Const;  // a fused pair's second op
  uint8_t fused = kFuseNone;
  bool squared = false;        // a fused pair's first value squared before the second op
  uint8_t kinds = 0;
  uint32_t dst = kNoReg;
  uint32_t a = kNoReg, b = kNoReg, c = kNoReg;
  float imm_a = 0, imm_b = 0, imm_c = 0;
  int32_t aux = 0;       // global/array slot, callee, or index into VmFunction::lists
  bool array_global = false;
  uint32_t line = 0, col = 0;
};

// A sin and a cos of one value in one block share one range reduction: the first of the two
// computes both (math::sincos_batch), the other's result into the extra register `c`, and the
// second copies it from there. Their `aux` says which they are; unpaired ones have c == kNoReg.
constexpr int32_t kTrigFirst = 1, kTrigSecond = 2;

struct Move {
  uint32_t dst, src;
};

struct Edge {
  uint32_t block = 0;                // target block index
  std::vector<Move> moves;           // phi copies, performed as one parallel copy
};

struct VBlock {
  uint32_t begin = 0, end = 0;       // instruction range, terminator excluded
  ir::Op term = ir::Op::Ret;
  uint32_t cond = kNoReg;            // Branch
  Edge edges[2];                     // Jump: [0]; Branch: [0] when truthy, [1] otherwise
  std::vector<uint32_t> results;     // Ret
};

struct VmFunction {
  std::string name;
  uint32_t num_params = 0;
  uint32_t num_results = 1;
  bool recursive = false;  // calls of it count against the call-depth budget
  uint32_t num_regs = 0;
  uint32_t num_arrays = 0;
  std::vector<std::string> array_names;
  std::vector<uint32_t> param_regs;              // register of each parameter (kNoReg if unused)
  std::vector<std::pair<uint32_t, float>> consts;  // registers holding constants, set once per run
  std::vector<VInst> code;
  std::vector<VBlock> blocks;
  std::vector<std::vector<uint32_t>> lists;      // call argument registers
};

struct VmProgram {
  std::vector<VmFunction> functions;
  uint32_t kernel = 0;
  uint32_t num_globals = 0;
  uint32_t num_global_arrays = 0;
  bool needs_lane_state = false;  // some function ticks, calls, or touches globals or arrays
  uint32_t row_params_from = 0;   // the kernel's ir::Function::row_params_from
  std::vector<std::string> global_names;
  std::vector<std::string> global_array_names;
};

// Binary ops whose operands may be immediates (kinds bits 0 and 1).
inline bool takes_immediates(ir::Op op) {
  switch (op) {
    case ir::Op::Add:
    case ir::Op::Sub:
    case ir::Op::Mul:
    case ir::Op::Div:
    case ir::Op::Mod:
    case ir::Op::Min:
    case ir::Op::Max:
    case ir::Op::Pow:
    case ir::Op::Atan2:
    case ir::Op::Eq:
    case ir::Op::Ne:
    case ir::Op::Lt:
    case ir::Op::Le:
    case ir::Op::Gt:
    case ir::Op::Ge: return true;
    default: return false;
  }
}

// Compiles every function of the module; the kernel is the function flagged `kernel`.
bool compile_program(const ir::Module& m, VmProgram& out, std::string& error);

// Bytecode listing, for debugging and `fscript emit-asm --backend vm`.
std::string disassemble(const VmProgram& p);

}  // namespace fscript::vm
