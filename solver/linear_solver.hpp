// SPDX-License-Identifier: MIT
// solver/linear_solver.hpp — the interface every linear solver of the step loop implements.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include <string>
#include <vector>

namespace nmm {

/// A symmetric matrix in compressed column storage; solvers read its upper triangle only.
using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

/// Outcome of a linear-solver call. Numerical failures are reported, not thrown, so the
/// stepper can react (cut the step, report a free body).
enum class SolveStatus {
  ok,
  not_positive_definite, ///< a pivot was zero or negative: a free body or a bad penalty
  failed,                ///< anything else (out of memory, wrong call order)
};

/// Human-readable name of a status, for messages.
[[nodiscard]] const char* to_string(SolveStatus status);

/// Work counters, reported in summary.json so "skip what the scene does not need" is
/// measurable.
struct SolverCounters {
  long symbolic_analyses = 0;
  long factorizations = 0;
  long solves = 0;
  long iterations = 0; ///< conjugate-gradient iterations (PcgSolver)
  long fallbacks = 0;  ///< solves PcgSolver left to CHOLMOD
};

/// Symmetric positive definite solver with a reusable symbolic analysis.
///
/// Call order: analyze() once per sparsity pattern, factorize() whenever the values change,
/// solve() any number of times per factorization. Owned through std::unique_ptr.
class LinearSolver {
public:
  LinearSolver() = default;
  LinearSolver(const LinearSolver&) = delete;
  LinearSolver& operator=(const LinearSolver&) = delete;
  LinearSolver(LinearSolver&&) = delete;
  LinearSolver& operator=(LinearSolver&&) = delete;
  virtual ~LinearSolver() = default;

  /// Orders and analyses the pattern of @p matrix (square, compressed, upper triangle used).
  [[nodiscard]] virtual SolveStatus analyze(const SparseMatrix& matrix) = 0;
  /// Numerical factorization of @p matrix, which must have the analysed pattern.
  [[nodiscard]] virtual SolveStatus factorize(const SparseMatrix& matrix) = 0;
  /// Solves A x = rhs with the last factorization; @p solution is resized as needed (an
  /// output argument so that the step loop can reuse its storage). An iterative solver
  /// starts from @p solution when it has the system's size: the caller's guess.
  [[nodiscard]] virtual SolveStatus solve(const Eigen::VectorXd& rhs,
                                          Eigen::VectorXd& solution) = 0;
  /// Counts of the calls above that succeeded.
  [[nodiscard]] virtual const SolverCounters& counters() const = 0;
  /// Short description, e.g. "CHOLMOD 3.0.14 supernodal".
  [[nodiscard]] virtual std::string name() const = 0;
  /// A new time step begins: an iterative solver forgets what it learned of the last one's
  /// systems, so that a run restarted at this step does the same arithmetic as one that was
  /// not stopped.
  virtual void start_step() {}
  /// What the solver carries from one step to the next beyond its counters, for a restart
  /// checkpoint: empty for a solver that carries nothing.
  [[nodiscard]] virtual std::vector<int> carried() const { return {}; }
  /// Takes back what carried() gave (a solver that carries nothing ignores it); false, and
  /// nothing changed, when it is not what this solver can carry.
  [[nodiscard]] virtual bool restore_carried(const std::vector<int>& /*carried*/) { return true; }
  /// The matrix's own column at which the last call that returned not_positive_definite met
  /// a non-positive pivot, or -1.
  [[nodiscard]] virtual long failed_column() const = 0;
  /// An iterative solver's solves from now on stop at its loose tolerance (true) or at its
  /// own (false). Returns whether the solver has a loose tolerance (a direct solver, which
  /// solves exactly, ignores the call and returns false).
  virtual bool set_loose(bool /*loose*/) { return false; }
};

} // namespace nmm
