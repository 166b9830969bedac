// SPDX-License-Identifier: MIT
// tests/unit/solver/random_groups.hpp — random dof groups and triplet references shared by
// the sparsity and assembler tests.
#pragma once

#include "solver/linear_solver.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <random>
#include <vector>

namespace nmm::testing {

/// Random couplings over @p n_dofs dofs: sizes 1..max_size, dofs drawn from a window (so
/// groups overlap as neighbouring elements do), unsorted, with repeats and, when
/// @p with_eliminated, some negative (eliminated) entries.
inline std::vector<std::vector<int>> make_random_groups(
    int n_dofs, int n_groups, int max_size, unsigned seed, bool with_eliminated = true) {
  std::mt19937 random(seed);
  std::vector<std::vector<int>> groups;
  for (int g = 0; g < n_groups; ++g) {
    const int size = std::uniform_int_distribution<int>(1, max_size)(random);
    const int window = std::min(n_dofs, std::max(size, 3 * max_size / 2));
    const int first = std::uniform_int_distribution<int>(0, n_dofs - window)(random);
    std::uniform_int_distribution<int> pick(first, first + window - 1);
    std::uniform_int_distribution<int> percent(0, 99);
    std::vector<int> dofs;
    for (int a = 0; a < size; ++a) {
      const int roll = percent(random);
      if (with_eliminated && roll < 5)
        dofs.push_back(-1);
      else if (roll < 10 && !dofs.empty() && dofs.back() >= 0)
        dofs.push_back(dofs.back()); // a repeated dof
      else
        dofs.push_back(pick(random));
    }
    groups.push_back(std::move(dofs));
  }
  return groups;
}

/// A symmetric matrix of size @p k with entries in [-1, 1] and a dominant positive diagonal.
inline Eigen::MatrixXd make_random_symmetric(int k, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd local(k, k);
  for (int b = 0; b < k; ++b) {
    for (int a = 0; a <= b; ++a) {
      local(a, b) = value(random);
      local(b, a) = local(a, b);
    }
    local(b, b) = 1.0 + k + value(random);
  }
  return local;
}

/// The reference: every local entry as a triplet (full P^T local P), then the upper
/// triangle, with an explicit diagonal entry for every dof.
inline SparseMatrix assemble_by_triplets(int n_dofs,
                                         const std::vector<std::vector<int>>& groups,
                                         const std::vector<Eigen::MatrixXd>& locals) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int dof = 0; dof < n_dofs; ++dof)
    entries.emplace_back(dof, dof, 0.0);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const std::vector<int>& dofs = groups[g];
    for (std::size_t b = 0; b < dofs.size(); ++b) {
      for (std::size_t a = 0; a < dofs.size(); ++a) {
        if (dofs[a] >= 0 && dofs[b] >= 0 && dofs[a] <= dofs[b]) {
          entries.emplace_back(
              dofs[a], dofs[b],
              locals[g](static_cast<Eigen::Index>(a), static_cast<Eigen::Index>(b)));
        }
      }
    }
  }
  SparseMatrix reference(n_dofs, n_dofs);
  reference.setFromTriplets(entries.begin(), entries.end());
  reference.makeCompressed();
  return reference;
}

} // namespace nmm::testing
