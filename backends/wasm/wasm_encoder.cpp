// The WebAssembly binary format (wasm_encoder.h): LEB128 numbers, sections sized by their
// contents, names as UTF-8 with their length.
#include "backends/wasm/wasm_encoder.h"

#include <cstring>

namespace fscript::wasm {
namespace {

void put_u32(std::vector<uint8_t>& out, uint32_t v) {
  do {
    uint8_t b = v & 0x7f;
    v >>= 7;
    out.push_back(static_cast<uint8_t>(b | (v ? 0x80 : 0)));
  } while (v);
}

void put_name(std::vector<uint8_t>& out, const std::string& s) {
  put_u32(out, static_cast<uint32_t>(s.size()));
  out.insert(out.end(), s.begin(), s.end());
}

void put_type(std::vector<uint8_t>& out, const FuncType& t) {
  out.push_back(0x60);
  put_u32(out, static_cast<uint32_t>(t.params.size()));
  for (ValType v : t.params) out.push_back(static_cast<uint8_t>(v));
  put_u32(out, static_cast<uint32_t>(t.results.size()));
  for (ValType v : t.results) out.push_back(static_cast<uint8_t>(v));
}

void section(std::vector<uint8_t>& out, uint8_t id, const std::vector<uint8_t>& body) {
  out.push_back(id);
  put_u32(out, static_cast<uint32_t>(body.size()));
  out.insert(out.end(), body.begin(), body.end());
}

}  // namespace

void Code::simd(Simd s) {
  bytes_.push_back(0xfd);
  u32(static_cast<uint32_t>(s));
}

void Code::u32(uint32_t v) { put_u32(bytes_, v); }

void Code::s64(int64_t v) {
  for (bool more = true; more;) {
    uint8_t b = v & 0x7f;
    v >>= 7;  // arithmetic: the sign stays
    more = !((v == 0 && !(b & 0x40)) || (v == -1 && (b & 0x40)));
    bytes_.push_back(static_cast<uint8_t>(b | (more ? 0x80 : 0)));
  }
}

void Code::s32(int32_t v) { s64(v); }

void Code::v128_const(const uint8_t bytes[16]) {
  simd(Simd::V128Const);
  bytes_.insert(bytes_.end(), bytes, bytes + 16);
}

void Code::f32x4_const(float v) {
  uint8_t b[16];
  for (int k = 0; k < 4; ++k) std::memcpy(b + 4 * k, &v, 4);
  v128_const(b);
}

void Code::i32x4_const(int32_t v) {
  uint8_t b[16];
  for (int k = 0; k < 4; ++k) std::memcpy(b + 4 * k, &v, 4);
  v128_const(b);
}

void Code::f64x2_const(double v) {
  uint8_t b[16];
  for (int k = 0; k < 2; ++k) std::memcpy(b + 8 * k, &v, 8);
  v128_const(b);
}

void Code::i8x16_shuffle(const uint8_t lanes[16]) {
  simd(Simd::I8x16Shuffle);
  bytes_.insert(bytes_.end(), lanes, lanes + 16);
}

uint32_t Module::type(const FuncType& t) {
  for (size_t i = 0; i < types_.size(); ++i)
    if (types_[i] == t) return static_cast<uint32_t>(i);
  types_.push_back(t);
  return static_cast<uint32_t>(types_.size() - 1);
}

uint32_t Module::import_function(const std::string& module, const std::string& name, const FuncType& t) {
  imports_.push_back({module, name, false, type(t)});
  return imported_functions_++;
}

void Module::import_memory(const std::string& module, const std::string& name, uint32_t min_pages) {
  imports_.push_back({module, name, true, min_pages});
}

uint32_t Module::function(const FuncType& t, std::vector<std::pair<uint32_t, ValType>> locals, Code body) {
  functions_.push_back({type(t), std::move(locals), std::move(body)});
  return imported_functions_ + static_cast<uint32_t>(functions_.size() - 1);
}

void Module::export_function(const std::string& name, uint32_t index) { exports_.emplace_back(name, index); }

uint32_t Module::global_v128(const std::array<uint8_t, 16>& bytes) {
  globals_.push_back(bytes);
  return static_cast<uint32_t>(globals_.size() - 1);
}

std::vector<uint8_t> Module::encode() const {
  std::vector<uint8_t> out = {0x00, 0x61, 0x73, 0x6d, 0x01, 0x00, 0x00, 0x00};
  std::vector<uint8_t> s;
  put_u32(s, static_cast<uint32_t>(types_.size()));
  for (const FuncType& t : types_) put_type(s, t);
  section(out, 1, s);
  s.clear();
  put_u32(s, static_cast<uint32_t>(imports_.size()));
  for (const Import& i : imports_) {
    put_name(s, i.module), put_name(s, i.name);
    s.push_back(i.memory ? 0x02 : 0x00);
    if (i.memory) s.push_back(0x00);  // limits: a minimum, no maximum
    put_u32(s, i.index);
  }
  section(out, 2, s);
  s.clear();
  put_u32(s, static_cast<uint32_t>(functions_.size()));
  for (const Function& f : functions_) put_u32(s, f.type);
  section(out, 3, s);
  s.clear();
  if (!globals_.empty()) {
    put_u32(s, static_cast<uint32_t>(globals_.size()));
    for (const auto& g : globals_) {
      s.push_back(static_cast<uint8_t>(ValType::V128)), s.push_back(0x01);  // mutable
      s.push_back(0xfd), put_u32(s, static_cast<uint32_t>(Simd::V128Const));
      s.insert(s.end(), g.begin(), g.end());
      s.push_back(0x0b);
    }
    section(out, 6, s);
    s.clear();
  }
  put_u32(s, static_cast<uint32_t>(exports_.size()));
  for (const auto& [name, index] : exports_) put_name(s, name), s.push_back(0x00), put_u32(s, index);
  section(out, 7, s);
  s.clear();
  put_u32(s, static_cast<uint32_t>(functions_.size()));
  for (const Function& f : functions_) {
    std::vector<uint8_t> body;
    put_u32(body, static_cast<uint32_t>(f.locals.size()));
    for (const auto& [count, type] : f.locals) put_u32(body, count), body.push_back(static_cast<uint8_t>(type));
    body.insert(body.end(), f.body.bytes().begin(), f.body.bytes().end());
    body.push_back(0x0b);  // the function's end
    put_u32(s, static_cast<uint32_t>(body.size()));
    s.insert(s.end(), body.begin(), body.end());
  }
  section(out, 10, s);
  return out;
}

}  // namespace fscript::wasm
