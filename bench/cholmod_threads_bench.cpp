// SPDX-License-Identifier: MIT
// CHOLMOD supernodal factor + solve of a 2D elasticity-like matrix (9-point stencil, 2 dofs
// per node) with the threads of OpenMP and OpenBLAS capped to the usable cores (what `nmm`
// does) against 1 thread, against an oversubscribed setting and against the solver's own
// choice (one thread for small factorizations), in the same process.
// Usage: bench_cholmod_threads [grid_n]   (dofs = 2 n^2; default n = 300 -> 1.8e5 dofs)
#include "solver/cholmod_solver.hpp"
#include "solver/threads.hpp"

#include "timing.hpp"

#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

nmm::SparseMatrix stencil_matrix(int n) {
  std::vector<Eigen::Triplet<double>> entries;
  const int dofs = 2 * n * n;
  entries.reserve(static_cast<std::size_t>(dofs) * 18 / 2);
  auto dof = [n](int i, int j, int c) { return 2 * (i * n + j) + c; };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int c = 0; c < 2; ++c) {
        // Upper triangle only, as the assembler will store it.
        for (int di = 0; di <= 1; ++di) {
          for (int dj = -1; dj <= 1; ++dj) {
            if (di == 0 && dj < 0)
              continue;
            const int i2 = i + di;
            const int j2 = j + dj;
            if (i2 >= n || j2 < 0 || j2 >= n)
              continue;
            for (int c2 = 0; c2 < 2; ++c2) {
              const int row = dof(i, j, c);
              const int col = dof(i2, j2, c2);
              if (col < row)
                continue;
              const double value = row == col ? 8.5 : (c == c2 ? -1.0 : 0.05);
              entries.emplace_back(row, col, value);
            }
          }
        }
      }
    }
  }
  nmm::SparseMatrix a(dofs, dofs);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

// Best of three factor+solve times with the given thread cap (analysis excluded). With
// @p automatic, the solver's own choice of one thread for small factorizations; otherwise
// every thread of the cap.
double factor_solve_seconds(const nmm::SparseMatrix& a, int threads, bool automatic = false) {
  nmm::limit_threads(threads);
  nmm::CholmodSolver solver;
  if (!automatic)
    solver.set_single_thread_flops(0.0);
  if (solver.analyze(a) != nmm::SolveStatus::ok)
    std::abort();
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(a.rows());
  Eigen::VectorXd x;
  return nmm::bench::best_seconds(
      3,
      [&] {
        if (solver.factorize(a) != nmm::SolveStatus::ok ||
            solver.solve(rhs, x) != nmm::SolveStatus::ok)
          std::abort();
      },
      3);
}

} // namespace

int main(int argc, char** argv) {
  const int n = argc > 1 ? std::atoi(argv[1]) : 300;
  const nmm::SparseMatrix a = stencil_matrix(n);
  const int cores = nmm::available_cores();
  std::printf("matrix: %ld dofs, %ld stored nonzeros; usable cores %d; %s\n",
              static_cast<long>(a.rows()), static_cast<long>(a.nonZeros()), cores,
              nmm::blas_description().c_str());
  {
    nmm::CholmodSolver probe;
    if (probe.analyze(a) != nmm::SolveStatus::ok)
      std::abort();
    std::printf("factorisation: %.3g flops\n", probe.factor_flops());
  }
  const double capped = factor_solve_seconds(a, cores);
  const double single = factor_solve_seconds(a, 1);
  const double oversubscribed = factor_solve_seconds(a, 4 * cores);
  const double automatic = factor_solve_seconds(a, cores, true);
  std::printf("factor+solve, threads capped to %d (baseline): %.3f s\n", cores, capped);
  std::printf("factor+solve, 1 thread:                      %.3f s  (%.2fx baseline)\n", single,
              single / capped);
  std::printf("factor+solve, %d threads (oversubscribed):    %.3f s  (%.2fx baseline)\n", 4 * cores,
              oversubscribed, oversubscribed / capped);
  std::printf("factor+solve, nmm's choice (1 thread below %.3g flops): %.3f s  (%.2fx baseline)\n",
              nmm::default_single_thread_flops, automatic, automatic / capped);
  return 0;
}
