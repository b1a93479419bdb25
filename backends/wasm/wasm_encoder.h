#pragma once
// A WebAssembly binary encoder: modules of imported memory and functions, our functions and their
// exports, written in the binary format (types, imports, functions, exports, code), with the
// instructions the emitter uses, SIMD's among them. Nothing here knows the IR.
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace fscript::wasm {

enum class ValType : uint8_t { I32 = 0x7f, I64 = 0x7e, F32 = 0x7d, F64 = 0x7c, V128 = 0x7b };

struct FuncType {
  std::vector<ValType> params, results;
  bool operator==(const FuncType& o) const { return params == o.params && results == o.results; }
};

// SIMD instructions (after the 0xfd prefix), the ones the emitter uses.
enum class Simd : uint32_t {
  V128Load = 0x00,
  V128Store = 0x0b,
  V128Const = 0x0c,
  I8x16Shuffle = 0x0d,  // then 16 lane indices
  I32x4Splat = 0x11,
  F32x4Splat = 0x13,
  F32x4ExtractLane = 0x1f,
  I32x4GtS = 0x3b,
  I32x4LeU = 0x3e,
  F32x4Eq = 0x41,
  F32x4Ne = 0x42,
  F32x4Lt = 0x43,
  F32x4Gt = 0x44,
  F32x4Le = 0x45,
  F32x4Ge = 0x46,
  V128Not = 0x4d,
  V128And = 0x4e,
  V128AndNot = 0x4f,
  V128Or = 0x50,
  V128Xor = 0x51,
  V128Bitselect = 0x52,
  V128AnyTrue = 0x53,
  F32x4DemoteF64x2Zero = 0x5e,
  F64x2PromoteLowF32x4 = 0x5f,
  F32x4Ceil = 0x67,
  F32x4Floor = 0x68,
  I32x4AllTrue = 0xa3,
  I32x4Shl = 0xab,
  I32x4ShrS = 0xac,
  I32x4ShrU = 0xad,
  I32x4Add = 0xae,
  I32x4Sub = 0xb1,
  I32x4MaxU = 0xb9,
  F32x4Sqrt = 0xe3,
  F32x4Add = 0xe4,
  F32x4Sub = 0xe5,
  F32x4Mul = 0xe6,
  F32x4Div = 0xe7,
  F32x4Pmin = 0xea,  // b < a ? b : a
  F32x4Pmax = 0xeb,  // a < b ? b : a
  F64x2Add = 0xf0,
  F64x2Sub = 0xf1,
  F64x2Mul = 0xf2,
};

// Scalar instructions (one byte).
enum class Opc : uint8_t {
  Unreachable = 0x00,
  Block = 0x02,
  Loop = 0x03,
  If = 0x04,
  Else = 0x05,
  End = 0x0b,
  Br = 0x0c,
  BrIf = 0x0d,
  Return = 0x0f,
  Call = 0x10,
  Drop = 0x1a,
  LocalGet = 0x20,
  LocalSet = 0x21,
  LocalTee = 0x22,
  GlobalGet = 0x23,
  I32Load = 0x28,
  I64Store = 0x37,
  I32Const = 0x41,
  I64Const = 0x42,
  I32Eqz = 0x45,
  I32GeU = 0x4f,
  I64Eqz = 0x50,
  I32Add = 0x6a,
  I32And = 0x71,
  I32Shl = 0x74,
};

// A function body: its instructions, appended in order.
class Code {
 public:
  void op(Opc o) { bytes_.push_back(static_cast<uint8_t>(o)); }
  void simd(Simd s);
  void u32(uint32_t v);  // LEB128
  void s32(int32_t v);
  void s64(int64_t v);
  void byte(uint8_t b) { bytes_.push_back(b); }

  void local_get(uint32_t i) { op(Opc::LocalGet), u32(i); }
  void local_set(uint32_t i) { op(Opc::LocalSet), u32(i); }
  void local_tee(uint32_t i) { op(Opc::LocalTee), u32(i); }
  void global_get(uint32_t i) { op(Opc::GlobalGet), u32(i); }
  void i32_const(int32_t v) { op(Opc::I32Const), s32(v); }
  void i64_const(int64_t v) { op(Opc::I64Const), s64(v); }
  void v128_const(const uint8_t bytes[16]);
  void f32x4_const(float v);  // the same float in every lane
  void i32x4_const(int32_t v);
  void f64x2_const(double v);
  // A vector of the 16 bytes picked from the two operands' 32 (0-15 the first's, 16-31 the second's).
  void i8x16_shuffle(const uint8_t lanes[16]);
  // Block instructions without results (0x40) or with one of `result`.
  void block() { op(Opc::Block), byte(0x40); }
  void loop() { op(Opc::Loop), byte(0x40); }
  void if_() { op(Opc::If), byte(0x40); }
  void end() { op(Opc::End); }
  void br(uint32_t depth) { op(Opc::Br), u32(depth); }
  void br_if(uint32_t depth) { op(Opc::BrIf), u32(depth); }
  void call(uint32_t f) { op(Opc::Call), u32(f); }
  void i32_load(uint32_t offset) { op(Opc::I32Load), u32(2), u32(offset); }  // aligned to 4
  void i64_store(uint32_t offset) { op(Opc::I64Store), u32(3), u32(offset); }  // aligned to 8
  void v128_load(uint32_t offset) { simd(Simd::V128Load), u32(4), u32(offset); }   // aligned to 16
  void v128_store(uint32_t offset) { simd(Simd::V128Store), u32(4), u32(offset); }
  // Unaligned forms, for arrays the caller owns (alignment is a hint: any address is valid).
  void v128_load_any(uint32_t offset) { simd(Simd::V128Load), u32(0), u32(offset); }
  void v128_store_any(uint32_t offset) { simd(Simd::V128Store), u32(0), u32(offset); }

  void append(const Code& more) { bytes_.insert(bytes_.end(), more.bytes_.begin(), more.bytes_.end()); }
  const std::vector<uint8_t>& bytes() const { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
};

class Module {
 public:
  uint32_t type(const FuncType& t);  // its index (the same type once)
  // Imports come before the module's own functions in the function index space: add them first.
  uint32_t import_function(const std::string& module, const std::string& name, const FuncType& t);
  void import_memory(const std::string& module, const std::string& name, uint32_t min_pages);
  // `locals`: runs of (count, type) after the parameters.
  uint32_t function(const FuncType& t, std::vector<std::pair<uint32_t, ValType>> locals, Code body);
  void export_function(const std::string& name, uint32_t index);
  // A mutable v128 global of these bytes, its index. The engine cannot take a mutable global's
  // value for a constant, so it keeps it in a register or a stack slot rather than rebuilding it.
  uint32_t global_v128(const std::array<uint8_t, 16>& bytes);
  std::vector<uint8_t> encode() const;

 private:
  struct Import {
    std::string module, name;
    bool memory;
    uint32_t index;  // type (function) or minimum pages (memory)
  };
  struct Function {
    uint32_t type;
    std::vector<std::pair<uint32_t, ValType>> locals;
    Code body;
  };
  std::vector<FuncType> types_;
  std::vector<Import> imports_;
  uint32_t imported_functions_ = 0;
  std::vector<Function> functions_;
  std::vector<std::pair<std::string, uint32_t>> exports_;
  std::vector<std::array<uint8_t, 16>> globals_;
};

}  // namespace fscript::wasm
