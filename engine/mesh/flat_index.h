#pragma once
// An open-addressing map from 64-bit keys to 32-bit indices (linear probing, no erase): dual
// contouring looks up millions of cells and octree nodes per mesh, and a node-based map spends
// most of that time allocating and chasing pointers.
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fscript::mesh {

class FlatIndex {
 public:
  static constexpr uint64_t kEmpty = ~uint64_t{0};  // never a key

  explicit FlatIndex(size_t expected = 16) {
    size_t cap = 16;
    while (cap < 2 * expected) cap *= 2;
    keys_.assign(cap, kEmpty);
    values_.resize(cap);
  }

  // The value stored for `key`, or `value` stored for it now (second: whether it was).
  std::pair<uint32_t, bool> try_emplace(uint64_t key, uint32_t value) {
    if (2 * (size_ + 1) > keys_.size()) grow();
    size_t i = slot(key);
    if (keys_[i] == key) return {values_[i], false};
    keys_[i] = key, values_[i] = value, ++size_;
    return {value, true};
  }
  // The value for `key`, or nullptr.
  const uint32_t* find(uint64_t key) const {
    size_t i = slot(key);
    return keys_[i] == key ? &values_[i] : nullptr;
  }
  size_t size() const { return size_; }

 private:
  static uint64_t mix(uint64_t k) {  // the finaliser of MurmurHash3
    k ^= k >> 33, k *= 0xff51afd7ed558ccdULL, k ^= k >> 33, k *= 0xc4ceb9fe1a85ec53ULL, k ^= k >> 33;
    return k;
  }
  size_t slot(uint64_t key) const {
    size_t mask = keys_.size() - 1, i = static_cast<size_t>(mix(key)) & mask;
    while (keys_[i] != key && keys_[i] != kEmpty) i = (i + 1) & mask;
    return i;
  }
  void grow() {
    std::vector<uint64_t> keys(keys_.size() * 2, kEmpty);
    std::vector<uint32_t> values(keys.size());
    keys.swap(keys_), values.swap(values_);
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) {
        size_t j = slot(keys[i]);
        keys_[j] = keys[i], values_[j] = values[i];
      }
  }

  std::vector<uint64_t> keys_;
  std::vector<uint32_t> values_;
  size_t size_ = 0;
};

}  // namespace fscript::mesh
