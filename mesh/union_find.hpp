// SPDX-License-Identifier: MIT
// mesh/union_find.hpp — disjoint sets of 0..n-1.
#pragma once

#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace nmm {

/// Union-find with path halving; unite() keeps the smaller index as the root, so the
/// results do not depend on the order of the unions.
class UnionFind {
public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int i) {
    while (parent_[index(i)] != i) {
      parent_[index(i)] = parent_[index(parent_[index(i)])];
      i = parent_[index(i)];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a == b)
      return;
    if (a < b)
      std::swap(a, b);
    parent_[index(a)] = b;
  }

private:
  static std::size_t index(int i) { return static_cast<std::size_t>(i); }
  std::vector<int> parent_;
};

} // namespace nmm
