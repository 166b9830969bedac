// SPDX-License-Identifier: MIT
// solver/cholmod_solver.hpp — supernodal Cholesky by CHOLMOD (the only CHOLMOD user).
#pragma once

#include "solver/linear_solver.hpp"

#include <memory>

namespace nmm {

/// CholmodSolver::set_single_thread_flops() default.
inline constexpr double default_single_thread_flops = 2e9;

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

  /// Factorizations below this many floating-point operations, and the solves with their
  /// factors, run BLAS on one thread: on
  /// the 2-core machine kind one thread was as fast or faster up to 1.8e9 flops (about 1e5
  /// unknowns of order 0) and two threads 10 % faster at 5e9 (docs/benchmarks.md "CHOLMOD
  /// threads"); 0 uses every thread limit_threads() allows for every size.
  void set_single_thread_flops(double flops);

  /// Floating-point operations of one numeric factorization, CHOLMOD's count from the last
  /// analyze() (0 before it).
  [[nodiscard]] double factor_flops() const;

  [[nodiscard]] long failed_column() const override;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// "CHOLMOD x.y.z".
[[nodiscard]] std::string cholmod_version();

} // namespace nmm
