// SPDX-License-Identifier: MIT
// solver/low_rank_solve.hpp — a factorised symmetric matrix plus an unsymmetric term of low
// rank (friction coupled to the normal force in the solve), by GMRES preconditioned with the
// factor.
#pragma once

#include "solver/linear_solver.hpp"

namespace nmm {

/// What solve_low_rank_update() did.
struct LowRankSolveReport {
  SolveStatus status = SolveStatus::ok;
  bool converged = false;
  int iterations = 0;             ///< GMRES iterations: one solve with the factor each
  double relative_residual = 0.0; ///< the last ||b - (A + U V^T) x|| / ||b|| GMRES estimated
};

/// Solves (A + U V^T) x = b, where @p factor holds the factorisation of the symmetric matrix
/// A (@p a, its upper triangle) and U, V are n x m with m small against n, starting from
/// @p x when it has the system's size (the caller's guess: GMRES then solves for the
/// correction) and from zero otherwise: GMRES on (A + U V^T) A^-1 y = r, x = x0 + A^-1 y
/// (right preconditioning by the factor; Saad, Iterative Methods for Sparse Linear Systems,
/// 2nd ed., 2003, sections 6.5 and 9.3). The preconditioned matrix is I + U (V^T A^-1),
/// the identity plus a term of rank m, so in exact arithmetic GMRES ends within m + 1
/// iterations; its residual is that of the preconditioned system, as exact as the factor's
/// solves. Stops when the residual is at most @p tolerance ||b|| or after
/// @p max_iterations (converged false). When @p factor solves only approximately (conjugate
/// gradients: @p exact_solves false), each iteration multiplies by A + U V^T itself instead
/// of taking A A^-1 q = q, and the method is flexible GMRES (Saad 2003, 9.4.1): the solves
/// may differ from iteration to iteration and the residual stays the true one.
[[nodiscard]] LowRankSolveReport solve_low_rank_update(LinearSolver& factor,
                                                       const SparseMatrix& a,
                                                       const SparseMatrix& u,
                                                       const SparseMatrix& v,
                                                       const Eigen::VectorXd& b,
                                                       Eigen::VectorXd& x,
                                                       double tolerance,
                                                       int max_iterations,
                                                       bool exact_solves = true);

} // namespace nmm
