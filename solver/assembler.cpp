// SPDX-License-Identifier: MIT
#include "solver/assembler.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <utility>

namespace nmm {

Assembler::Assembler(const SparsityPattern& pattern) { reset(pattern); }

void Assembler::reset(const SparsityPattern& pattern) {
  const int n = pattern.n_dofs();
  const int nnz = pattern.n_nonzeros();
  // resize() and resizeNonZeros() keep the allocation when it is large enough, so a new
  // pattern each step costs a copy of its indices, not a fresh allocation.
  matrix_.resize(n, n);
  matrix_.resizeNonZeros(nnz);
  std::copy(pattern.column_starts().begin(), pattern.column_starts().end(),
            matrix_.outerIndexPtr());
  std::copy(pattern.row_indices().begin(), pattern.row_indices().end(), matrix_.innerIndexPtr());
  rhs_.resize(n);
  zero();
  clear_plans();
}

std::span<const double> Assembler::values() const {
  return {matrix_.valuePtr(), static_cast<std::size_t>(matrix_.nonZeros())};
}

void Assembler::assign_values(std::span<const double> values) {
  NMM_ASSERT(values.size() == static_cast<std::size_t>(matrix_.nonZeros()),
             "assign_values needs one value per entry of the pattern");
  std::copy(values.begin(), values.end(), matrix_.valuePtr());
}

void Assembler::zero() {
  std::fill_n(matrix_.valuePtr(), matrix_.nonZeros(), 0.0);
  rhs_.setZero();
}

int Assembler::search_position(int row, int column) const {
  NMM_ASSERT(row < n_dofs() && column < n_dofs(), "dof index out of range");
  if (row > column)
    std::swap(row, column);
  const int* rows = matrix_.innerIndexPtr();
  const int* begin = rows + matrix_.outerIndexPtr()[column];
  const int* end = rows + matrix_.outerIndexPtr()[column + 1];
  // The column ends with its diagonal and row <= column, so the result is inside the column
  // even when (row, column) is missing: memory stays safe in Release.
  const int* found = std::lower_bound(begin, end, row);
  NMM_ASSERT(found != end && *found == row, "entry (row, column) is not in the sparsity pattern");
  return static_cast<int>(found - rows);
}

void Assembler::add(std::span<const int> dofs, const Eigen::Ref<const Eigen::MatrixXd>& local) {
  const auto k = static_cast<Eigen::Index>(dofs.size());
  NMM_ASSERT(local.rows() == k && local.cols() == k, "local matrix size != number of dofs");
  double* values = matrix_.valuePtr();
  for (Eigen::Index b = 0; b < k; ++b) {
    const int column = dofs[static_cast<std::size_t>(b)];
    if (column < 0)
      continue;
    for (Eigen::Index a = 0; a <= b; ++a) {
      const int row = dofs[static_cast<std::size_t>(a)];
      if (row < 0)
        continue;
      const int position = search_position(row, column);
      // Two local entries (a, b) and (b, a) land on one global diagonal entry.
      values[position] += (a != b && row == column) ? 2.0 * local(a, b) : local(a, b);
    }
  }
}

void Assembler::add_vector(std::span<const int> dofs,
                           const Eigen::Ref<const Eigen::VectorXd>& local) {
  NMM_ASSERT(local.size() == static_cast<Eigen::Index>(dofs.size()),
             "local vector size != number of dofs");
  for (std::size_t a = 0; a < dofs.size(); ++a) {
    NMM_ASSERT(dofs[a] < n_dofs(), "dof index out of range");
    if (dofs[a] >= 0)
      rhs_[dofs[a]] += local[static_cast<Eigen::Index>(a)];
  }
}

void Assembler::add_diagonal(int dof, double value) {
  NMM_ASSERT(dof >= 0 && dof < n_dofs(), "dof index out of range");
  // Rows are sorted and at most the column, so the diagonal closes its column.
  matrix_.valuePtr()[matrix_.outerIndexPtr()[dof + 1] - 1] += value;
}

int Assembler::plan(std::span<const int> dofs) {
  const int id = plan_if_in_pattern(dofs);
  NMM_ASSERT(id >= 0, "entry (row, column) is not in the sparsity pattern");
  return id;
}

int Assembler::plan_if_in_pattern(std::span<const int> dofs) {
  Plan plan;
  plan.n_local = static_cast<int>(dofs.size());
  plan.kept_begin = kept_local_.size();
  for (std::size_t a = 0; a < dofs.size(); ++a) {
    NMM_ASSERT(dofs[a] < n_dofs(), "dof index out of range");
    if (dofs[a] >= 0) {
      kept_local_.push_back(static_cast<int>(a));
      kept_dofs_.push_back(dofs[a]);
    }
  }
  const int m = static_cast<int>(kept_local_.size() - plan.kept_begin);
  plan.n_kept = m;
  plan.position_begin = positions_.size();
  plan.repeat_begin = repeats_.size();
  const int* kept = kept_local_.data() + plan.kept_begin;
  const int* kept_dof = kept_dofs_.data() + plan.kept_begin;

  // Visit the pairs in sorted-dof order, so each column is walked upwards once, and store
  // each position where add(plan, local) will read it: slot q (q + 1) / 2 + p for kept
  // local indices p <= q.
  sorted_.resize(static_cast<std::size_t>(m));
  for (int q = 0; q < m; ++q)
    sorted_[static_cast<std::size_t>(q)] = q;
  std::sort(sorted_.begin(), sorted_.end(),
            [kept_dof](int left, int right) { return kept_dof[left] < kept_dof[right]; });
  positions_.resize(plan.position_begin + static_cast<std::size_t>(m) * (m + 1) / 2);
  int* slots = positions_.data() + plan.position_begin;
  const int* rows = matrix_.innerIndexPtr();
  for (int u = 0; u < m; ++u) {
    const int b = sorted_[static_cast<std::size_t>(u)];
    const int column = kept_dof[b];
    const int* cursor = rows + matrix_.outerIndexPtr()[column];
    for (int s = 0; s <= u; ++s) {
      const int a = sorted_[static_cast<std::size_t>(s)];
      const int row = kept_dof[a];
      // The column ends with its diagonal and row <= column: cursor stays in the column.
      while (*cursor < row)
        ++cursor;
      if (*cursor != row) { // not in the pattern: no plan
        drop_data_from(plan);
        return -1;
      }
      const auto position = static_cast<int>(cursor - rows);
      const int p = std::min(a, b);
      const int q = std::max(a, b);
      slots[q * (q + 1) / 2 + p] = position;
      if (p != q && row == column)
        repeats_.push_back({kept[p], kept[q], position});
    }
  }
  plan.repeat_end = repeats_.size();
  plan.kept_size = kept_local_.size();
  plan.positions_size = positions_.size();
  plan.repeats_size = repeats_.size();
  plans_.push_back(plan);
  return static_cast<int>(plans_.size()) - 1;
}

void Assembler::add(int plan_id, const Eigen::Ref<const Eigen::MatrixXd>& local) {
  NMM_ASSERT(plan_id >= 0 && plan_id < n_plans(), "unknown plan");
  const Plan& plan = plans_[static_cast<std::size_t>(plan_id)];
  NMM_ASSERT(local.rows() == plan.n_local && local.cols() == plan.n_local,
             "local matrix size != number of dofs of the plan");
  double* values = matrix_.valuePtr();
  const int* position = positions_.data() + plan.position_begin;
  const double* data = local.data();
  const Eigen::Index stride = local.outerStride();
  if (plan.n_kept == plan.n_local) {
    // The common case, nothing eliminated: local indices are used directly.
    for (int b = 0; b < plan.n_kept; ++b) {
      const double* column = data + b * stride;
      for (int a = 0; a <= b; ++a)
        values[*position++] += column[a];
    }
  } else {
    const int* kept = kept_local_.data() + plan.kept_begin;
    for (int q = 0; q < plan.n_kept; ++q) {
      const double* column = data + kept[q] * stride;
      for (int p = 0; p <= q; ++p)
        values[*position++] += column[kept[p]];
    }
  }
  for (std::size_t r = plan.repeat_begin; r < plan.repeat_end; ++r) {
    const Repeat& repeat = repeats_[r];
    values[repeat.position] += data[repeat.row + repeat.column * stride];
  }
}

void Assembler::add_vector(int plan_id, const Eigen::Ref<const Eigen::VectorXd>& local) {
  NMM_ASSERT(plan_id >= 0 && plan_id < n_plans(), "unknown plan");
  const Plan& plan = plans_[static_cast<std::size_t>(plan_id)];
  NMM_ASSERT(local.size() == plan.n_local, "local vector size != number of dofs of the plan");
  const int* kept = kept_local_.data() + plan.kept_begin;
  const int* kept_dof = kept_dofs_.data() + plan.kept_begin;
  for (int q = 0; q < plan.n_kept; ++q)
    rhs_[kept_dof[q]] += local[kept[q]];
}

int Assembler::plan_as(int plan_id) {
  NMM_ASSERT(plan_id >= 0 && plan_id < n_plans(), "no such plan to share");
  Plan plan = plans_[static_cast<std::size_t>(plan_id)];
  plan.kept_size = kept_local_.size();
  plan.positions_size = positions_.size();
  plan.repeats_size = repeats_.size();
  plans_.push_back(plan);
  return static_cast<int>(plans_.size()) - 1;
}

void Assembler::truncate_plans(int first) {
  NMM_ASSERT(first >= 0 && first <= n_plans(), "no such plan");
  if (first == n_plans())
    return;
  if (first == 0) {
    kept_local_.clear();
    kept_dofs_.clear();
    positions_.clear();
    repeats_.clear();
  } else {
    const Plan& last = plans_[static_cast<std::size_t>(first) - 1];
    kept_local_.resize(last.kept_size);
    kept_dofs_.resize(last.kept_size);
    positions_.resize(last.positions_size);
    repeats_.resize(last.repeats_size);
  }
  plans_.resize(static_cast<std::size_t>(first));
}

void Assembler::drop_data_from(const Plan& plan) {
  kept_local_.resize(plan.kept_begin);
  kept_dofs_.resize(plan.kept_begin);
  positions_.resize(plan.position_begin);
  repeats_.resize(plan.repeat_begin);
}

void Assembler::clear_plans() { truncate_plans(0); }

} // namespace nmm
