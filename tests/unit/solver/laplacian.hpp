// SPDX-License-Identifier: MIT
// tests/unit/solver/laplacian.hpp — a symmetric positive definite test matrix shared by the
// solver tests.
#pragma once

#include "solver/linear_solver.hpp"

#include <vector>

namespace nmm::testing {

// 5-point Laplacian on an n x n grid plus `shift` on the diagonal, full symmetric storage.
inline SparseMatrix laplacian(int n, double shift) {
  std::vector<Eigen::Triplet<double>> entries;
  auto id = [n](int i, int j) { return i * n + j; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      entries.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i + 1 < n) {
        entries.emplace_back(id(i, j), id(i + 1, j), -1.0);
        entries.emplace_back(id(i + 1, j), id(i, j), -1.0);
      }
      if (j + 1 < n) {
        entries.emplace_back(id(i, j), id(i, j + 1), -1.0);
        entries.emplace_back(id(i, j + 1), id(i, j), -1.0);
      }
    }
  }
  SparseMatrix a(n * n, n * n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

} // namespace nmm::testing
