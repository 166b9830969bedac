// SPDX-License-Identifier: MIT
// solver/low_rank_solve.cpp — GMRES on a factorised symmetric matrix plus a low-rank term.
#include "solver/low_rank_solve.hpp"

#include "mesh/error.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <cstddef>
#include <vector>

namespace nmm {

LowRankSolveReport solve_low_rank_update(LinearSolver& factor,
                                         const SparseMatrix& a,
                                         const SparseMatrix& u,
                                         const SparseMatrix& v,
                                         const Eigen::VectorXd& b,
                                         Eigen::VectorXd& x,
                                         double tolerance,
                                         int max_iterations,
                                         bool exact_solves) {
  NMM_ASSERT(u.rows() == b.size() && v.rows() == b.size() && u.cols() == v.cols(),
             "U and V are n x m for a system of n unknowns");
  NMM_ASSERT(max_iterations > 0, "GMRES needs at least one iteration");
  LowRankSolveReport report;
  const double scale = b.norm(); // the tolerance is relative to the right side
  if (scale == 0.0) {            // x = 0, whatever the guess
    x.setZero(b.size());
    report.converged = true;
    return report;
  }
  // (A + U V^T) y, A stored as its upper triangle.
  auto times_system = [&](const Eigen::VectorXd& y) -> Eigen::VectorXd {
    return a.selfadjointView<Eigen::Upper>() * y + u * (v.transpose() * y);
  };
  Eigen::VectorXd residual = b;
  if (x.size() == b.size())
    residual -= times_system(x);
  else
    x.setZero(b.size());
  const double beta = residual.norm();
  report.relative_residual = beta / scale;
  if (beta <= tolerance * scale) {
    report.converged = true;
    return report;
  }
  const auto n_max = static_cast<std::size_t>(max_iterations);
  // Arnoldi basis q_k, their preconditioned images z_k = A^-1 q_k (x is a combination of
  // these, so no solve is needed at the end), the Hessenberg matrix reduced by Givens
  // rotations (c, s) to upper triangular, and the rotated right side g.
  std::vector<Eigen::VectorXd> q;
  std::vector<Eigen::VectorXd> z;
  q.reserve(n_max + 1);
  z.reserve(n_max);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(max_iterations + 1, max_iterations);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(max_iterations);
  Eigen::VectorXd s = Eigen::VectorXd::Zero(max_iterations);
  Eigen::VectorXd g = Eigen::VectorXd::Zero(max_iterations + 1);
  g(0) = beta;
  q.push_back(residual / beta);
  Eigen::VectorXd w;
  int k = 0;
  while (k < max_iterations) {
    const auto kk = static_cast<std::size_t>(k);
    z.emplace_back(); // empty: an iterative solve starts from zero
    report.status = factor.solve(q[kk], z[kk]);
    if (report.status != SolveStatus::ok)
      return report;
    // (A + U V^T) A^-1 q_k = q_k + U (V^T z_k) when the solve is exact.
    if (exact_solves)
      w = q[kk] + u * (v.transpose() * z[kk]);
    else
      w = times_system(z[kk]);
    for (int i = 0; i <= k; ++i) { // modified Gram-Schmidt
      h(i, k) = q[static_cast<std::size_t>(i)].dot(w);
      w -= h(i, k) * q[static_cast<std::size_t>(i)];
    }
    const double next = w.norm();
    for (int i = 0; i < k; ++i) {
      const double t = c(i) * h(i, k) + s(i) * h(i + 1, k);
      h(i + 1, k) = -s(i) * h(i, k) + c(i) * h(i + 1, k);
      h(i, k) = t;
    }
    const double r = std::hypot(h(k, k), next);
    if (r == 0.0) // the preconditioned matrix is singular: A + U V^T is
      break;
    c(k) = h(k, k) / r;
    s(k) = next / r;
    h(k, k) = r;
    g(k + 1) = -s(k) * g(k);
    g(k) *= c(k);
    ++k;
    report.relative_residual = std::abs(g(k)) / scale;
    if (report.relative_residual <= tolerance || next == 0.0) {
      report.converged = true;
      break;
    }
    q.push_back(w / next);
  }
  report.iterations = k;
  if (k > 0) {
    const Eigen::VectorXd y = h.topLeftCorner(k, k).triangularView<Eigen::Upper>().solve(g.head(k));
    for (int i = 0; i < k; ++i)
      x += y(i) * z[static_cast<std::size_t>(i)];
  }
  return report;
}

} // namespace nmm
