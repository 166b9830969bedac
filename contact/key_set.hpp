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
/// scattered nodes are a sizeable part of a step of thousands of blocks (docs/benchmarks.md,
/// "Blocks: DDA, VEM, NMM and conjugate gradients"). Lookups only: no iteration, so the order of
/// the table never shows, and neither does the hash. The key with all bits set is reserved (no
/// contact key or pair of indices is it).
///
/// The table keeps near indices near: a key's probe starts at 8 times its high 32 bits (a
/// pair's lower index, twice a contact's slave) plus 0 to 7 from its low bits, so the keys of
/// one vertex or edge share a cache line and those of one block's boundary (consecutive
/// indices) a few. The detection and the transfer visit the boundary block by block; with a
/// hash that scattered every key each probe was a cache miss (the probes were 30% of the
/// detection at 10,004 DDA blocks: 0.9 of its time since; on bench_contact's brick wall of
/// 113,399 edges the detection is 3.5 times faster). Indices with more than about 8
/// keys each over a stretch (an NMM model's short edges along a joint, each near a dozen on
/// the other face) make one long run of probes: a probe longer than 64 slots turns the table
/// to splitmix64 over all the bits (scattered) for good, the table of before.
class KeyIndex {
public:
  /// What find() returns for a key that is not there.
  static constexpr int none = -1;

  /// @param with_values  false for a set (KeySet): no values are stored or read.
  explicit KeyIndex(std::size_t expected = 0, bool with_values = true) : with_values_(with_values) {
    reserve(expected);
  }

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
    std::size_t probes = 0;
    const std::size_t i = slot(key, &probes);
    if (keys_[i] == key)
      return false;
    if (probes > max_local_probes && !scattered_) {
      scattered_ = true;
      rebuild(keys_.size());
      return insert(key, value);
    }
    keys_[i] = key;
    if (with_values_)
      values_[i] = value;
    ++size_;
    return true;
  }

  /// The value of @p key, or none. @pre a table with values.
  [[nodiscard]] int find(std::uint64_t key) const {
    NMM_ASSERT(with_values_, "a set has no values to find");
    const std::size_t i = slot(key);
    return keys_[i] == key ? values_[i] : none;
  }

  /// Whether @p key is there.
  [[nodiscard]] bool contains(std::uint64_t key) const { return keys_[slot(key)] == key; }

  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  /// Whether a long probe has turned the table to the scattering hash.
  [[nodiscard]] bool scattered() const noexcept { return scattered_; }

  /// splitmix64's finaliser: the table's scattering hash, and a mix for keys made of several
  /// values (Assembler's plans).
  [[nodiscard]] static std::uint64_t hash(std::uint64_t key) noexcept {
    key ^= key >> 30U;
    key *= 0xbf58476d1ce4e5b9ULL;
    key ^= key >> 27U;
    key *= 0x94d049bb133111ebULL;
    key ^= key >> 31U;
    return key;
  }

private:
  static constexpr std::uint64_t empty = ~std::uint64_t{0};
  static constexpr std::size_t max_local_probes = 64;

  /// Where the probe for @p key starts (see the class comment).
  [[nodiscard]] std::size_t home(std::uint64_t key) const noexcept {
    if (scattered_)
      return hash(key) & mask_;
    return ((key >> 32U) * 8U + (hash(key & 0xffffffffU) & 7U)) & mask_;
  }

  /// The slot holding @p key, or the empty slot that ends its probe; @p probes (if given)
  /// gets the number of other keys passed on the way. Never loops for ever: the table is at
  /// most half full.
  [[nodiscard]] std::size_t slot(std::uint64_t key, std::size_t* probes = nullptr) const noexcept {
    std::size_t i = home(key);
    std::size_t passed = 0;
    for (; keys_[i] != empty && keys_[i] != key; ++passed)
      i = (i + 1) & mask_;
    if (probes != nullptr)
      *probes = passed;
    return i;
  }

  void rebuild(std::size_t capacity) {
    std::vector<std::uint64_t> old_keys;
    std::vector<int> old_values;
    old_keys.swap(keys_);
    old_values.swap(values_);
    keys_.assign(capacity, empty);
    if (with_values_)
      values_.assign(capacity, none);
    mask_ = capacity - 1;
    size_ = 0;
    for (std::size_t k = 0; k < old_keys.size(); ++k) {
      if (old_keys[k] != empty)
        insert(old_keys[k], with_values_ ? old_values[k] : 0);
    }
  }

  std::vector<std::uint64_t> keys_;
  std::vector<int> values_; // empty without values
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
  bool with_values_ = true;
  bool scattered_ = false;
};

/// A set of 64-bit keys: a KeyIndex without values.
class KeySet {
public:
  explicit KeySet(std::size_t expected = 0) : index_(expected, false) {}

  /// Room for @p count keys without growing.
  void reserve(std::size_t count) { index_.reserve(count); }

  /// Adds @p key; true when it was not there.
  bool insert(std::uint64_t key) { return index_.insert(key, 0); }

  [[nodiscard]] bool contains(std::uint64_t key) const { return index_.contains(key); }

  [[nodiscard]] std::size_t size() const noexcept { return index_.size(); }
  /// KeyIndex::scattered().
  [[nodiscard]] bool scattered() const noexcept { return index_.scattered(); }

private:
  KeyIndex index_;
};

} // namespace nmm
