// SPDX-License-Identifier: MIT
// solver/pcg_solver.hpp — conjugate gradients with a block-Jacobi preconditioner, falling
// back on CHOLMOD for a system it does not solve.
#pragma once

#include "solver/linear_solver.hpp"

#include <memory>

namespace nmm {

/// Tuning of PcgSolver.
struct PcgOptions {
  /// A solve has converged when the residual's 2-norm is at most this fraction of the
  /// right-hand side's.
  double tolerance = 1e-10;
  /// The tolerance of the solves of an open-close iteration while contacts still change
  /// mode (set_loose(true)): its modes are decided on a solution this close, and the
  /// iteration's last solve, once no mode changes, is done to `tolerance` (at most this
  /// tolerance is used; not looser than `tolerance`).
  double loose_tolerance = 1e-6;
  /// Iterations after which a solve gives up and is done by CHOLMOD instead.
  int max_iterations = 200;
  /// Most steps done by CHOLMOD alone after a step conjugate gradients gave up in (the
  /// number doubles from 1 with each such step and starts again after a step they solve).
  int max_skipped_steps = 64;
  /// A product with a matrix of at least this many stored entries runs its two halves on
  /// two threads (when there are); the results are the same either way.
  long parallel_entries = 200000;
};

/// Preconditioned conjugate gradients (DESIGN.md "Measured facts": in dynamic steps the
/// inertia term M 2/dt^2 makes the step matrix well conditioned, and a few iterations beat a
/// factorisation). The preconditioner is the inverse of the matrix's diagonal blocks, one
/// block per run of consecutive unknowns with the same pattern (the unknowns of one cover or
/// one DDA block). A solve starts from the solution vector it is given when it has the
/// system's size (the caller's guess) and from zero otherwise.
///
/// factorize() copies the values (the caller may change its matrix afterwards) and inverts
/// the diagonal blocks. A solve that does not reach the tolerance in max_iterations, or
/// meets a direction of non-positive curvature, is done again by CHOLMOD, and so is every
/// later one until the next analyze() or start_step(). After a step they gave up in, the
/// next 1, 2, 4, ... (at most max_skipped_steps) steps are done by CHOLMOD alone: a scene
/// whose systems conjugate gradients do not solve (static steps, stiff springs on light
/// blocks) pays the futile iterations in a few steps, not in every one.
/// A matrix that is not positive definite is reported as CHOLMOD reports it (with
/// failed_column()).
class PcgSolver final : public LinearSolver {
public:
  explicit PcgSolver(PcgOptions options = {});
  ~PcgSolver() override;

  [[nodiscard]] SolveStatus analyze(const SparseMatrix& matrix) override;
  [[nodiscard]] SolveStatus factorize(const SparseMatrix& matrix) override;
  [[nodiscard]] SolveStatus solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) override;
  [[nodiscard]] const SolverCounters& counters() const override;
  [[nodiscard]] std::string name() const override;
  [[nodiscard]] long failed_column() const override;
  bool set_loose(bool loose) override;
  /// Conjugate gradients are tried again on a pattern they gave up on in the last step,
  /// unless the step is one to skip.
  void start_step() override;
  /// The steps to skip: {the length of the next run of them, the steps of this run still to
  /// skip, whether the last step was tried, whether it gave up}.
  [[nodiscard]] std::vector<int> carried() const override;
  [[nodiscard]] bool restore_carried(const std::vector<int>& carried) override;
  /// Whether the step begun last goes to CHOLMOD without conjugate gradients.
  [[nodiscard]] bool skipping() const;

  /// Sizes of the preconditioner's diagonal blocks from the last analyze(), in order.
  [[nodiscard]] std::vector<int> block_sizes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace nmm
