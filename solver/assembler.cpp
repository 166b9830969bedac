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
  scratch_local_.clear();
  scratch_dofs_.clear();
  for (std::size_t a = 0; a < dofs.size(); ++a) {
    NMM_ASSERT(dofs[a] < n_dofs(), "dof index out of range");
    if (dofs[a] >= 0) {
      scratch_local_.push_back(static_cast<int>(a));
      scratch_dofs_.push_back(dofs[a]);
    }
  }
  const int n_local = static_cast<int>(dofs.size());
  const int m = static_cast<int>(scratch_local_.size());
  // The positions of a plan for the same dofs, if there was one.
  const std::uint64_t key = plan_key(n_local, scratch_local_.data(), scratch_dofs_.data(), m);
  const int known = index_.find(key);
  if (known != KeyIndex::none) {
    const Plan& plan = known_[static_cast<std::size_t>(known)];
    if (has_pairs(plan, kept_local_, kept_dofs_, n_local, scratch_local_.data(),
                  scratch_dofs_.data(), m)) {
      plans_.push_back(plan);
      return static_cast<int>(plans_.size()) - 1;
    }
  }
  ++searches_;
  Plan plan;
  plan.n_local = n_local;
  plan.n_kept = m;
  plan.kept_begin = kept_local_.size();
  kept_local_.insert(kept_local_.end(), scratch_local_.begin(), scratch_local_.end());
  kept_dofs_.insert(kept_dofs_.end(), scratch_dofs_.begin(), scratch_dofs_.end());
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
  if (known == KeyIndex::none) { // (another set of dofs with the same key keeps it)
    index_.insert(key, static_cast<int>(known_.size()));
    known_.push_back(plan);
  }
  plans_.push_back(plan);
  return static_cast<int>(plans_.size()) - 1;
}

std::uint64_t Assembler::plan_key(int n_local, const int* kept, const int* dofs, int m) {
  // splitmix64's finaliser over the size and the pairs, one after the other.
  std::uint64_t key =
      KeyIndex::hash(static_cast<std::uint64_t>(static_cast<std::uint32_t>(n_local)));
  for (int q = 0; q < m; ++q) {
    const auto pair = static_cast<std::uint64_t>(static_cast<std::uint32_t>(kept[q])) << 32U |
                      static_cast<std::uint32_t>(dofs[q]);
    key = KeyIndex::hash(key ^ pair);
  }
  return key == ~std::uint64_t{0} ? 0 : key; // all bits set: KeyIndex's empty slot
}

bool Assembler::has_pairs(const Plan& plan,
                          const std::vector<int>& kept_local,
                          const std::vector<int>& kept_dofs,
                          int n_local,
                          const int* kept,
                          const int* dofs,
                          int m) {
  const auto begin = static_cast<std::ptrdiff_t>(plan.kept_begin);
  return plan.n_local == n_local && plan.n_kept == m &&
         std::equal(kept, kept + m, kept_local.begin() + begin) &&
         std::equal(dofs, dofs + m, kept_dofs.begin() + begin);
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
  plans_.push_back(plans_[static_cast<std::size_t>(plan_id)]);
  return static_cast<int>(plans_.size()) - 1;
}

void Assembler::truncate_plans(int first) {
  NMM_ASSERT(first >= 0 && first <= n_plans(), "no such plan");
  if (known_.size() > 2 * plans_.size() + 1024)
    compact();
  plans_.resize(static_cast<std::size_t>(first));
}

void Assembler::compact() {
  std::vector<int> kept_local;
  std::vector<int> kept_dofs;
  std::vector<int> positions;
  std::vector<Repeat> repeats;
  std::vector<Plan> known;
  KeyIndex index(plans_.size());
  for (Plan& plan : plans_) {
    const auto kept = static_cast<std::ptrdiff_t>(plan.kept_begin);
    const int* local = kept_local_.data() + kept;
    const int* dofs = kept_dofs_.data() + kept;
    const std::uint64_t key = plan_key(plan.n_local, local, dofs, plan.n_kept);
    const int found = index.find(key);
    if (found != KeyIndex::none) {
      const Plan& moved = known[static_cast<std::size_t>(found)];
      if (has_pairs(moved, kept_local, kept_dofs, plan.n_local, local, dofs, plan.n_kept)) {
        plan = moved;
        continue;
      }
    }
    Plan copy = plan;
    copy.kept_begin = kept_local.size();
    kept_local.insert(kept_local.end(), local, local + plan.n_kept);
    kept_dofs.insert(kept_dofs.end(), dofs, dofs + plan.n_kept);
    copy.position_begin = positions.size();
    const auto first = positions_.begin() + static_cast<std::ptrdiff_t>(plan.position_begin);
    positions.insert(positions.end(), first,
                     first + static_cast<std::ptrdiff_t>(plan.n_kept) * (plan.n_kept + 1) / 2);
    copy.repeat_begin = repeats.size();
    repeats.insert(repeats.end(), repeats_.begin() + static_cast<std::ptrdiff_t>(plan.repeat_begin),
                   repeats_.begin() + static_cast<std::ptrdiff_t>(plan.repeat_end));
    copy.repeat_end = repeats.size();
    if (found == KeyIndex::none) {
      index.insert(key, static_cast<int>(known.size()));
      known.push_back(copy);
    }
    plan = copy;
  }
  kept_local_.swap(kept_local);
  kept_dofs_.swap(kept_dofs);
  positions_.swap(positions);
  repeats_.swap(repeats);
  known_.swap(known);
  std::swap(index_, index);
}

void Assembler::drop_data_from(const Plan& plan) {
  kept_local_.resize(plan.kept_begin);
  kept_dofs_.resize(plan.kept_begin);
  positions_.resize(plan.position_begin);
  repeats_.resize(plan.repeat_begin);
}

void Assembler::clear_plans() {
  plans_.clear();
  kept_local_.clear();
  kept_dofs_.clear();
  positions_.clear();
  repeats_.clear();
  known_.clear();
  index_.clear();
}

} // namespace nmm
