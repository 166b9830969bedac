// SPDX-License-Identifier: MIT
// contact/key_set.hpp — a set of 64-bit contact keys by open addressing.
#pragma once

#include "mesh/error.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace nmm {

/// A set of 64-bit keys (contact keys, pairs of boundary indices) in one flat table with
/// linear probing: the detection builds four such sets of tens of thousands of keys every
/// step, and std::unordered_set's allocation per key and rehashing took 6 % of a step of
/// 10,004 DDA blocks (docs/benchmarks.md, "Conjugate gradients"). Membership only: no
/// iteration, so the order of the table never shows. The key with all bits set is reserved
/// (no contact key or pair of indices is it).
class KeySet {
public:
  explicit KeySet(std::size_t expected = 0) { reserve(expected); }

  /// Room for @p count keys without growing.
  void reserve(std::size_t count) {
    std::size_t capacity = 16;
    while (capacity < 2 * count)
      capacity *= 2;
    if (capacity > slots_.size())
      rebuild(capacity);
  }

  /// Adds @p key; true when it was not there.
  bool insert(std::uint64_t key) {
    NMM_ASSERT(key != empty, "the key with all bits set is reserved");
    if (2 * (size_ + 1) > slots_.size())
      rebuild(2 * slots_.size());
    std::size_t i = hash(key) & mask_;
    while (slots_[i] != empty) {
      if (slots_[i] == key)
        return false;
      i = (i + 1) & mask_;
    }
    slots_[i] = key;
    ++size_;
    return true;
  }

  [[nodiscard]] bool contains(std::uint64_t key) const {
    std::size_t i = hash(key) & mask_;
    while (slots_[i] != empty) {
      if (slots_[i] == key)
        return true;
      i = (i + 1) & mask_;
    }
    return false;
  }

  [[nodiscard]] std::size_t size() const noexcept { return size_; }

private:
  static constexpr std::uint64_t empty = ~std::uint64_t{0};

  /// splitmix64's finaliser: keys built of small indices in fixed bit fields spread over
  /// the whole table.
  static std::uint64_t hash(std::uint64_t key) noexcept {
    key ^= key >> 30U;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27U;
    key *= 0x94d049bb133111ebULL;
    key ^= key >> 31U;
    return key;
  }

  void rebuild(std::size_t capacity) {
    std::vector<std::uint64_t> old;
    old.swap(slots_);
    slots_.assign(capacity, empty);
    mask_ = capacity - 1;
    size_ = 0;
    for (const std::uint64_t key : old) {
      if (key != empty)
        insert(key);
    }
  }

  std::vector<std::uint64_t> slots_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

} // namespace nmm
