// SPDX-License-Identifier: MIT
#include "solver/sparsity.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <climits>
#include <functional>
#include <stdexcept>
#include <utility>

namespace nmm {

SparsityPattern::SparsityPattern(int n_dofs,
                                 std::vector<int> column_starts,
                                 std::vector<int> row_indices)
    : n_dofs_(n_dofs), column_starts_(std::move(column_starts)),
      row_indices_(std::move(row_indices)) {
  NMM_ASSERT(n_dofs_ >= 0, "a pattern needs a non-negative size");
  NMM_ASSERT(column_starts_.size() == static_cast<std::size_t>(n_dofs_) + 1,
             "column_starts needs n_dofs + 1 entries");
  NMM_ASSERT(column_starts_.front() == 0 &&
                 column_starts_.back() == static_cast<int>(row_indices_.size()),
             "column_starts must run from 0 to the number of entries");
#if !defined(NDEBUG) || defined(NMM_ENABLE_ASSERTS)
  for (int column = 0; column < n_dofs_; ++column) {
    const std::span<const int> rows = rows_of_column(column);
    NMM_ASSERT(!rows.empty() && rows.back() == column,
               "every column must end with its diagonal entry");
    NMM_ASSERT(std::adjacent_find(rows.begin(), rows.end(), std::greater_equal<>()) == rows.end() &&
                   rows.front() >= 0,
               "rows of a column must be strictly increasing and non-negative");
  }
#endif
}

std::span<const int> SparsityPattern::rows_of_column(int column) const {
  NMM_ASSERT(column >= 0 && column < n_dofs_, "column out of range");
  const auto begin = static_cast<std::size_t>(column_starts_[static_cast<std::size_t>(column)]);
  const auto end = static_cast<std::size_t>(column_starts_[static_cast<std::size_t>(column) + 1]);
  return std::span<const int>(row_indices_).subspan(begin, end - begin);
}

int SparsityPattern::position(int row, int column) const {
  NMM_ASSERT(row >= 0 && row < n_dofs_ && column >= 0 && column < n_dofs_, "entry out of range");
  if (row > column)
    std::swap(row, column);
  const std::span<const int> rows = rows_of_column(column);
  const auto found = std::lower_bound(rows.begin(), rows.end(), row);
  if (found == rows.end() || *found != row)
    return -1;
  return column_starts_[static_cast<std::size_t>(column)] + static_cast<int>(found - rows.begin());
}

SparsityBuilder::SparsityBuilder(int n_dofs) : n_dofs_(n_dofs) {
  NMM_ASSERT(n_dofs >= 0, "a pattern needs a non-negative size");
}

void SparsityBuilder::reserve(std::size_t n_groups, std::size_t n_group_dofs) {
  group_starts_.reserve(n_groups + 1);
  group_dofs_.reserve(n_group_dofs);
}

void SparsityBuilder::add(std::span<const int> dofs) {
  const std::size_t begin = group_dofs_.size();
  for (const int dof : dofs) {
    NMM_ASSERT(dof < n_dofs_, "dof index out of range");
    if (dof >= 0)
      group_dofs_.push_back(dof);
  }
  // Sorted groups let build() stop scanning a group at the column's own dof.
  const auto first = group_dofs_.begin() + static_cast<std::ptrdiff_t>(begin);
  std::sort(first, group_dofs_.end());
  group_dofs_.erase(std::unique(first, group_dofs_.end()), group_dofs_.end());
  group_starts_.push_back(group_dofs_.size());
}

void SparsityBuilder::clear() {
  group_starts_.resize(1);
  group_dofs_.clear();
}

SparsityPattern SparsityBuilder::build() {
  const auto n = static_cast<std::size_t>(n_dofs_);
  const std::size_t n_group_entries = group_dofs_.size();
  if (n_groups() > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("SparsityBuilder: more than 2^31 - 1 groups");

  // Transpose the groups: for every dof, the groups holding it (counting sort). The scratch
  // arrays are members so that a build every time step does not page-fault them in again.
  incidence_starts_.assign(n + 1, 0);
  for (const int dof : group_dofs_)
    ++incidence_starts_[static_cast<std::size_t>(dof) + 1];
  for (std::size_t dof = 0; dof < n; ++dof)
    incidence_starts_[dof + 1] += incidence_starts_[dof];
  incidence_.resize(n_group_entries);
  for (std::size_t group = 0; group + 1 < group_starts_.size(); ++group) {
    for (std::size_t k = group_starts_[group]; k < group_starts_[group + 1]; ++k)
      incidence_[incidence_starts_[static_cast<std::size_t>(group_dofs_[k])]++] =
          static_cast<int>(group);
  }
  // The fill above moved every start to the next dof's start: shift back.
  for (std::size_t dof = n; dof > 0; --dof)
    incidence_starts_[dof] = incidence_starts_[dof - 1];
  incidence_starts_[0] = 0;

  // Column by column: the rows of column j are the dofs <= j of the groups holding j.
  // marker[i] == j says row i is already in column j, so no set or search is needed and the
  // columns come out in order, appended to one flat array.
  std::vector<int> column_starts(n + 1);
  std::vector<int> row_indices;
  // The last build's size is a close guess in a time-step loop; the first build guesses
  // from a 2D mesh (7-10 entries per upper column with 2-dof covers). Growth is geometric.
  row_indices.reserve(last_n_nonzeros_ > 0 ? last_n_nonzeros_ + last_n_nonzeros_ / 16
                                           : std::max(n * 8, n_group_entries));
  marker_.assign(n, -1);
  column_starts[0] = 0;
  for (std::size_t column = 0; column < n; ++column) {
    const int j = static_cast<int>(column);
    const std::size_t begin = row_indices.size();
    for (std::size_t k = incidence_starts_[column]; k < incidence_starts_[column + 1]; ++k) {
      const auto group = static_cast<std::size_t>(incidence_[k]);
      const int* dof = group_dofs_.data() + group_starts_[group];
      // Each group is sorted and holds j, so the scan meets j before leaving the group.
      for (; *dof < j; ++dof) {
        const auto row = static_cast<std::size_t>(*dof);
        if (marker_[row] != j) {
          marker_[row] = j;
          row_indices.push_back(*dof);
        }
      }
    }
    row_indices.push_back(j); // the diagonal, also for a dof no group couples
    // Only the rows below the diagonal need sorting; a single group's rows already are.
    std::sort(row_indices.begin() + static_cast<std::ptrdiff_t>(begin), row_indices.end() - 1);
    if (row_indices.size() > static_cast<std::size_t>(INT_MAX))
      throw std::length_error("SparsityBuilder: pattern exceeds 2^31 - 1 entries");
    column_starts[column + 1] = static_cast<int>(row_indices.size());
  }
  last_n_nonzeros_ = row_indices.size();
  if (row_indices.capacity() > row_indices.size() + row_indices.size() / 4)
    row_indices.shrink_to_fit();
  return {n_dofs_, std::move(column_starts), std::move(row_indices)};
}

} // namespace nmm
