// SPDX-License-Identifier: MIT
// solver/dof_map.hpp — from the model's raw unknowns to the unknowns of the linear system,
// by exact elimination of linear constraints (tiny-cover extensions, fixed boundaries,
// order-1 dependency fixes): d_raw = T d_reduced + t0.
#pragma once

#include "manifold/linear_constraint.hpp"

#include <Eigen/Core>

#include <span>
#include <string>
#include <utility>
#include <vector>

namespace nmm {

/// The expansion of one raw unknown: either a free unknown of the system or a combination
/// of free unknowns plus a constant.
struct DofExpansion {
  std::vector<std::pair<int, double>> terms; ///< (reduced index, coefficient)
  double constant = 0.0;
};

/// Statistics of the elimination, for summary.json and tests.
struct DofMapStats {
  int constraints = 0;
  int eliminated = 0; ///< raw unknowns that became slaves
  int redundant = 0;  ///< constraints implied by the others (dropped)
};

/// Raw unknowns -> system unknowns (DESIGN.md "dof map").
///
/// Constraints are eliminated in the order given, each by Gaussian elimination against
/// the slaves chosen before it: a constraint that reduces to 0 = 0 is redundant (a fixed
/// point repeating an earlier one, or a flex fix implied by a support) and is dropped; one
/// that reduces to 0 = c != 0 is contradictory and reported. Slaves are always expressed in
/// free unknowns only (no chains), so assembly needs one expansion per raw unknown.
class DofMap {
public:
  /// @param n_raw        number of raw unknowns.
  /// @param constraints  rows in elimination order.
  /// @param tolerance    a reduced coefficient below tolerance × the row's largest original
  ///                     coefficient counts as zero.
  /// @param length       the model's size (m): redundant rows that disagree by less than
  ///                     1e-9 of it agree (support points carry the rounding of their moves,
  ///                     and each row corrects its own point's drift).
  /// @param previous     the map of the last step, or null: where a row may pivot on an
  ///                     unknown that was a slave there (with at least a tenth of the row's
  ///                     largest coefficient), it does. Coefficients of supports on a moving
  ///                     geometry change a little from step to step; without this, near ties
  ///                     swap slaves, and every step gets a new sparsity pattern and symbolic
  ///                     analysis (bench/step_bench.cpp, order 1).
  /// @throws InputError when constraints contradict each other (naming both origins).
  DofMap(int n_raw,
         std::span<const LinearConstraint> constraints,
         double tolerance = 1e-12,
         double length = 1.0,
         const DofMap* previous = nullptr);

  [[nodiscard]] int n_raw() const noexcept { return static_cast<int>(reduced_of_.size()); }
  [[nodiscard]] int n_reduced() const noexcept { return n_reduced_; }
  /// Reduced index of a free raw unknown, or -1 for a slave.
  [[nodiscard]] int reduced(int raw) const { return reduced_of_[static_cast<std::size_t>(raw)]; }
  [[nodiscard]] bool is_slave(int raw) const { return reduced(raw) < 0; }
  /// The expansion of any raw unknown (a single term with coefficient 1 for a free one).
  [[nodiscard]] DofExpansion expansion(int raw) const;
  /// d_raw = T d_reduced + t0.
  [[nodiscard]] Eigen::VectorXd expand(const Eigen::VectorXd& reduced) const;
  /// T^T v: the reduced form of a raw load vector (ignores t0).
  [[nodiscard]] Eigen::VectorXd restrict(const Eigen::VectorXd& raw) const;
  [[nodiscard]] const DofMapStats& stats() const noexcept { return stats_; }

private:
  std::vector<int> reduced_of_;
  std::vector<DofExpansion> slaves_; ///< indexed by raw unknown; meaningful for slaves
  int n_reduced_ = 0;
  DofMapStats stats_;
};

} // namespace nmm
