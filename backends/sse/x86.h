#pragma once
// An x86-64 encoder for the instructions the SSE backend emits: SSE/SSE2/SSE4.1 packed and scalar
// single precision, the integer moves, arithmetic, compares, jumps and calls around them, with
// REX prefixes and every ModRM/SIB/displacement form including rip-relative constants. Bytes go
// into a buffer; labels are resolved and the aligned constant pool appended by finish(). In wide
// mode the packed single operations are encoded as AVX's eight-lane VEX.256 forms (see enable_wide).
#include <array>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <vector>

namespace fscript::sse {

enum class Gp : uint8_t { rax, rcx, rdx, rbx, rsp, rbp, rsi, rdi, r8, r9, r10, r11, r12, r13, r14, r15 };
enum class Xmm : uint8_t { x0, x1, x2, x3, x4, x5, x6, x7, x8, x9, x10, x11, x12, x13, x14, x15 };

// Condition codes of Jcc (the low nibble of 0F 8x).
enum class Cond : uint8_t { O, NO, B, AE, E, NE, BE, A, S, NS, P, NP, L, GE, LE, G };
// Predicates of CMPPS / CMPSS.
enum class Pred : uint8_t { Eq, Lt, Le, Unord, Neq, Nlt, Nle, Ord };
// Rounding modes of ROUNDPS / ROUNDSS (with the precision exception suppressed).
enum class Rounding : uint8_t { Nearest = 8, Down = 9, Up = 10, Truncate = 11 };

struct Label {
  int id = -1;
};

// A memory operand: [base + index * scale + disp], or [rip + label] for the constant pool.
struct Mem {
  Gp base = Gp::rax;
  Gp index = Gp::rsp;  // rsp: no index
  uint8_t scale = 1;
  int32_t disp = 0;
  int label = -1;      // >= 0: rip-relative to this label
  static Mem at(Gp base, int32_t disp = 0) { return {base, Gp::rsp, 1, disp, -1}; }
  static Mem at(Gp base, Gp index, uint8_t scale, int32_t disp = 0) { return {base, index, scale, disp, -1}; }
  static Mem rip(Label l) { return {Gp::rax, Gp::rsp, 1, 0, l.id}; }
};

class Assembler {
 public:
  // ---- SSE: packed and scalar single, register or memory source ----
#define FS_SSE_BINARY(name) \
  void name(Xmm d, Xmm s);  \
  void name(Xmm d, const Mem& s);
  FS_SSE_BINARY(addps)
  FS_SSE_BINARY(subps)
  FS_SSE_BINARY(mulps)
  FS_SSE_BINARY(divps)
  FS_SSE_BINARY(minps)
  FS_SSE_BINARY(maxps)
  FS_SSE_BINARY(sqrtps)
  FS_SSE_BINARY(andps)
  FS_SSE_BINARY(andnps)
  FS_SSE_BINARY(orps)
  FS_SSE_BINARY(xorps)
  FS_SSE_BINARY(addss)
  FS_SSE_BINARY(subss)
  FS_SSE_BINARY(mulss)
  FS_SSE_BINARY(divss)
  FS_SSE_BINARY(minss)
  FS_SSE_BINARY(maxss)
  FS_SSE_BINARY(sqrtss)
  FS_SSE_BINARY(blendvps)  // xmm0 is the implicit mask
  FS_SSE_BINARY(cvtdq2ps)
  FS_SSE_BINARY(cvttps2dq)
  FS_SSE_BINARY(cvtps2dq)
  FS_SSE_BINARY(pand)
  FS_SSE_BINARY(pandn)
  FS_SSE_BINARY(por)
  FS_SSE_BINARY(pxor)
  FS_SSE_BINARY(pcmpeqd)
  FS_SSE_BINARY(pcmpgtd)
  FS_SSE_BINARY(paddd)
  FS_SSE_BINARY(psubd)
  FS_SSE_BINARY(ucomiss)
  FS_SSE_BINARY(cvtps2pd)
  FS_SSE_BINARY(cvtpd2ps)
  FS_SSE_BINARY(cvttpd2dq)  // low two lanes <-> doubles
  FS_SSE_BINARY(addpd)
  FS_SSE_BINARY(subpd)
  FS_SSE_BINARY(mulpd)
  FS_SSE_BINARY(punpcklqdq)
#undef FS_SSE_BINARY
  // ---- AVX (VEX.128): the same operations in three-operand form, d = s1 op s2, no copy of s1 ----
#define FS_VEX_BINARY(name)         \
  void name(Xmm d, Xmm s1, Xmm s2); \
  void name(Xmm d, Xmm s1, const Mem& s2);
  FS_VEX_BINARY(vaddps)
  FS_VEX_BINARY(vsubps)
  FS_VEX_BINARY(vmulps)
  FS_VEX_BINARY(vdivps)
  FS_VEX_BINARY(vminps)
  FS_VEX_BINARY(vmaxps)
  FS_VEX_BINARY(vandps)
  FS_VEX_BINARY(vxorps)
#undef FS_VEX_BINARY
  void cmpps(Xmm d, Xmm s, Pred p);
  void cmpps(Xmm d, const Mem& s, Pred p);
  void cmpss(Xmm d, Xmm s, Pred p);
  void roundps(Xmm d, Xmm s, Rounding r);
  void roundss(Xmm d, Xmm s, Rounding r);
  void shufps(Xmm d, Xmm s, uint8_t imm);
  void pslld(Xmm d, uint8_t imm);
  void psrld(Xmm d, uint8_t imm);
  void psrad(Xmm d, uint8_t imm);
  void movhlps(Xmm d, Xmm s);  // d.low = s.high
  void movlhps(Xmm d, Xmm s);  // d.high = s.low
  void movaps(Xmm d, Xmm s);
  void movaps(Xmm d, const Mem& s);
  void movaps(const Mem& d, Xmm s);
  void movups(Xmm d, const Mem& s);
  void movups(const Mem& d, Xmm s);
  void movss(Xmm d, const Mem& s);
  void movss(const Mem& d, Xmm s);
  void movd(Xmm d, Gp s);    // 32 bits
  void movd(Gp d, Xmm s);
  void movmskps(Gp d, Xmm s);
  void vbroadcastss(Xmm d, const Mem& s);  // every lane = the float at s (VEX; eight lanes when wide)
  // AVX (VEX.256 whatever the mode): a 128-bit half of a ymm register out, or in.
  void vextractf128(Xmm d, Xmm s, uint8_t imm);
  void vinsertf128(Xmm d, Xmm s1, Xmm s2, uint8_t imm);
  void vzeroupper();
  void cvtsi2ss(Xmm d, Gp s);   // 64-bit integer source
  void cvttss2si(Gp d, Xmm s);  // 64-bit integer result

