// The x86-64 encoder as data: one row per instruction form with the bytes GNU as gives for it and
// the text objdump prints; the rows are also disassembled by objdump (an independent decoder) and
// must read back as written. Then labels, rip-relative constants, and code run from W^X memory.
#include <catch2/catch.hpp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>
#include <unistd.h>

#include "backends/sse/code_memory.h"
#include "backends/sse/x86.h"
#include "tests/support/skip.h"

using namespace fscript::sse;

namespace {

struct Row {
  const char* text;  // objdump -M intel, spaces collapsed
  std::function<void(Assembler&)> emit;
  const char* bytes;
};

const Row kRows[] = {
    {"addps xmm0,xmm1", [](Assembler& a) { a.addps(Xmm::x0, Xmm::x1); }, "0f 58 c1"},
    {"addps xmm8,xmm15", [](Assembler& a) { a.addps(Xmm::x8, Xmm::x15); }, "45 0f 58 c7"},
    {"addps xmm3,XMMWORD PTR [rax]", [](Assembler& a) { a.addps(Xmm::x3, Mem::at(Gp::rax)); }, "0f 58 18"},
    {"subps xmm2,xmm9", [](Assembler& a) { a.subps(Xmm::x2, Xmm::x9); }, "41 0f 5c d1"},
    {"mulps xmm10,XMMWORD PTR [rsp+0x10]", [](Assembler& a) { a.mulps(Xmm::x10, Mem::at(Gp::rsp, 16)); },
     "44 0f 59 54 24 10"},
    {"divps xmm1,XMMWORD PTR [rbp+0x0]", [](Assembler& a) { a.divps(Xmm::x1, Mem::at(Gp::rbp)); }, "0f 5e 4d 00"},
    {"minps xmm4,XMMWORD PTR [r12+0x200]", [](Assembler& a) { a.minps(Xmm::x4, Mem::at(Gp::r12, 0x200)); },
     "41 0f 5d a4 24 00 02 00 00"},
    {"maxps xmm5,XMMWORD PTR [r13-0x8]", [](Assembler& a) { a.maxps(Xmm::x5, Mem::at(Gp::r13, -8)); },
     "41 0f 5f 6d f8"},
    {"sqrtps xmm6,xmm7", [](Assembler& a) { a.sqrtps(Xmm::x6, Xmm::x7); }, "0f 51 f7"},
    {"andps xmm0,XMMWORD PTR [rdi+rcx*4+0xc]", [](Assembler& a) { a.andps(Xmm::x0, Mem::at(Gp::rdi, Gp::rcx, 4, 12)); },
     "0f 54 44 8f 0c"},
    {"andnps xmm11,XMMWORD PTR [r8+r9*8-0x1000]",
     [](Assembler& a) { a.andnps(Xmm::x11, Mem::at(Gp::r8, Gp::r9, 8, -0x1000)); }, "47 0f 55 9c c8 00 f0 ff ff"},
    {"orps xmm12,XMMWORD PTR [rbx+r10*1]", [](Assembler& a) { a.orps(Xmm::x12, Mem::at(Gp::rbx, Gp::r10, 1)); },
     "46 0f 56 24 13"},
    {"xorps xmm13,XMMWORD PTR [r13+rax*2+0x0]", [](Assembler& a) { a.xorps(Xmm::x13, Mem::at(Gp::r13, Gp::rax, 2)); },
     "45 0f 57 6c 45 00"},
    {"addss xmm0,xmm1", [](Assembler& a) { a.addss(Xmm::x0, Xmm::x1); }, "f3 0f 58 c1"},
    {"subss xmm14,DWORD PTR [rsi+0x4]", [](Assembler& a) { a.subss(Xmm::x14, Mem::at(Gp::rsi, 4)); },
     "f3 44 0f 5c 76 04"},
    {"mulss xmm1,xmm2", [](Assembler& a) { a.mulss(Xmm::x1, Xmm::x2); }, "f3 0f 59 ca"},
    {"divss xmm9,xmm1", [](Assembler& a) { a.divss(Xmm::x9, Xmm::x1); }, "f3 44 0f 5e c9"},
    {"minss xmm2,xmm3", [](Assembler& a) { a.minss(Xmm::x2, Xmm::x3); }, "f3 0f 5d d3"},
    {"maxss xmm4,DWORD PTR [rdx]", [](Assembler& a) { a.maxss(Xmm::x4, Mem::at(Gp::rdx)); }, "f3 0f 5f 22"},
    {"sqrtss xmm15,xmm15", [](Assembler& a) { a.sqrtss(Xmm::x15, Xmm::x15); }, "f3 45 0f 51 ff"},
    {"blendvps xmm3,xmm4,xmm0", [](Assembler& a) { a.blendvps(Xmm::x3, Xmm::x4); }, "66 0f 38 14 dc"},
    {"blendvps xmm9,XMMWORD PTR [r15+0x20],xmm0", [](Assembler& a) { a.blendvps(Xmm::x9, Mem::at(Gp::r15, 32)); },
     "66 45 0f 38 14 4f 20"},
    {"cvtdq2ps xmm1,xmm2", [](Assembler& a) { a.cvtdq2ps(Xmm::x1, Xmm::x2); }, "0f 5b ca"},
    {"cvttps2dq xmm3,xmm12", [](Assembler& a) { a.cvttps2dq(Xmm::x3, Xmm::x12); }, "f3 41 0f 5b dc"},
    {"cvtps2dq xmm8,xmm0", [](Assembler& a) { a.cvtps2dq(Xmm::x8, Xmm::x0); }, "66 44 0f 5b c0"},
    {"pand xmm1,xmm2", [](Assembler& a) { a.pand(Xmm::x1, Xmm::x2); }, "66 0f db ca"},
    {"pandn xmm1,XMMWORD PTR [rax+0x10]", [](Assembler& a) { a.pandn(Xmm::x1, Mem::at(Gp::rax, 16)); },
     "66 0f df 48 10"},
    {"por xmm10,xmm2", [](Assembler& a) { a.por(Xmm::x10, Xmm::x2); }, "66 44 0f eb d2"},
    {"pxor xmm7,xmm7", [](Assembler& a) { a.pxor(Xmm::x7, Xmm::x7); }, "66 0f ef ff"},
    {"cvtps2pd xmm1,xmm2", [](Assembler& a) { a.cvtps2pd(Xmm::x1, Xmm::x2); }, "0f 5a ca"},
    {"cvtps2pd xmm9,xmm12", [](Assembler& a) { a.cvtps2pd(Xmm::x9, Xmm::x12); }, "45 0f 5a cc"},
    {"cvtpd2ps xmm3,xmm4", [](Assembler& a) { a.cvtpd2ps(Xmm::x3, Xmm::x4); }, "66 0f 5a dc"},
    {"cvtpd2ps xmm10,xmm1", [](Assembler& a) { a.cvtpd2ps(Xmm::x10, Xmm::x1); }, "66 44 0f 5a d1"},
    {"mulpd xmm1,XMMWORD PTR [rsp+0x20]", [](Assembler& a) { a.mulpd(Xmm::x1, Mem::at(Gp::rsp, 32)); },
     "66 0f 59 4c 24 20"},
    {"mulpd xmm8,xmm9", [](Assembler& a) { a.mulpd(Xmm::x8, Xmm::x9); }, "66 45 0f 59 c1"},
    {"addpd xmm2,xmm3", [](Assembler& a) { a.addpd(Xmm::x2, Xmm::x3); }, "66 0f 58 d3"},
    {"subpd xmm11,xmm2", [](Assembler& a) { a.subpd(Xmm::x11, Xmm::x2); }, "66 44 0f 5c da"},
    {"cvttpd2dq xmm5,xmm6", [](Assembler& a) { a.cvttpd2dq(Xmm::x5, Xmm::x6); }, "66 0f e6 ee"},
    {"cvttpd2dq xmm13,xmm14", [](Assembler& a) { a.cvttpd2dq(Xmm::x13, Xmm::x14); }, "66 45 0f e6 ee"},
    {"movhlps xmm1,xmm2", [](Assembler& a) { a.movhlps(Xmm::x1, Xmm::x2); }, "0f 12 ca"},
    {"movhlps xmm9,xmm10", [](Assembler& a) { a.movhlps(Xmm::x9, Xmm::x10); }, "45 0f 12 ca"},
    {"movlhps xmm3,xmm4", [](Assembler& a) { a.movlhps(Xmm::x3, Xmm::x4); }, "0f 16 dc"},
    {"movlhps xmm12,xmm1", [](Assembler& a) { a.movlhps(Xmm::x12, Xmm::x1); }, "44 0f 16 e1"},
    {"punpcklqdq xmm5,xmm6", [](Assembler& a) { a.punpcklqdq(Xmm::x5, Xmm::x6); }, "66 0f 6c ee"},
    {"punpcklqdq xmm15,xmm0", [](Assembler& a) { a.punpcklqdq(Xmm::x15, Xmm::x0); }, "66 44 0f 6c f8"},
    {"pcmpgtd xmm3,XMMWORD PTR [rsp+0x70]", [](Assembler& a) { a.pcmpgtd(Xmm::x3, Mem::at(Gp::rsp, 112)); },
     "66 0f 66 5c 24 70"},
    {"pcmpgtd xmm9,xmm1", [](Assembler& a) { a.pcmpgtd(Xmm::x9, Xmm::x1); }, "66 44 0f 66 c9"},
    {"pcmpeqd xmm6,xmm6", [](Assembler& a) { a.pcmpeqd(Xmm::x6, Xmm::x6); }, "66 0f 76 f6"},
    {"paddd xmm1,xmm14", [](Assembler& a) { a.paddd(Xmm::x1, Xmm::x14); }, "66 41 0f fe ce"},
    {"psubd xmm1,xmm2", [](Assembler& a) { a.psubd(Xmm::x1, Xmm::x2); }, "66 0f fa ca"},
    {"ucomiss xmm0,xmm1", [](Assembler& a) { a.ucomiss(Xmm::x0, Xmm::x1); }, "0f 2e c1"},
    // VEX.128: the 2-byte prefix where no X/B bit is needed, else the 3-byte one (as GNU as picks).
    {"vaddps xmm0,xmm1,xmm2", [](Assembler& a) { a.vaddps(Xmm::x0, Xmm::x1, Xmm::x2); }, "c5 f0 58 c2"},
    {"vsubps xmm9,xmm2,xmm15", [](Assembler& a) { a.vsubps(Xmm::x9, Xmm::x2, Xmm::x15); }, "c4 41 68 5c cf"},
    {"vmulps xmm3,xmm12,xmm4", [](Assembler& a) { a.vmulps(Xmm::x3, Xmm::x12, Xmm::x4); }, "c5 98 59 dc"},
    {"vdivps xmm1,xmm2,XMMWORD PTR [rsp+0x10]", [](Assembler& a) { a.vdivps(Xmm::x1, Xmm::x2, Mem::at(Gp::rsp, 16)); },
     "c5 e8 5e 4c 24 10"},
    {"vminps xmm11,xmm3,XMMWORD PTR [r12+0x200]",
     [](Assembler& a) { a.vminps(Xmm::x11, Xmm::x3, Mem::at(Gp::r12, 0x200)); }, "c4 41 60 5d 9c 24 00 02 00 00"},
    {"vmaxps xmm5,xmm14,XMMWORD PTR [r8+r9*8-0x1000]",
     [](Assembler& a) { a.vmaxps(Xmm::x5, Xmm::x14, Mem::at(Gp::r8, Gp::r9, 8, -0x1000)); },
     "c4 81 08 5f ac c8 00 f0 ff ff"},
    {"vandps xmm2,xmm3,XMMWORD PTR [rax]", [](Assembler& a) { a.vandps(Xmm::x2, Xmm::x3, Mem::at(Gp::rax)); },
     "c5 e0 54 10"},
    {"vaddps xmm8,xmm8,xmm8", [](Assembler& a) { a.vaddps(Xmm::x8, Xmm::x8, Xmm::x8); }, "c4 41 38 58 c0"},
    {"vxorps xmm7,xmm6,XMMWORD PTR [rax+rbx*2+0x4]",
     [](Assembler& a) { a.vxorps(Xmm::x7, Xmm::x6, Mem::at(Gp::rax, Gp::rbx, 2, 4)); }, "c5 c8 57 7c 58 04"},
    {"cmpeqps xmm1,xmm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Eq); }, "0f c2 ca 00"},
    {"cmpltps xmm1,xmm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Lt); }, "0f c2 ca 01"},
    {"cmpleps xmm9,xmm2", [](Assembler& a) { a.cmpps(Xmm::x9, Xmm::x2, Pred::Le); }, "44 0f c2 ca 02"},
    {"cmpunordps xmm1,xmm10", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x10, Pred::Unord); }, "41 0f c2 ca 03"},
    {"cmpneqps xmm1,XMMWORD PTR [rcx+0x40]", [](Assembler& a) { a.cmpps(Xmm::x1, Mem::at(Gp::rcx, 64), Pred::Neq); },
     "0f c2 49 40 04"},
    {"cmpnltps xmm1,xmm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Nlt); }, "0f c2 ca 05"},
    {"cmpnleps xmm1,xmm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Nle); }, "0f c2 ca 06"},
    {"cmpordps xmm1,xmm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Ord); }, "0f c2 ca 07"},
    {"cmpltss xmm3,xmm4", [](Assembler& a) { a.cmpss(Xmm::x3, Xmm::x4, Pred::Lt); }, "f3 0f c2 dc 01"},
    {"roundps xmm1,xmm2,0x9", [](Assembler& a) { a.roundps(Xmm::x1, Xmm::x2, Rounding::Down); }, "66 0f 3a 08 ca 09"},
    {"roundps xmm9,xmm10,0xa", [](Assembler& a) { a.roundps(Xmm::x9, Xmm::x10, Rounding::Up); },
     "66 45 0f 3a 08 ca 0a"},
    {"roundss xmm1,xmm2,0xb", [](Assembler& a) { a.roundss(Xmm::x1, Xmm::x2, Rounding::Truncate); },
     "66 0f 3a 0a ca 0b"},
    {"shufps xmm1,xmm1,0x0", [](Assembler& a) { a.shufps(Xmm::x1, Xmm::x1, 0); }, "0f c6 c9 00"},
    {"pslld xmm2,0x1f", [](Assembler& a) { a.pslld(Xmm::x2, 31); }, "66 0f 72 f2 1f"},
    {"psrld xmm11,0x1", [](Assembler& a) { a.psrld(Xmm::x11, 1); }, "66 41 0f 72 d3 01"},
    {"psrad xmm3,0x1f", [](Assembler& a) { a.psrad(Xmm::x3, 31); }, "66 0f 72 e3 1f"},
    {"movaps xmm0,xmm8", [](Assembler& a) { a.movaps(Xmm::x0, Xmm::x8); }, "41 0f 28 c0"},
    {"movaps xmm1,XMMWORD PTR [rsp]", [](Assembler& a) { a.movaps(Xmm::x1, Mem::at(Gp::rsp)); }, "0f 28 0c 24"},
    {"movaps XMMWORD PTR [rsp+0x80],xmm9", [](Assembler& a) { a.movaps(Mem::at(Gp::rsp, 0x80), Xmm::x9); },
     "44 0f 29 8c 24 80 00 00 00"},
    {"movups xmm2,XMMWORD PTR [rsi+rax*4]", [](Assembler& a) { a.movups(Xmm::x2, Mem::at(Gp::rsi, Gp::rax, 4)); },
     "0f 10 14 86"},
    {"movups XMMWORD PTR [r11+r14*4+0x4],xmm12",
     [](Assembler& a) { a.movups(Mem::at(Gp::r11, Gp::r14, 4, 4), Xmm::x12); }, "47 0f 11 64 b3 04"},
    {"movss xmm5,DWORD PTR [rdi]", [](Assembler& a) { a.movss(Xmm::x5, Mem::at(Gp::rdi)); }, "f3 0f 10 2f"},
    {"movss DWORD PTR [r9+0x8],xmm10", [](Assembler& a) { a.movss(Mem::at(Gp::r9, 8), Xmm::x10); },
     "f3 45 0f 11 51 08"},
    {"movd xmm1,eax", [](Assembler& a) { a.movd(Xmm::x1, Gp::rax); }, "66 0f 6e c8"},
    {"movd r10d,xmm9", [](Assembler& a) { a.movd(Gp::r10, Xmm::x9); }, "66 45 0f 7e ca"},
    {"movmskps eax,xmm1", [](Assembler& a) { a.movmskps(Gp::rax, Xmm::x1); }, "0f 50 c1"},
    {"movmskps r9d,xmm12", [](Assembler& a) { a.movmskps(Gp::r9, Xmm::x12); }, "45 0f 50 cc"},
    {"cvtsi2ss xmm1,rax", [](Assembler& a) { a.cvtsi2ss(Xmm::x1, Gp::rax); }, "f3 48 0f 2a c8"},
    {"cvttss2si r8,xmm2", [](Assembler& a) { a.cvttss2si(Gp::r8, Xmm::x2); }, "f3 4c 0f 2c c2"},
    {"mov rax,rbx", [](Assembler& a) { a.mov(Gp::rax, Gp::rbx); }, "48 89 d8"},
    {"mov r12,rsp", [](Assembler& a) { a.mov(Gp::r12, Gp::rsp); }, "49 89 e4"},
    {"mov rcx,QWORD PTR [rdi+0x8]", [](Assembler& a) { a.mov(Gp::rcx, Mem::at(Gp::rdi, 8)); }, "48 8b 4f 08"},
    {"mov QWORD PTR [rsp+0x18],r15", [](Assembler& a) { a.mov(Mem::at(Gp::rsp, 24), Gp::r15); }, "4c 89 7c 24 18"},
    {"mov edx,DWORD PTR [rbp-0x4]", [](Assembler& a) { a.mov32(Gp::rdx, Mem::at(Gp::rbp, -4)); }, "8b 55 fc"},
    {"mov DWORD PTR [r13+0x0],r8d", [](Assembler& a) { a.mov32(Mem::at(Gp::r13), Gp::r8); }, "45 89 45 00"},
    {"mov eax,0x2a", [](Assembler& a) { a.mov_imm(Gp::rax, 42); }, "b8 2a 00 00 00"},
    {"mov r11d,0x12345678", [](Assembler& a) { a.mov_imm(Gp::r11, 0x12345678); }, "41 bb 78 56 34 12"},
    {"movabs rcx,0x1122334455667788", [](Assembler& a) { a.mov_imm(Gp::rcx, 0x1122334455667788ull); },
     "48 b9 88 77 66 55 44 33 22 11"},
    {"lea rsi,[rsi+rcx*4]", [](Assembler& a) { a.lea(Gp::rsi, Mem::at(Gp::rsi, Gp::rcx, 4)); }, "48 8d 34 8e"},
    {"lea r14,[rsp+0x100]", [](Assembler& a) { a.lea(Gp::r14, Mem::at(Gp::rsp, 0x100)); }, "4c 8d b4 24 00 01 00 00"},
    {"add rax,rcx", [](Assembler& a) { a.add(Gp::rax, Gp::rcx); }, "48 01 c8"},
    {"sub r8,r9", [](Assembler& a) { a.sub(Gp::r8, Gp::r9); }, "4d 29 c8"},
    {"cmp rdi,rsi", [](Assembler& a) { a.cmp(Gp::rdi, Gp::rsi); }, "48 39 f7"},
    {"test rax,rax", [](Assembler& a) { a.test(Gp::rax, Gp::rax); }, "48 85 c0"},
    {"imul rdx,r10", [](Assembler& a) { a.imul(Gp::rdx, Gp::r10); }, "49 0f af d2"},
    {"add rsp,0x8", [](Assembler& a) { a.add(Gp::rsp, 8); }, "48 83 c4 08"},
    {"sub rsp,0x1000", [](Assembler& a) { a.sub(Gp::rsp, 0x1000); }, "48 81 ec 00 10 00 00"},
    {"cmp r12,0xffffffffffffffff", [](Assembler& a) { a.cmp(Gp::r12, -1); }, "49 83 fc ff"},
    {"add QWORD PTR [rdi+0x10],0x1", [](Assembler& a) { a.add(Mem::at(Gp::rdi, 16), 1); }, "48 83 47 10 01"},
    {"sub QWORD PTR [rax],0x3e8", [](Assembler& a) { a.sub(Mem::at(Gp::rax), 1000); }, "48 81 28 e8 03 00 00"},
    {"cmp QWORD PTR [rsp+0x8],0x0", [](Assembler& a) { a.cmp(Mem::at(Gp::rsp, 8), 0); }, "48 83 7c 24 08 00"},
    {"cmp BYTE PTR [rax],0x0", [](Assembler& a) { a.cmp8(Mem::at(Gp::rax), 0); }, "80 38 00"},
    {"cmp BYTE PTR [r13+0x1],0x7f", [](Assembler& a) { a.cmp8(Mem::at(Gp::r13, 1), 0x7f); }, "41 80 7d 01 7f"},
    {"push rbx", [](Assembler& a) { a.push(Gp::rbx); }, "53"},
    {"push r15", [](Assembler& a) { a.push(Gp::r15); }, "41 57"},
    {"pop rbp", [](Assembler& a) { a.pop(Gp::rbp); }, "5d"},
    {"pop r12", [](Assembler& a) { a.pop(Gp::r12); }, "41 5c"},
    {"call rax", [](Assembler& a) { a.call(Gp::rax); }, "ff d0"},
    {"call r11", [](Assembler& a) { a.call(Gp::r11); }, "41 ff d3"},
    {"call QWORD PTR [rbx+0x8]", [](Assembler& a) { a.call(Mem::at(Gp::rbx, 8)); }, "ff 53 08"},
    {"ret", [](Assembler& a) { a.ret(); }, "c3"},
    {"vbroadcastss xmm3,DWORD PTR [rax]", [](Assembler& a) { a.vbroadcastss(Xmm::x3, Mem::at(Gp::rax)); },
     "c4 e2 79 18 18"},
};

// Wide mode (Assembler::enable_wide): the packed single forms as VEX.256 on ymm registers, d = d op s;
// the double, integer and conversion forms of the inline sin/cos.
const Row kWideRows[] = {
    {"vaddps ymm0,ymm0,ymm1", [](Assembler& a) { a.addps(Xmm::x0, Xmm::x1); }, "c5 fc 58 c1"},
    {"vaddps ymm8,ymm8,ymm15", [](Assembler& a) { a.addps(Xmm::x8, Xmm::x15); }, "c4 41 3c 58 c7"},
    {"vsubps ymm3,ymm3,YMMWORD PTR [rsp+0x20]", [](Assembler& a) { a.subps(Xmm::x3, Mem::at(Gp::rsp, 32)); },
     "c5 e4 5c 5c 24 20"},
    {"vmulps ymm2,ymm2,YMMWORD PTR [rdx]", [](Assembler& a) { a.mulps(Xmm::x2, Mem::at(Gp::rdx)); }, "c5 ec 59 12"},
    {"vdivps ymm9,ymm9,ymm2", [](Assembler& a) { a.divps(Xmm::x9, Xmm::x2); }, "c5 34 5e ca"},
    {"vminps ymm4,ymm4,YMMWORD PTR [r12+0x200]", [](Assembler& a) { a.minps(Xmm::x4, Mem::at(Gp::r12, 0x200)); },
     "c4 c1 5c 5d a4 24 00 02 00 00"},
    {"vmaxps ymm5,ymm5,YMMWORD PTR [r8+r9*8-0x1000]",
     [](Assembler& a) { a.maxps(Xmm::x5, Mem::at(Gp::r8, Gp::r9, 8, -0x1000)); }, "c4 81 54 5f ac c8 00 f0 ff ff"},
    {"vsqrtps ymm6,ymm7", [](Assembler& a) { a.sqrtps(Xmm::x6, Xmm::x7); }, "c5 fc 51 f7"},
    {"vsqrtps ymm10,YMMWORD PTR [rax]", [](Assembler& a) { a.sqrtps(Xmm::x10, Mem::at(Gp::rax)); }, "c5 7c 51 10"},
    {"vandps ymm0,ymm0,ymm1", [](Assembler& a) { a.andps(Xmm::x0, Xmm::x1); }, "c5 fc 54 c1"},
    {"vandnps ymm11,ymm11,ymm3", [](Assembler& a) { a.andnps(Xmm::x11, Xmm::x3); }, "c5 24 55 db"},
    {"vorps ymm1,ymm1,ymm13", [](Assembler& a) { a.orps(Xmm::x1, Xmm::x13); }, "c4 c1 74 56 cd"},
    {"vxorps ymm13,ymm13,YMMWORD PTR [r13+rax*2+0x0]",
     [](Assembler& a) { a.xorps(Xmm::x13, Mem::at(Gp::r13, Gp::rax, 2)); }, "c4 41 14 57 6c 45 00"},
    {"vblendvps ymm3,ymm3,ymm4,ymm0", [](Assembler& a) { a.blendvps(Xmm::x3, Xmm::x4); }, "c4 e3 65 4a dc 00"},
    {"vblendvps ymm9,ymm9,YMMWORD PTR [r15+0x20],ymm0", [](Assembler& a) { a.blendvps(Xmm::x9, Mem::at(Gp::r15, 32)); },
     "c4 43 35 4a 4f 20 00"},
    {"vcmpltps ymm1,ymm1,ymm2", [](Assembler& a) { a.cmpps(Xmm::x1, Xmm::x2, Pred::Lt); }, "c5 f4 c2 ca 01"},
    {"vcmpunordps ymm9,ymm9,ymm10", [](Assembler& a) { a.cmpps(Xmm::x9, Xmm::x10, Pred::Unord); }, "c4 41 34 c2 ca 03"},
    {"vcmpneqps ymm1,ymm1,YMMWORD PTR [rcx+0x40]",
     [](Assembler& a) { a.cmpps(Xmm::x1, Mem::at(Gp::rcx, 64), Pred::Neq); }, "c5 f4 c2 49 40 04"},
    {"vroundps ymm1,ymm2,0x9", [](Assembler& a) { a.roundps(Xmm::x1, Xmm::x2, Rounding::Down); }, "c4 e3 7d 08 ca 09"},
    {"vroundps ymm9,ymm10,0xa", [](Assembler& a) { a.roundps(Xmm::x9, Xmm::x10, Rounding::Up); }, "c4 43 7d 08 ca 0a"},
    {"vmovaps ymm8,ymm0", [](Assembler& a) { a.movaps(Xmm::x8, Xmm::x0); }, "c5 7c 28 c0"},
    {"vmovaps ymm1,YMMWORD PTR [rsp]", [](Assembler& a) { a.movaps(Xmm::x1, Mem::at(Gp::rsp)); }, "c5 fc 28 0c 24"},
    {"vmovaps YMMWORD PTR [rsp+0x80],ymm9", [](Assembler& a) { a.movaps(Mem::at(Gp::rsp, 0x80), Xmm::x9); },
     "c5 7c 29 8c 24 80 00 00 00"},
    {"vmovups ymm2,YMMWORD PTR [rsi+rax*4]", [](Assembler& a) { a.movups(Xmm::x2, Mem::at(Gp::rsi, Gp::rax, 4)); },
     "c5 fc 10 14 86"},
    {"vmovups YMMWORD PTR [r11+r14*4+0x4],ymm12",
     [](Assembler& a) { a.movups(Mem::at(Gp::r11, Gp::r14, 4, 4), Xmm::x12); }, "c4 01 7c 11 64 b3 04"},
    {"vaddps ymm1,ymm2,ymm3", [](Assembler& a) { a.vaddps(Xmm::x1, Xmm::x2, Xmm::x3); }, "c5 ec 58 cb"},
    {"vxorps ymm7,ymm6,YMMWORD PTR [rax+rbx*2+0x4]",
     [](Assembler& a) { a.vxorps(Xmm::x7, Xmm::x6, Mem::at(Gp::rax, Gp::rbx, 2, 4)); }, "c5 cc 57 7c 58 04"},
    {"vbroadcastss ymm3,DWORD PTR [rax]", [](Assembler& a) { a.vbroadcastss(Xmm::x3, Mem::at(Gp::rax)); },
     "c4 e2 7d 18 18"},
    {"vbroadcastss ymm12,DWORD PTR [r13+0x8]", [](Assembler& a) { a.vbroadcastss(Xmm::x12, Mem::at(Gp::r13, 8)); },
     "c4 42 7d 18 65 08"},
    {"vzeroupper", [](Assembler& a) { a.vzeroupper(); }, "c5 f8 77"},
    {"and rsp,0xffffffffffffffe0", [](Assembler& a) { a.and_(Gp::rsp, -32); }, "48 83 e4 e0"},
    {"and r10,0x100", [](Assembler& a) { a.and_(Gp::r10, 0x100); }, "49 81 e2 00 01 00 00"},
    {"vaddpd ymm1,ymm1,ymm2", [](Assembler& a) { a.addpd(Xmm::x1, Xmm::x2); }, "c5 f5 58 ca"},
    {"vsubpd ymm9,ymm9,YMMWORD PTR [rsp+0x40]", [](Assembler& a) { a.subpd(Xmm::x9, Mem::at(Gp::rsp, 64)); },
     "c5 35 5c 4c 24 40"},
    {"vmulpd ymm3,ymm3,YMMWORD PTR [rax+0x20]", [](Assembler& a) { a.mulpd(Xmm::x3, Mem::at(Gp::rax, 32)); },
     "c5 e5 59 58 20"},
    {"vpand ymm1,ymm1,ymm10", [](Assembler& a) { a.pand(Xmm::x1, Xmm::x10); }, "c4 c1 75 db ca"},
    {"vpcmpeqd ymm0,ymm0,YMMWORD PTR [rdx]", [](Assembler& a) { a.pcmpeqd(Xmm::x0, Mem::at(Gp::rdx)); }, "c5 fd 76 02"},
    {"vpaddd ymm12,ymm12,ymm3", [](Assembler& a) { a.paddd(Xmm::x12, Xmm::x3); }, "c5 1d fe e3"},
    {"vpslld ymm1,ymm1,0x1e", [](Assembler& a) { a.pslld(Xmm::x1, 30); }, "c5 f5 72 f1 1e"},
    {"vpslld ymm11,ymm11,0x1f", [](Assembler& a) { a.pslld(Xmm::x11, 31); }, "c4 c1 25 72 f3 1f"},
    {"vmovmskps eax,ymm0", [](Assembler& a) { a.movmskps(Gp::rax, Xmm::x0); }, "c5 fc 50 c0"},
    {"vmovmskps r9d,ymm12", [](Assembler& a) { a.movmskps(Gp::r9, Xmm::x12); }, "c4 41 7c 50 cc"},
    {"vcvtps2pd ymm2,xmm1", [](Assembler& a) { a.cvtps2pd(Xmm::x2, Xmm::x1); }, "c5 fc 5a d1"},
    {"vcvtps2pd ymm10,xmm13", [](Assembler& a) { a.cvtps2pd(Xmm::x10, Xmm::x13); }, "c4 41 7c 5a d5"},
    {"vcvtpd2ps xmm3,ymm4", [](Assembler& a) { a.cvtpd2ps(Xmm::x3, Xmm::x4); }, "c5 fd 5a dc"},
    {"vcvtpd2ps xmm11,ymm2", [](Assembler& a) { a.cvtpd2ps(Xmm::x11, Xmm::x2); }, "c5 7d 5a da"},
    {"vcvttpd2dq xmm5,ymm6", [](Assembler& a) { a.cvttpd2dq(Xmm::x5, Xmm::x6); }, "c5 fd e6 ee"},
    {"vcvttpd2dq xmm13,ymm14", [](Assembler& a) { a.cvttpd2dq(Xmm::x13, Xmm::x14); }, "c4 41 7d e6 ee"},
    {"vextractf128 xmm1,ymm2,0x1", [](Assembler& a) { a.vextractf128(Xmm::x1, Xmm::x2, 1); }, "c4 e3 7d 19 d1 01"},
    {"vextractf128 xmm9,ymm12,0x1", [](Assembler& a) { a.vextractf128(Xmm::x9, Xmm::x12, 1); }, "c4 43 7d 19 e1 01"},
    {"vinsertf128 ymm3,ymm3,xmm4,0x1", [](Assembler& a) { a.vinsertf128(Xmm::x3, Xmm::x3, Xmm::x4, 1); },
     "c4 e3 65 18 dc 01"},
    {"vinsertf128 ymm10,ymm2,xmm11,0x1", [](Assembler& a) { a.vinsertf128(Xmm::x10, Xmm::x2, Xmm::x11, 1); },
     "c4 43 6d 18 d3 01"},
};

std::string hex(const std::vector<uint8_t>& b) {
  std::string s;
  char buf[4];
  for (size_t i = 0; i < b.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%s%02x", i ? " " : "", b[i]);
    s += buf;
  }
  return s;
}

std::string collapse(const std::string& s) {
  std::istringstream in(s);
  std::string word, out;
  while (in >> word) out += (out.empty() ? "" : " ") + word;
  return out;
}

}  // namespace

TEST_CASE("x86: every instruction form encodes to the bytes of the reference assembler") {
  for (const auto& row : kRows) {
    Assembler a;
    row.emit(a);
    INFO(row.text);
    CHECK(hex(a.bytes()) == row.bytes);
  }
  for (const auto& row : kWideRows) {
    Assembler a;
    a.enable_wide();
    row.emit(a);
    INFO(row.text);
    CHECK(hex(a.bytes()) == row.bytes);
    CHECK(a.wide_refused().empty());
  }
}

TEST_CASE("x86: wide mode refuses what has no eight-lane form, and its constants are 32 bytes") {
  Assembler a;
  a.enable_wide();
  a.addps(Xmm::x1, Xmm::x2);
  CHECK(a.wide_refused().empty());
  a.cvtps2pd(Xmm::x1, Xmm::x2);  // four floats to four doubles: a wide form
  CHECK(a.wide_refused().empty());
  a.movhlps(Xmm::x1, Xmm::x2);  // the two-lane moves of the four-lane sin/cos: none
  a.movss(Xmm::x1, Mem::at(Gp::rax));
  CHECK(a.wide_refused() == "movhlps");  // the first one
  Assembler w;
  w.enable_wide();
  w.enable_listing();
  w.movaps(Xmm::x3, Mem::rip(w.constant_ps(2.5f)));
  std::vector<uint8_t> code = w.finish();
  REQUIRE(code.size() == 32 + 32);  // the load padded to 32 bytes, then one constant of eight lanes
  float lanes[8];
  std::memcpy(lanes, code.data() + 32, 32);
  for (float f : lanes) CHECK(f == 2.5f);
  CHECK(w.listing().find("vmovaps ymm3, [rip+L0]") != std::string::npos);
  CHECK(w.listing().find(".float 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5, 2.5") != std::string::npos);
}

TEST_CASE("x86: objdump decodes the encoder's bytes back to the same instructions") {
  if (std::system("command -v objdump > /dev/null 2>&1") != 0) {
    fscript::test::skip(fscript::test::SkipKind::Missing, "objdump is not installed (Debian binutils): no cross-check");
    return;
  }
  Assembler a, w;
  for (const auto& row : kRows) row.emit(a);
  w.enable_wide();
  for (const auto& row : kWideRows) row.emit(w);
  std::vector<uint8_t> bytes = a.bytes();
  bytes.insert(bytes.end(), w.bytes().begin(), w.bytes().end());
  char path[] = "/tmp/fs_x86_XXXXXX";
  int fd = mkstemp(path);
  REQUIRE(fd >= 0);
  close(fd);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  std::string cmd = std::string("objdump -D -b binary -m i386:x86-64 -M intel ") + path;
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p);
  std::vector<std::string> texts;
  char line[512];
  while (std::fgets(line, sizeof line, p)) {
    std::string l = line;
    size_t tab1 = l.find('\t'), tab2 = tab1 == std::string::npos ? tab1 : l.find('\t', tab1 + 1);
    if (tab2 != std::string::npos) texts.push_back(collapse(l.substr(tab2 + 1)));
  }
  pclose(p);
  std::remove(path);
  REQUIRE(texts.size() == std::size(kRows) + std::size(kWideRows));
  for (size_t i = 0; i < texts.size(); ++i) {
    INFO("row " << i);
    CHECK(texts[i] == (i < std::size(kRows) ? kRows[i].text : kWideRows[i - std::size(kRows)].text));
  }
}

TEST_CASE("x86: jumps to labels bound before and after, rip-relative constants after the code") {
  Assembler a;
  Label top = a.new_label(), out = a.new_label();
  a.bind(top);
  a.jcc(Cond::E, out);           // 0: 0f 84 rel32 -> 11
  a.jmp(top);                    // 6: e9 rel32 -> 0
  a.bind(out);
  a.movaps(Xmm::x1, Mem::rip(a.constant_ps(2.0f)));  // 11: 0f 28 0d rel32 -> 32 (after the padding)
  a.ret();                       // 18
  auto code = a.finish();
  REQUIRE(code.size() == 32 + 16);  // padded to 16, then the pool
  CHECK(hex({code.begin(), code.begin() + 19}) == "0f 84 05 00 00 00 e9 f5 ff ff ff 0f 28 0d 0e 00 00 00 c3");
  CHECK(hex({code.begin() + 32, code.end()}) == "00 00 00 40 00 00 00 40 00 00 00 40 00 00 00 40");
  Assembler b;
  CHECK(b.constant_ps(1.0f).id == b.constant_ps(1.0f).id);  // the pool is deduplicated
}

TEST_CASE("x86: code runs from W^X memory: (a + b) * 2 on four lanes") {
  Assembler a;
  // System V: rdi = a, rsi = b, rdx = out.
  a.movups(Xmm::x0, Mem::at(Gp::rdi));
  a.movups(Xmm::x9, Mem::at(Gp::rsi));
  a.addps(Xmm::x0, Xmm::x9);
  a.mulps(Xmm::x0, Mem::rip(a.constant_ps(2.0f)));
  a.movups(Mem::at(Gp::rdx), Xmm::x0);
  a.ret();
  std::string error;
  auto mem = CodeMemory::create(a.finish(), error);
  REQUIRE(mem);
  auto fn = reinterpret_cast<void (*)(const float*, const float*, float*)>(const_cast<uint8_t*>(mem->start()));
  float x[4] = {1, 2, 3, -4}, y[4] = {0.5f, 0, -3, 4}, out[4] = {};
  fn(x, y, out);
  CHECK(out[0] == 3.0f);
  CHECK(out[1] == 4.0f);
  CHECK(out[2] == 0.0f);
  CHECK(out[3] == 0.0f);
}

TEST_CASE("x86: the listing names every instruction, label and constant") {
  Assembler a;
  a.enable_listing();
  Label top = a.new_label();
  a.bind(top);
  a.cmpps(Xmm::x1, Mem::at(Gp::rsp, Gp::rax, 4, -16), Pred::Le);
  a.mulps(Xmm::x2, Mem::rip(a.constant_ps(0.5f)));
  a.jcc(Cond::NE, top);
  a.ret();
  a.finish();
  CHECK(a.listing() ==
        "L0:\n"
        "     0    cmpleps xmm1, [rsp+rax*4-16]\n"
        "     6    mulps xmm2, [rip+L1]\n"
        "     d    jne L0\n"
        "    13    ret\n"
        "L1:\n"
        "    20    .float 0.5, 0.5, 0.5, 0.5\n");
}
