// SPDX-License-Identifier: MIT
// solver/sparsity.hpp — the symmetric sparsity pattern of the step's matrix, built from
// dense couplings ("dof groups"): elements, contact candidates, DDA and VEM blocks.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace nmm {

/// Upper triangle of a symmetric n x n sparsity pattern in compressed-column form, the
/// layout of SparseMatrix (solver/linear_solver.hpp): column j holds the rows i <= j of its
/// nonzeros, sorted ascending, and always its diagonal, which is therefore its last entry.
///
/// A value type: cheap to move, compared entry by entry. Built once per time step by
/// SparsityBuilder (DESIGN.md "Numerical choices": the pattern includes every contact
/// candidate of the step, so the symbolic analysis is done once per step).
class SparsityPattern {
public:
  /// The empty 0 x 0 pattern.
  SparsityPattern() = default;

  /// Takes ownership of compressed-column arrays.
  /// @pre column_starts.size() == n_dofs + 1, column_starts[0] == 0, non-decreasing,
  ///      column_starts[n_dofs] == row_indices.size(); each column's rows are strictly
  ///      increasing, at most the column index, and end with the diagonal (checked by
  ///      NMM_ASSERT).
  SparsityPattern(int n_dofs, std::vector<int> column_starts, std::vector<int> row_indices);

  /// Number of rows and columns.
  [[nodiscard]] int n_dofs() const { return n_dofs_; }
  /// Number of stored (upper-triangle) entries, diagonal included.
  [[nodiscard]] int n_nonzeros() const { return static_cast<int>(row_indices_.size()); }
  /// n_dofs() + 1 offsets into row_indices(); column j is [starts[j], starts[j + 1]).
  [[nodiscard]] std::span<const int> column_starts() const { return column_starts_; }
  /// Row index of every stored entry, column after column.
  [[nodiscard]] std::span<const int> row_indices() const { return row_indices_; }
  /// Sorted rows of the stored entries of column @p column (its last one is @p column).
  [[nodiscard]] std::span<const int> rows_of_column(int column) const;

  /// Position in row_indices() (and in the value array of a matrix with this pattern) of
  /// entry (row, column) or of its transpose, whichever lies in the upper triangle; -1 when
  /// the pattern does not hold it. O(log of the column's height).
  /// @pre 0 <= row, column < n_dofs().
  [[nodiscard]] int position(int row, int column) const;
  /// Whether position(row, column) >= 0.
  [[nodiscard]] bool contains(int row, int column) const { return position(row, column) >= 0; }

  /// Same size and same entries.
  friend bool operator==(const SparsityPattern&, const SparsityPattern&) = default;

private:
  int n_dofs_ = 0;
  std::vector<int> column_starts_{0};
  std::vector<int> row_indices_;
};

/// Collects dense couplings and builds their SparsityPattern.
///
/// Each add() says "all these dofs couple with each other": the pattern gets entry (i, j)
/// for every pair i, j of the group (and its diagonal for every dof of the matrix, coupled
/// or not). A group is an element (the dofs of its 3 covers: 6, 18 or 36), a contact
/// candidate (the dofs of two elements, up to 72), a DDA block (6) or a VEM block
/// (2 x vertices). Cost: O(sum of k^2 + nnz log h) time for groups of k dofs and columns of
/// height h, O(sum of k + n_dofs + nnz) memory; nothing n x n, no per-column tree.
///
/// Typical use, once per time step: clear(), add() every element and contact candidate,
/// then build(). clear() keeps the storage, so steady state does not allocate.
class SparsityBuilder {
public:
  /// A builder for an @p n_dofs x @p n_dofs pattern. @pre n_dofs >= 0.
  explicit SparsityBuilder(int n_dofs);

  /// Reserves room for @p n_groups groups holding @p n_group_dofs dofs in all.
  void reserve(std::size_t n_groups, std::size_t n_group_dofs);

  /// Adds one dense coupling. @p dofs may be unsorted and hold repeats; negative entries are
  /// eliminated dofs and are ignored (so a fixed cover can keep its place in the list).
  /// @pre every non-negative entry is < n_dofs() (checked by NMM_ASSERT).
  void add(std::span<const int> dofs);

  /// Forgets every group; keeps n_dofs() and the storage.
  void clear();

  /// Number of rows and columns of the pattern to build.
  [[nodiscard]] int n_dofs() const { return n_dofs_; }
  /// Number of groups added since construction or clear().
  [[nodiscard]] std::size_t n_groups() const { return group_starts_.size() - 1; }

  /// The upper-triangle pattern of all groups added so far, plus every diagonal. Not const:
  /// it keeps its scratch storage (O(n_dofs + sum of group sizes)) for the next build.
  /// @throws std::length_error if it would exceed 2^31 - 1 entries (SparseMatrix has int
  ///         indices).
  [[nodiscard]] SparsityPattern build();

private:
  int n_dofs_;
  std::vector<std::size_t> group_starts_{0}; // group g is group_dofs_[starts[g], starts[g+1])
  std::vector<int> group_dofs_;              // each group sorted, unique, non-negative
  // build() scratch, kept between builds: dof -> groups holding it, and a column marker.
  std::vector<std::size_t> incidence_starts_;
  std::vector<int> incidence_;
  std::vector<int> marker_;
  std::size_t last_n_nonzeros_ = 0;
};

} // namespace nmm