  // ---- general purpose (64-bit unless named 32) ----
  void mov(Gp d, Gp s);
  void mov(Gp d, const Mem& s);
  void mov(const Mem& d, Gp s);
  void mov32(Gp d, const Mem& s);
  void mov32(const Mem& d, Gp s);
  void mov_imm(Gp d, uint64_t imm);  // the shortest of mov r32, imm32 and mov r64, imm64
  void lea(Gp d, const Mem& s);
  void add(Gp d, Gp s);
  void sub(Gp d, Gp s);
  void cmp(Gp a, Gp b);
  void test(Gp a, Gp b);
  void imul(Gp d, Gp s);
  void add(Gp d, int32_t imm);
  void sub(Gp d, int32_t imm);
  void cmp(Gp a, int32_t imm);
  void and_(Gp d, int32_t imm);
  void add(const Mem& d, int32_t imm);  // qword
  void sub(const Mem& d, int32_t imm);
  void cmp(const Mem& a, int32_t imm);
  void cmp8(const Mem& a, uint8_t imm);  // byte
  void push(Gp r);
  void pop(Gp r);
  void call(Gp target);
  void call(const Mem& target);
  void ret();
  void jmp(Label l);
  void jcc(Cond c, Label l);

  // ---- labels and constants ----
  Label new_label();
  void bind(Label l);
  // A 16-byte constant in the pool (deduplicated; 32 bytes, the four words twice, in wide mode);
  // use with Mem::rip.
  Label constant(const std::array<uint32_t, 4>& bits);
  Label constant_ps(float v);  // four lanes of v
  size_t size() const { return code_.size(); }
  // Overwrites the 32-bit little-endian field at `at` (an immediate fixed once the code is known).
  void patch32(size_t at, uint32_t v);
  const std::vector<uint8_t>& bytes() const { return code_; }
  // Resolves every label use, appends the constant pool; the code is then position-independent.
  std::vector<uint8_t> finish();

