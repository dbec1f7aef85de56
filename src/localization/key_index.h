#pragma once

#include <cstdint>
#include <utility>
#include <vector>

// A set of 64-bit keys, each numbered in insertion order, in one open-addressed table: the
// KLD bins and the particle clusters look a key up once per particle and per neighbour bin,
// where std::unordered_set / std::map cost an allocation per key and a pointer chase per look-up.
namespace semchain::localization {

class KeyIndex {
 public:
  KeyIndex() { Reset(16); }

  // The number of 'key' (its insertion rank) and whether it was added by this call.
  std::pair<int, bool> Insert(std::uint64_t key) {
    if (2 * (size_ + 1) > static_cast<int>(keys_.size())) Reset(2 * keys_.size(), true);
    std::size_t slot = SlotOf(key);
    while (values_[slot] >= 0) {
      if (keys_[slot] == key) return {values_[slot], false};
      slot = (slot + 1) & mask_;
    }
    keys_[slot] = key;
    values_[slot] = size_;
    return {size_++, true};
  }
  // The number of 'key', or -1 when absent.
  int Find(std::uint64_t key) const {
    for (std::size_t slot = SlotOf(key); values_[slot] >= 0; slot = (slot + 1) & mask_) {
      if (keys_[slot] == key) return values_[slot];
    }
    return -1;
  }
  int size() const { return size_; }
  // Empties the set, keeping room for 'expected' keys without growing.
  void Clear(std::size_t expected = 0) {
    std::size_t capacity = 16;
    while (capacity < 2 * expected) capacity *= 2;
    Reset(capacity);
  }

 private:
  std::size_t SlotOf(std::uint64_t key) const {
    // Fibonacci hashing: packed bin indices differ in a few low bits of each field.
    return static_cast<std::size_t>((key * 0x9E3779B97F4A7C15ull) >> 32) & mask_;
  }
  void Reset(std::size_t capacity, bool keep = false) {
    std::vector<std::uint64_t> keys(capacity);
    std::vector<int> values(capacity, -1);
    keys.swap(keys_);
    values.swap(values_);
    mask_ = capacity - 1;
    if (!keep) {
      size_ = 0;
      return;
    }
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (values[i] < 0) continue;
      std::size_t slot = SlotOf(keys[i]);
      while (values_[slot] >= 0) slot = (slot + 1) & mask_;
      keys_[slot] = keys[i];
      values_[slot] = values[i];
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<int> values_;  // -1: empty slot
  std::size_t mask_ = 0;
  int size_ = 0;
};

}  // namespace semchain::localization
