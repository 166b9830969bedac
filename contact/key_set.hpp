// SPDX-License-Identifier: MIT
// contact/key_set.hpp — sets and indices of 64-bit contact keys by open addressing.
#pragma once

#include "mesh/error.hpp"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace nmm {

/// 64-bit keys (contact keys, pairs of boundary indices), each with an int value, in one
/// flat table with linear probing: the detection builds four sets of tens of thousands of
/// keys every step and the contacts look up the states carried from the last step by key,
/// and std::unordered_set's and std::unordered_map's allocation per key, rehashing and
/// scattered nodes took 6 % and 10 % of a step of 10,004 DDA blocks (docs/benchmarks.md,
/// "Conjugate gradients"). Lookups only: no iteration, so the order of the table never
/// shows. The key with all bits set is reserved (no contact key or pair of indices is it).
class KeyIndex {
public:
  /// What find() returns for a key that is not there.
  static constexpr int none = -1;

  explicit KeyIndex(std::size_t expected = 0) { reserve(expected); }

  /// Room for @p count keys without growing.
  void reserve(std::size_t count) {
    std::size_t capacity = 16;
    while (capacity < 2 * count)
      capacity *= 2;
    if (capacity > keys_.size())
      rebuild(capacity);
  }

  /// Empty, with the room it had.
  void clear() {
    std::fill(keys_.begin(), keys_.end(), empty);
    size_ = 0;
  }

  /// Adds @p key with @p value; true when it was not there (a key that is keeps its value).
  bool insert(std::uint64_t key, int value) {
    NMM_ASSERT(key != empty, "the key with all bits set is reserved");
    if (2 * (size_ + 1) > keys_.size())
      rebuild(2 * keys_.size());
    std::size_t i = hash(key) & mask_;
    while (keys_[i] != empty) {
      if (keys_[i] == key)
        return false;
      i = (i + 1) & mask_;
    }
    keys_[i] = key;
    values_[i] = value;
    ++size_;
    return true;
  }

  /// The value of @p key, or none.
  [[nodiscard]] int find(std::uint64_t key) const {
    std::size_t i = hash(key) & mask_;
    while (keys_[i] != empty) {
      if (keys_[i] == key)
        return values_[i];
      i = (i + 1) & mask_;
    }
    return none;
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
    std::vector<std::uint64_t> old_keys;
    std::vector<int> old_values;
    old_keys.swap(keys_);
    old_values.swap(values_);
    keys_.assign(capacity, empty);
    values_.assign(capacity, none);
    mask_ = capacity - 1;
    size_ = 0;
    for (std::size_t k = 0; k < old_keys.size(); ++k) {
      if (old_keys[k] != empty)
        insert(old_keys[k], old_values[k]);
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<int> values_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

/// A set of 64-bit keys: a KeyIndex whose values are not used.
class KeySet {
public:
  explicit KeySet(std::size_t expected = 0) : index_(expected) {}

  /// Room for @p count keys without growing.
  void reserve(std::size_t count) { index_.reserve(count); }

  /// Adds @p key; true when it was not there.
  bool insert(std::uint64_t key) { return index_.insert(key, 0); }

  [[nodiscard]] bool contains(std::uint64_t key) const {
    return index_.find(key) != KeyIndex::none;
  }

  [[nodiscard]] std::size_t size() const noexcept { return index_.size(); }

private:
  KeyIndex index_;
};

} // namespace nmm
