#pragma once
// Little-endian scalars and length-prefixed arrays of trivially copyable values, for the files one
// run of ours writes and another reads (shard parts). The reader checks every length against what
// is left, so a truncated or hostile file is an error (ok == false), never a huge allocation.
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace fscript::support {

struct ByteWriter {
  std::string out;
  template <class T>
  void put(const T& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    out.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void put_vector(const std::vector<T>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(v.size());
    if (!v.empty()) out.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void put_bytes(const void* p, size_t n) { out.append(static_cast<const char*>(p), n); }
  void put_string(const std::string& s) {
    put<uint64_t>(s.size());
    out += s;
  }
};

struct ByteReader {
  std::string_view in;
  size_t at = 0;
  bool ok = true;
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T v{};
    if (!ok || in.size() - at < sizeof v) return ok = false, v;
    std::memcpy(&v, in.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  template <class T>
  std::vector<T> get_vector() {
    uint64_t n = get<uint64_t>();
    if (!ok || n > (in.size() - at) / sizeof(T)) return ok = false, std::vector<T>{};
    std::vector<T> v(n);
    if (n) std::memcpy(v.data(), in.data() + at, n * sizeof(T));  // an empty vector's data() may be null
    at += n * sizeof(T);
    return v;
  }
  bool get_bytes(void* p, size_t n) {
    if (!ok || in.size() - at < n) return ok = false;
    std::memcpy(p, in.data() + at, n);
    at += n;
    return true;
  }
  std::string get_string() {
    uint64_t n = get<uint64_t>();
    if (!ok || n > in.size() - at) return ok = false, std::string{};
    std::string s(in.substr(at, n));
    at += n;
    return s;
  }
};

}  // namespace fscript::support
