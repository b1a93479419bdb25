// x86-64 encoding: legacy prefix, REX, opcode, ModRM, SIB, displacement, immediate (Intel SDM
// vol. 2, chapter 2). rsp/r12 as a base need a SIB byte; rbp/r13 as a base with no displacement
// need an explicit disp8 of 0; rip-relative operands are resolved in finish().
#include "backends/sse/x86.h"

#include <cstdio>
#include <cstring>

namespace fscript::sse {
namespace {

uint8_t n(Gp g) { return static_cast<uint8_t>(g); }
uint8_t n(Xmm x) { return static_cast<uint8_t>(x); }
bool fits8(int32_t v) { return v >= -128 && v <= 127; }

}  // namespace

void Assembler::emit(uint8_t prefix, bool w, std::initializer_list<uint8_t> opcode, uint8_t reg, const Operand& rm,
                     int imm_size, uint32_t imm) {
  if (prefix) code_.push_back(prefix);
  uint8_t rex = 0x40 | (w ? 8 : 0) | ((reg >> 3) & 1) << 2;
  if (rm.is_mem && rm.mem.label < 0) {
    rex |= (n(rm.mem.index) >> 3 & 1) << 1;
    rex |= n(rm.mem.base) >> 3 & 1;
  } else if (!rm.is_mem) {
    rex |= rm.reg >> 3 & 1;
  }
  if (rex != 0x40) code_.push_back(rex);
  code_.insert(code_.end(), opcode.begin(), opcode.end());
  modrm(reg, rm, imm_size, imm);
}

void Assembler::modrm(uint8_t reg, const Operand& rm, int imm_size, uint32_t imm) {
  auto immediate = [&] {
    for (int k = 0; k < imm_size; ++k) code_.push_back(static_cast<uint8_t>(imm >> (8 * k)));
  };
  uint8_t r3 = (reg & 7) << 3;
  if (!rm.is_mem) {
    code_.push_back(0xC0 | r3 | (rm.reg & 7));
    immediate();
    return;
  }
  const Mem& mem = rm.mem;
  if (mem.label >= 0) {  // [rip + disp32]
    code_.push_back(0x05 | r3);
    size_t at = code_.size();
    code_.insert(code_.end(), 4, 0);
    immediate();
    fixups_.push_back({at, code_.size(), mem.label});
    return;
  }
  bool sib = mem.index != Gp::rsp || (n(mem.base) & 7) == 4;
  uint8_t mod = mem.disp == 0 && (n(mem.base) & 7) != 5 ? 0x00 : fits8(mem.disp) ? 0x40 : 0x80;
  code_.push_back(mod | r3 | (sib ? 4 : (n(mem.base) & 7)));
  if (sib) {
    uint8_t ss = mem.scale == 8 ? 3 : mem.scale == 4 ? 2 : mem.scale == 2 ? 1 : 0;
    code_.push_back(static_cast<uint8_t>(ss << 6 | (n(mem.index) & 7) << 3 | (n(mem.base) & 7)));
  }
  if (mod == 0x40) code_.push_back(static_cast<uint8_t>(mem.disp));
  if (mod == 0x80) {
    uint32_t d = static_cast<uint32_t>(mem.disp);
    for (int k = 0; k < 4; ++k) code_.push_back(static_cast<uint8_t>(d >> (8 * k)));
  }
  immediate();
}

void Assembler::sse(uint8_t prefix, std::initializer_list<uint8_t> opcode, Xmm d, const Operand& s, int imm8) {
  emit(prefix, false, opcode, n(d), s, imm8 >= 0 ? 1 : 0, static_cast<uint32_t>(imm8));
}

// VEX (SDM vol. 2, 2.3): R, X, B and vvvv stored inverted; L = 1 (256 bits) in wide mode, W = 0.
void Assembler::vex(uint8_t pp, uint8_t opcode, Xmm d, Xmm v, const Operand& rm, uint8_t map, int imm8, int l) {
  uint8_t r = ~n(d) >> 3 & 1, x = 1, b = 1;
  if (rm.is_mem && rm.mem.label < 0) {
    x = ~n(rm.mem.index) >> 3 & 1;
    b = ~n(rm.mem.base) >> 3 & 1;
  } else if (!rm.is_mem) {
    b = ~rm.reg >> 3 & 1;
  }
  uint8_t vvvv = static_cast<uint8_t>((~n(v) & 15) << 3 | ((l < 0 ? wide_ : l == 1) ? 4 : 0) | pp);
  if (x && b && map == 1) {
    code_.insert(code_.end(), {0xC5, static_cast<uint8_t>(r << 7 | vvvv)});
  } else {
    code_.insert(code_.end(), {0xC4, static_cast<uint8_t>(r << 7 | x << 6 | b << 5 | map), vvvv});
  }
  code_.push_back(opcode);
  modrm(n(d), rm, imm8 >= 0 ? 1 : 0, static_cast<uint32_t>(imm8));
}

void Assembler::wide_op(const char* name, uint8_t pp, uint8_t map, uint8_t opcode, Xmm d, const Operand& s, bool unary,
                        int imm8) {
  if (listing_on_) {
    std::string text = std::string(name) + " " + operand(d) + (unary ? "" : ", " + operand(d)) + ", " +
        (s.is_mem ? operand(s.mem) : operand(static_cast<Xmm>(s.reg))) +
        (opcode == 0x4A && map == 3 ? ", ymm0" : "");  // vblendvps's mask register
    lines_.push_back({code_.size(), text});
  }
  vex(pp, opcode, d, unary ? Xmm::x0 : d, s, map, imm8);
}

// ---- SSE ----
// Packed operations with an eight-lane form: VEX.256 in map 0F in wide mode, with the legacy
// prefix as VEX.pp (none: single precision; 66: the double and integer ones of the inline sin/cos,
// doubles four to a ymm register, integers eight: AVX2).
#define FS_PACKED_DEFINE(name, prefix, pp, opcode, unary)                   \
  void Assembler::name(Xmm d, Xmm s) {                                      \
    if (wide_) return wide_op("v" #name, pp, 1, opcode, d, r(n(s)), unary); \
    list(#name, d, s), sse(prefix, {0x0F, opcode}, d, r(n(s)));             \
  }                                                                         \
  void Assembler::name(Xmm d, const Mem& s) {                               \
    if (wide_) return wide_op("v" #name, pp, 1, opcode, d, m(s), unary);    \
    list(#name, d, s), sse(prefix, {0x0F, opcode}, d, m(s));                \
  }
FS_PACKED_DEFINE(addps, 0, 0, 0x58, false)
FS_PACKED_DEFINE(subps, 0, 0, 0x5C, false)
FS_PACKED_DEFINE(mulps, 0, 0, 0x59, false)
FS_PACKED_DEFINE(divps, 0, 0, 0x5E, false)
FS_PACKED_DEFINE(minps, 0, 0, 0x5D, false)
FS_PACKED_DEFINE(maxps, 0, 0, 0x5F, false)
FS_PACKED_DEFINE(sqrtps, 0, 0, 0x51, true)
FS_PACKED_DEFINE(andps, 0, 0, 0x54, false)
FS_PACKED_DEFINE(andnps, 0, 0, 0x55, false)
FS_PACKED_DEFINE(orps, 0, 0, 0x56, false)
FS_PACKED_DEFINE(xorps, 0, 0, 0x57, false)
FS_PACKED_DEFINE(addpd, 0x66, 1, 0x58, false)
FS_PACKED_DEFINE(subpd, 0x66, 1, 0x5C, false)
FS_PACKED_DEFINE(mulpd, 0x66, 1, 0x59, false)
FS_PACKED_DEFINE(pand, 0x66, 1, 0xDB, false)
FS_PACKED_DEFINE(pcmpeqd, 0x66, 1, 0x76, false)
FS_PACKED_DEFINE(paddd, 0x66, 1, 0xFE, false)
#undef FS_PACKED_DEFINE

// The rest have no eight-lane form here: refused in wide mode.
#define FS_SSE_DEFINE(name, prefix, ...)                                                                           \
  void Assembler::name(Xmm d, Xmm s) { narrow(#name), list(#name, d, s), sse(prefix, {__VA_ARGS__}, d, r(n(s))); } \
  void Assembler::name(Xmm d, const Mem& s) { narrow(#name), list(#name, d, s), sse(prefix, {__VA_ARGS__}, d, m(s)); }
FS_SSE_DEFINE(addss, 0xF3, 0x0F, 0x58)
FS_SSE_DEFINE(subss, 0xF3, 0x0F, 0x5C)
FS_SSE_DEFINE(mulss, 0xF3, 0x0F, 0x59)
FS_SSE_DEFINE(divss, 0xF3, 0x0F, 0x5E)
FS_SSE_DEFINE(minss, 0xF3, 0x0F, 0x5D)
FS_SSE_DEFINE(maxss, 0xF3, 0x0F, 0x5F)
FS_SSE_DEFINE(sqrtss, 0xF3, 0x0F, 0x51)
FS_SSE_DEFINE(cvtdq2ps, 0, 0x0F, 0x5B)
FS_SSE_DEFINE(cvttps2dq, 0xF3, 0x0F, 0x5B)
FS_SSE_DEFINE(cvtps2dq, 0x66, 0x0F, 0x5B)
FS_SSE_DEFINE(pandn, 0x66, 0x0F, 0xDF)
FS_SSE_DEFINE(por, 0x66, 0x0F, 0xEB)
FS_SSE_DEFINE(pxor, 0x66, 0x0F, 0xEF)
FS_SSE_DEFINE(pcmpgtd, 0x66, 0x0F, 0x66)
FS_SSE_DEFINE(psubd, 0x66, 0x0F, 0xFA)
FS_SSE_DEFINE(ucomiss, 0, 0x0F, 0x2E)
FS_SSE_DEFINE(punpcklqdq, 0x66, 0x0F, 0x6C)
#undef FS_SSE_DEFINE

// Conversions between four floats or int32s (an xmm register) and four doubles (a ymm register)
// in wide mode; the two-lane forms otherwise.
void Assembler::cvtps2pd(Xmm d, Xmm s) {
  if (wide_) return half("vcvtps2pd", d, true, s, false), vex(0, 0x5A, d, Xmm::x0, r(n(s)));
  list("cvtps2pd", d, s), sse(0, {0x0F, 0x5A}, d, r(n(s)));
}
void Assembler::cvtps2pd(Xmm d, const Mem& s) {
  narrow("cvtps2pd"), list("cvtps2pd", d, s), sse(0, {0x0F, 0x5A}, d, m(s));
}
void Assembler::cvtpd2ps(Xmm d, Xmm s) {
  if (wide_) return half("vcvtpd2ps", d, false, s, true), vex(1, 0x5A, d, Xmm::x0, r(n(s)));
  list("cvtpd2ps", d, s), sse(0x66, {0x0F, 0x5A}, d, r(n(s)));
}
void Assembler::cvtpd2ps(Xmm d, const Mem& s) {
  narrow("cvtpd2ps"), list("cvtpd2ps", d, s), sse(0x66, {0x0F, 0x5A}, d, m(s));
}
void Assembler::cvttpd2dq(Xmm d, Xmm s) {
  if (wide_) return half("vcvttpd2dq", d, false, s, true), vex(1, 0xE6, d, Xmm::x0, r(n(s)));
  list("cvttpd2dq", d, s), sse(0x66, {0x0F, 0xE6}, d, r(n(s)));
}
void Assembler::cvttpd2dq(Xmm d, const Mem& s) {
  narrow("cvttpd2dq"), list("cvttpd2dq", d, s), sse(0x66, {0x0F, 0xE6}, d, m(s));
}
void Assembler::vextractf128(Xmm d, Xmm s, uint8_t imm) {  // d (xmm) = half imm of s (ymm)
  if (listing_on_)
    lines_.push_back(
        {code_.size(),
         "vextractf128 xmm" + std::to_string(n(d)) + ", ymm" + std::to_string(n(s)) + ", " + std::to_string(imm)});
  vex(1, 0x19, s, Xmm::x0, r(n(d)), 3, imm, 1);
}
void Assembler::vinsertf128(Xmm d, Xmm s1, Xmm s2, uint8_t imm) {  // d = s1 with half imm from s2 (xmm)
  if (listing_on_)
    lines_.push_back({code_.size(),
                      "vinsertf128 ymm" + std::to_string(n(d)) + ", ymm" + std::to_string(n(s1)) + ", xmm" +
                          std::to_string(n(s2)) + ", " + std::to_string(imm)});
  vex(1, 0x18, d, s1, r(n(s2)), 3, imm, 1);
}
void Assembler::half(const char* name, Xmm d, bool d_wide, Xmm s, bool s_wide) {
  if (!listing_on_) return;
  auto reg = [](Xmm x, bool w) { return (w ? "ymm" : "xmm") + std::to_string(n(x)); };
  lines_.push_back({code_.size(), std::string(name) + " " + reg(d, d_wide) + ", " + reg(s, s_wide)});
}

#define FS_VEX_DEFINE(name, pp, opcode)                                                                     \
  void Assembler::name(Xmm d, Xmm s1, Xmm s2) { list(#name, d, s1, s2), vex(pp, opcode, d, s1, r(n(s2))); } \
  void Assembler::name(Xmm d, Xmm s1, const Mem& s2) { list(#name, d, s1, s2), vex(pp, opcode, d, s1, m(s2)); }
FS_VEX_DEFINE(vaddps, 0, 0x58)
FS_VEX_DEFINE(vsubps, 0, 0x5C)
FS_VEX_DEFINE(vmulps, 0, 0x59)
FS_VEX_DEFINE(vdivps, 0, 0x5E)
FS_VEX_DEFINE(vminps, 0, 0x5D)
FS_VEX_DEFINE(vmaxps, 0, 0x5F)
FS_VEX_DEFINE(vandps, 0, 0x54)
FS_VEX_DEFINE(vxorps, 0, 0x57)
#undef FS_VEX_DEFINE

void Assembler::blendvps(Xmm d, Xmm s) {  // wide: vblendvps d, d, s, ymm0 (the mask register in imm8[7:4])
  if (wide_) return wide_op("vblendvps", 1, 3, 0x4A, d, r(n(s)), false, 0x00);
  list("blendvps", d, s), sse(0x66, {0x0F, 0x38, 0x14}, d, r(n(s)));
}
void Assembler::blendvps(Xmm d, const Mem& s) {
  if (wide_) return wide_op("vblendvps", 1, 3, 0x4A, d, m(s), false, 0x00);
  list("blendvps", d, s), sse(0x66, {0x0F, 0x38, 0x14}, d, m(s));
}
void Assembler::cmpps(Xmm d, Xmm s, Pred p) {
  if (wide_) return wide_op(("vcmp" + operand(p) + "ps").c_str(), 0, 1, 0xC2, d, r(n(s)), false, static_cast<int>(p));
  if (listing_on_) list(("cmp" + operand(p) + "ps").c_str(), d, s);
  sse(0, {0x0F, 0xC2}, d, r(n(s)), static_cast<int>(p));
}
void Assembler::cmpps(Xmm d, const Mem& s, Pred p) {
  if (wide_) return wide_op(("vcmp" + operand(p) + "ps").c_str(), 0, 1, 0xC2, d, m(s), false, static_cast<int>(p));
  if (listing_on_) list(("cmp" + operand(p) + "ps").c_str(), d, s);
  sse(0, {0x0F, 0xC2}, d, m(s), static_cast<int>(p));
}
void Assembler::cmpss(Xmm d, Xmm s, Pred p) {
  narrow("cmpss");
  if (listing_on_) list(("cmp" + operand(p) + "ss").c_str(), d, s);
  sse(0xF3, {0x0F, 0xC2}, d, r(n(s)), static_cast<int>(p));
}
void Assembler::roundps(Xmm d, Xmm s, Rounding k) {
  if (wide_) {
    list("vroundps", d, s, k);
    return vex(1, 0x08, d, Xmm::x0, r(n(s)), 3, static_cast<int>(k));
  }
  list("roundps", d, s, k);
  sse(0x66, {0x0F, 0x3A, 0x08}, d, r(n(s)), static_cast<int>(k));
}
void Assembler::roundss(Xmm d, Xmm s, Rounding k) {
  narrow("roundss");
  list("roundss", d, s, k);
  sse(0x66, {0x0F, 0x3A, 0x0A}, d, r(n(s)), static_cast<int>(k));
}
void Assembler::shufps(Xmm d, Xmm s, uint8_t imm) {
  narrow("shufps");
  list("shufps", d, s, imm);
  sse(0, {0x0F, 0xC6}, d, r(n(s)), imm);
}
void Assembler::pslld(Xmm d, uint8_t imm) {  // wide: vpslld d, d, imm (the destination in vvvv, /6)
  list(wide_ ? "vpslld" : "pslld", d, imm);
  if (wide_) return vex(1, 0x72, static_cast<Xmm>(6), d, r(n(d)), 1, imm);
  emit(0x66, false, {0x0F, 0x72}, 6, r(n(d)), 1, imm);
}
void Assembler::psrld(Xmm d, uint8_t imm) {
  narrow("psrld");
  list("psrld", d, imm);
  emit(0x66, false, {0x0F, 0x72}, 2, r(n(d)), 1, imm);
}
void Assembler::psrad(Xmm d, uint8_t imm) {
  narrow("psrad");
  list("psrad", d, imm);
  emit(0x66, false, {0x0F, 0x72}, 4, r(n(d)), 1, imm);
}
void Assembler::movhlps(Xmm d, Xmm s) {
  narrow("movhlps");
  list("movhlps", d, s);
  sse(0, {0x0F, 0x12}, d, r(n(s)));
}
void Assembler::movlhps(Xmm d, Xmm s) {
  narrow("movlhps");
  list("movlhps", d, s);
  sse(0, {0x0F, 0x16}, d, r(n(s)));
}
// Moves: VEX.256 vmovaps / vmovups in wide mode (an aligned move needs 32-byte alignment there).
#define FS_MOVE(name, load, store)                     \
  void Assembler::name(Xmm d, const Mem& s) {          \
    list(wide_ ? "v" #name : #name, d, s);             \
    if (wide_) return vex(0, load, d, Xmm::x0, m(s));  \
    sse(0, {0x0F, load}, d, m(s));                     \
  }                                                    \
  void Assembler::name(const Mem& d, Xmm s) {          \
    list(wide_ ? "v" #name : #name, d, s);             \
    if (wide_) return vex(0, store, s, Xmm::x0, m(d)); \
    sse(0, {0x0F, store}, s, m(d));                    \
  }
FS_MOVE(movaps, 0x28, 0x29)
FS_MOVE(movups, 0x10, 0x11)
#undef FS_MOVE
void Assembler::movaps(Xmm d, Xmm s) {
  list(wide_ ? "vmovaps" : "movaps", d, s);
  if (wide_) return vex(0, 0x28, d, Xmm::x0, r(n(s)));
  sse(0, {0x0F, 0x28}, d, r(n(s)));
}
void Assembler::movss(Xmm d, const Mem& s) {
  narrow("movss");
  list("movss", d, s);
  sse(0xF3, {0x0F, 0x10}, d, m(s));
}
void Assembler::movss(const Mem& d, Xmm s) {
  narrow("movss");
  list("movss", d, s);
  sse(0xF3, {0x0F, 0x11}, s, m(d));
}
void Assembler::movd(Xmm d, Gp s) {
  narrow("movd");
  list("movd", d, s);
  emit(0x66, false, {0x0F, 0x6E}, n(d), r(n(s)));
}
void Assembler::movd(Gp d, Xmm s) {
  narrow("movd");
  list("movd", d, s);
  emit(0x66, false, {0x0F, 0x7E}, n(s), r(n(d)));
}
void Assembler::movmskps(Gp d, Xmm s) {  // wide: eight sign bits
  list(wide_ ? "vmovmskps" : "movmskps", d, s);
  if (wide_) return vex(0, 0x50, static_cast<Xmm>(n(d)), Xmm::x0, r(n(s)));
  emit(0, false, {0x0F, 0x50}, n(d), r(n(s)));
}
void Assembler::cvtsi2ss(Xmm d, Gp s) {
  narrow("cvtsi2ss");
  list("cvtsi2ss", d, s);
  emit(0xF3, true, {0x0F, 0x2A}, n(d), r(n(s)));
}
void Assembler::vbroadcastss(Xmm d, const Mem& s) { list("vbroadcastss", d, s), vex(1, 0x18, d, Xmm::x0, m(s), 2); }
void Assembler::vzeroupper() { list("vzeroupper"), code_.insert(code_.end(), {0xC5, 0xF8, 0x77}); }
void Assembler::cvttss2si(Gp d, Xmm s) {
  narrow("cvttss2si");
  list("cvttss2si", d, s);
  emit(0xF3, true, {0x0F, 0x2C}, n(d), r(n(s)));
}

// ---- general purpose ----
void Assembler::mov(Gp d, Gp s) {
  list("mov", d, s);
  emit(0, true, {0x89}, n(s), r(n(d)));
}
void Assembler::mov(Gp d, const Mem& s) {
  list("mov", d, s);
  emit(0, true, {0x8B}, n(d), m(s));
}
void Assembler::mov(const Mem& d, Gp s) {
  list("mov", d, s);
  emit(0, true, {0x89}, n(s), m(d));
}
void Assembler::mov32(Gp d, const Mem& s) {
  list("mov32", d, s);
  emit(0, false, {0x8B}, n(d), m(s));
}
void Assembler::mov32(const Mem& d, Gp s) {
  list("mov32", d, s);
  emit(0, false, {0x89}, n(s), m(d));
}
void Assembler::lea(Gp d, const Mem& s) {
  list("lea", d, s);
  emit(0, true, {0x8D}, n(d), m(s));
}
void Assembler::add(Gp d, Gp s) {
  list("add", d, s);
  emit(0, true, {0x01}, n(s), r(n(d)));
}
void Assembler::sub(Gp d, Gp s) {
  list("sub", d, s);
  emit(0, true, {0x29}, n(s), r(n(d)));
}
void Assembler::cmp(Gp a, Gp b) {
  list("cmp", a, b);
  emit(0, true, {0x39}, n(b), r(n(a)));
}
void Assembler::test(Gp a, Gp b) {
  list("test", a, b);
  emit(0, true, {0x85}, n(b), r(n(a)));
}
void Assembler::imul(Gp d, Gp s) {
  list("imul", d, s);
  emit(0, true, {0x0F, 0xAF}, n(d), r(n(s)));
}

void Assembler::mov_imm(Gp d, uint64_t imm) {
  list("mov", d, imm);
  if (imm <= 0xFFFFFFFFu) {  // mov r32, imm32 zero-extends
    if (n(d) >= 8) code_.push_back(0x41);
    code_.push_back(static_cast<uint8_t>(0xB8 + (n(d) & 7)));
    for (int k = 0; k < 4; ++k) code_.push_back(static_cast<uint8_t>(imm >> (8 * k)));
    return;
  }
  code_.push_back(static_cast<uint8_t>(0x48 | (n(d) >> 3)));
  code_.push_back(static_cast<uint8_t>(0xB8 + (n(d) & 7)));
  for (int k = 0; k < 8; ++k) code_.push_back(static_cast<uint8_t>(imm >> (8 * k)));
}

namespace {
// The group-1 immediate forms: 83 /digit ib, or 81 /digit id.
constexpr uint8_t kAdd = 0, kSub = 5, kCmp = 7;
}  // namespace

#define FS_GROUP1(name, digit)                                                                \
  void Assembler::name(Gp d, int32_t imm) {                                                   \
    list(#name, d, imm);                                                                      \
    bool small = fits8(imm);                                                                  \
    emit(0, true, {static_cast<uint8_t>(small ? 0x83 : 0x81)}, digit, r(n(d)), small ? 1 : 4, \
         static_cast<uint32_t>(imm));                                                         \
  }                                                                                           \
  void Assembler::name(const Mem& d, int32_t imm) {                                           \
    list(#name, d, imm);                                                                      \
    bool small = fits8(imm);                                                                  \
    emit(0, true, {static_cast<uint8_t>(small ? 0x83 : 0x81)}, digit, m(d), small ? 1 : 4,    \
         static_cast<uint32_t>(imm));                                                         \
  }
FS_GROUP1(add, kAdd)
FS_GROUP1(sub, kSub)
FS_GROUP1(cmp, kCmp)
#undef FS_GROUP1
void Assembler::cmp8(const Mem& a, uint8_t imm) {
  list("cmp8", a, imm);
  emit(0, false, {0x80}, kCmp, m(a), 1, imm);
}
void Assembler::and_(Gp d, int32_t imm) {
  list("and", d, imm);
  bool small = fits8(imm);
  emit(0, true, {static_cast<uint8_t>(small ? 0x83 : 0x81)}, 4, r(n(d)), small ? 1 : 4, static_cast<uint32_t>(imm));
}

void Assembler::push(Gp g) {
  list("push", g);
  if (n(g) >= 8) code_.push_back(0x41);
  code_.push_back(static_cast<uint8_t>(0x50 + (n(g) & 7)));
}
void Assembler::pop(Gp g) {
  list("pop", g);
  if (n(g) >= 8) code_.push_back(0x41);
  code_.push_back(static_cast<uint8_t>(0x58 + (n(g) & 7)));
}
void Assembler::call(Gp target) {
  list("call", target);
  emit(0, false, {0xFF}, 2, r(n(target)));
}
void Assembler::call(const Mem& target) {
  list("call", target);
  emit(0, false, {0xFF}, 2, m(target));
}
void Assembler::ret() {
  list("ret");
  code_.push_back(0xC3);
}

void Assembler::rel32(Label l) {
  size_t at = code_.size();
  code_.insert(code_.end(), 4, 0);
  fixups_.push_back({at, code_.size(), l.id});
}
void Assembler::jmp(Label l) {
  list("jmp", l);
  code_.push_back(0xE9);
  rel32(l);
}
void Assembler::jcc(Cond c, Label l) {
  if (listing_on_) list(("j" + operand(c)).c_str(), l);
  code_.push_back(0x0F);
  code_.push_back(static_cast<uint8_t>(0x80 + static_cast<uint8_t>(c)));
  rel32(l);
}

// ---- labels and constants ----
Label Assembler::new_label() {
  label_pos_.push_back(-1);
  return {static_cast<int>(label_pos_.size()) - 1};
}
void Assembler::bind(Label l) {
  label_pos_[l.id] = static_cast<int64_t>(code_.size());
  if (listing_on_) lines_.push_back({code_.size(), "L" + std::to_string(l.id) + ":"});
}

void Assembler::patch32(size_t at, uint32_t v) { std::memcpy(code_.data() + at, &v, 4); }

Label Assembler::constant(const std::array<uint32_t, 4>& bits) {
  auto [it, fresh] = pool_index_.try_emplace(bits, 0);
  if (!fresh) return {it->second};
  Label l = new_label();
  it->second = l.id;
  pool_.push_back({bits, l.id});
  return l;
}

Label Assembler::constant_ps(float v) {
  uint32_t b;
  std::memcpy(&b, &v, 4);
  return constant({b, b, b, b});
}

std::vector<uint8_t> Assembler::finish() {
  int copies = wide_ ? 2 : 1;  // a wide constant is its four words twice: eight lanes
  while (code_.size() % (16 * copies)) code_.push_back(0xCC);  // int3 padding: never executed
  for (const auto& [value, label] : pool_) {
    label_pos_[label] = static_cast<int64_t>(code_.size());
    for (int c = 0; c < copies; ++c)
      for (uint32_t word : value)
        for (int k = 0; k < 4; ++k) code_.push_back(static_cast<uint8_t>(word >> (8 * k)));
  }
  for (const auto& f : fixups_) {
    int32_t rel = static_cast<int32_t>(label_pos_[f.label] - static_cast<int64_t>(f.end));
    std::memcpy(code_.data() + f.at, &rel, 4);
  }
  return code_;
}

// ---- listing ----
std::string Assembler::operand(Xmm x) const { return (wide_ ? "ymm" : "xmm") + std::to_string(n(x)); }
std::string Assembler::operand(Gp g) {
  static const char* kNames[] = {"rax", "rcx", "rdx", "rbx", "rsp", "rbp", "rsi", "rdi",
                                 "r8",  "r9",  "r10", "r11", "r12", "r13", "r14", "r15"};
  return kNames[n(g)];
}
std::string Assembler::operand(const Mem& m) {
  if (m.label >= 0) return "[rip+L" + std::to_string(m.label) + "]";
  std::string s = "[" + operand(m.base);
  if (m.index != Gp::rsp) s += "+" + operand(m.index) + "*" + std::to_string(m.scale);
  if (m.disp) s += (m.disp < 0 ? "-" : "+") + std::to_string(m.disp < 0 ? -static_cast<int64_t>(m.disp) : m.disp);
  return s + "]";
}
std::string Assembler::operand(Pred p) {
  static const char* kNames[] = {"eq", "lt", "le", "unord", "neq", "nlt", "nle", "ord"};
  return kNames[static_cast<int>(p)];
}
std::string Assembler::operand(Rounding r) {
  switch (r) {
    case Rounding::Nearest: return "nearest";
    case Rounding::Down: return "down";
    case Rounding::Up: return "up";
    case Rounding::Truncate: return "truncate";
  }
  return "?";
}
std::string Assembler::operand(Cond c) {
  static const char* kNames[] = {"o", "no", "b", "ae", "e", "ne", "be", "a",
                                 "s", "ns", "p", "np", "l", "ge", "le", "g"};
  return kNames[static_cast<int>(c)];
}
std::string Assembler::operand(Label l) { return "L" + std::to_string(l.id); }
std::string Assembler::operand(int64_t v) { return std::to_string(v); }
std::string Assembler::operand(uint64_t v) {
  char buf[24];
  std::snprintf(buf, sizeof buf, "0x%llx", static_cast<unsigned long long>(v));
  return buf;
}

std::string Assembler::listing() const {
  std::string out;
  char buf[32];
  for (const auto& [offset, text] : lines_) {
    bool label = text.back() == ':';
    std::snprintf(buf, sizeof buf, "%6zx  ", offset);
    out += (label ? std::string() : std::string(buf)) + (label ? "" : "  ") + text + "\n";
  }
  for (const auto& [value, label] : pool_) {
    if (label_pos_[label] < 0) continue;  // before finish()
    float f[4];
    std::memcpy(f, value.data(), 16);
    std::snprintf(buf, sizeof buf, "%6llx  ", static_cast<unsigned long long>(label_pos_[label]));
    out += "L" + std::to_string(label) + ":\n" + buf + "  .float";
    for (int k = 0; k < (wide_ ? 8 : 4); ++k) {
      char num[40];
      std::snprintf(num, sizeof num, "%s %.9g", k ? "," : "", f[k % 4]);
      out += num;
    }
    out += "\n";
  }
  return out;
}

}  // namespace fscript::sse