  // Assembly text of everything emitted (Intel operand order), for `fscript emit-asm`: turned on
  // before emitting; after finish() it also lists the constant pool.
  void enable_listing() { listing_on_ = true; }
  // The target runs AVX: code generators may use the three-operand VEX forms above.
  void enable_vex() { vex_ = true; }
  bool vex() const { return vex_; }
  // Eight lanes: the packed single operations above (moves, arithmetic, min/max, logic, sqrt,
  // compares, roundps, blendvps with ymm0 as its mask, movmskps, and the three-operand forms),
  // and the double and integer ones the inline sin/cos uses (addpd, subpd, mulpd on four doubles;
  // pand, pcmpeqd, paddd, pslld on eight int32s: AVX2; cvtps2pd from, cvtpd2ps and cvttpd2dq to
  // an xmm half) are emitted as their VEX.256 forms on ymm registers, the two-operand ones as
  // d = d op s. An instruction with no eight-lane meaning here (scalar, shuffles, the two-lane
  // moves) is refused: the first such mnemonic is kept in wide_refused(), and the code must not
  // be used.
  void enable_wide() { wide_ = vex_ = true; }
  bool wide() const { return wide_; }
  const std::string& wide_refused() const { return wide_refused_; }
  // Code that runs a fixed count of four lanes (calls of batch functions, lane helpers) says so.
  void refuse_wide(const char* what) { narrow(what); }
  std::string listing() const;

 private:
  struct Operand {  // a register number (0..15) or memory
    bool is_mem;
    uint8_t reg;
    Mem mem;
  };
  static Operand r(uint8_t reg) { return {false, reg, {}}; }
  static Operand m(const Mem& mem) { return {true, 0, mem}; }
  // [prefix] [REX] opcode... ModRM [SIB] [disp] [imm8]
  void emit(uint8_t prefix, bool w, std::initializer_list<uint8_t> opcode, uint8_t reg, const Operand& rm,
            int imm_size = 0, uint32_t imm = 0);
  // ModRM [SIB] [disp] [imm] of an instruction whose prefixes and opcode are out.
  void modrm(uint8_t reg, const Operand& rm, int imm_size, uint32_t imm);
  void sse(uint8_t prefix, std::initializer_list<uint8_t> opcode, Xmm d, const Operand& s, int imm8 = -1);
  // VEX in map 1 (0F), 2 (0F38) or 3 (0F3A) (pp: 0 none, 1 66, 2 F3, 3 F2), L = 1 in wide mode:
  // the 2-byte form when the map is 0F and no X/B bit is needed. v = x0 where vvvv is unused.
  // l: 0 or 1 forces VEX.L (the 128-bit halves' instructions), -1 takes it from the mode.
  void vex(uint8_t pp, uint8_t opcode, Xmm d, Xmm v, const Operand& rm, uint8_t map = 1, int imm8 = -1, int l = -1);
  // A listing line whose operands are halves (xmm) or wholes (ymm) as the instruction has them.
  void half(const char* name, Xmm d, bool d_wide, Xmm s, bool s_wide);
  // A packed single two-operand operation in wide mode: d = d op s (v = d), or d = op s when unary.
  void wide_op(const char* name, uint8_t pp, uint8_t map, uint8_t opcode, Xmm d, const Operand& s, bool unary,
               int imm8 = -1);
  void narrow(const char* name) {
    if (wide_ && wide_refused_.empty()) wide_refused_ = name;
  }
  void rel32(Label l);

  // One listing line per instruction: its offset and text.
  template <typename... Args>
  void list(const char* mnemonic, const Args&... args) {
    if (!listing_on_) return;
    std::string text = mnemonic;
    if constexpr (sizeof...(Args) > 0) {
      const char* sep = " ";
      ((text += sep, text += operand(args), sep = ", "), ...);
    }
    lines_.push_back({code_.size(), text});
  }
  std::string operand(Xmm x) const;
  static std::string operand(Gp g);
  static std::string operand(const Mem& m);
  static std::string operand(Pred p);
  static std::string operand(Rounding r);
  static std::string operand(Cond c);
  static std::string operand(Label l);
  static std::string operand(int64_t v);
  static std::string operand(int32_t v) { return operand(static_cast<int64_t>(v)); }
  static std::string operand(uint8_t v) { return operand(static_cast<int64_t>(v)); }
  static std::string operand(uint64_t v);

  bool listing_on_ = false;
  bool vex_ = false, wide_ = false;
  std::string wide_refused_;
  std::vector<std::pair<size_t, std::string>> lines_;
  std::vector<uint8_t> code_;
  std::vector<int64_t> label_pos_;                 // -1: unbound
  struct Fixup {
    size_t at;   // position of the 32-bit displacement
    size_t end;  // the end of its instruction (displacements are relative to it)
    int label;
  };
  std::vector<Fixup> fixups_;
  std::vector<std::pair<std::array<uint32_t, 4>, int>> pool_;  // constant, label
  struct PoolHash {
    size_t operator()(const std::array<uint32_t, 4>& v) const {
      uint64_t h = 1469598103934665603ull;
      for (uint32_t w : v) h = (h ^ w) * 1099511628211ull;
      return static_cast<size_t>(h);
    }
  };
  std::unordered_map<std::array<uint32_t, 4>, int, PoolHash> pool_index_;
};

}  // namespace fscript::sse
