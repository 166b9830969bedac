// SPDX-License-Identifier: MIT
// solver/cholmod_solver.hpp — supernodal Cholesky by CHOLMOD (the only CHOLMOD user).
#pragma once

#include "solver/linear_solver.hpp"

#include <memory>

namespace nmm {

/// CHOLMOD supernodal LL^T with the symbolic analysis (fill-reducing ordering) kept until
/// the next analyze(); numeric refactorizations reuse it (DESIGN.md "Numerical choices").
class CholmodSolver final : public LinearSolver {
public:
  CholmodSolver();
  ~CholmodSolver() override;

  [[nodiscard]] SolveStatus analyze(const SparseMatrix& matrix) override;
  [[nodiscard]] SolveStatus factorize(const SparseMatrix& matrix) override;
  [[nodiscard]] SolveStatus solve(const Eigen::VectorXd& rhs, Eigen::VectorXd& solution) override;
  [[nodiscard]] const SolverCounters& counters() const override;
  [[nodiscard]] std::string name() const override;

  /// Column at which the last failed factorization met a non-positive pivot, or -1.
  [[nodiscard]] long failed_column() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "CHOLMOD x.y.z".
[[nodiscard]] std::string cholmod_version();

} // namespace nmm
