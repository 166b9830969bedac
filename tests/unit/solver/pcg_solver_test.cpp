// SPDX-License-Identifier: MIT
#include "solver/cholmod_solver.hpp"
#include "solver/pcg_solver.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace nmm {
namespace {

// A row of `blocks` blocks of `size` unknowns, as the step matrix of DDA blocks in a row:
// each block's own mass matrix (a dense SPD one, `mass` times about the identity), and
// between neighbours a spring `spring` [C, -C; -C, C] that couples all their unknowns (C =
// 0.9 I + 0.1 ones / size, SPD). Full symmetric storage; `spring` / `mass` sets the
// condition number (about 4 spring / mass + 1).
SparseMatrix block_row(int blocks, int size, double mass, double spring) {
  std::vector<Eigen::Triplet<double>> entries;
  for (int b = 0; b < blocks; ++b) {
    for (int i = 0; i < size; ++i) {
      for (int j = 0; j < size; ++j) {
        const int r = b * size + i;
        const int c = b * size + j;
        entries.emplace_back(r, c, i == j ? mass * (1.0 + 0.1 * i) : 0.05 * mass);
        if (b + 1 < blocks) {
          const double coupling = spring * ((i == j ? 0.9 : 0.0) + 0.1 / size);
          entries.emplace_back(r, c, coupling);
          entries.emplace_back(r + size, c + size, coupling);
          entries.emplace_back(r, c + size, -coupling);
          entries.emplace_back(r + size, c, -coupling);
        }
      }
    }
  }
  const int n = blocks * size;
  SparseMatrix a(n, n);
  a.setFromTriplets(entries.begin(), entries.end());
  a.makeCompressed();
  return a;
}

SparseMatrix upper(const SparseMatrix& full) {
  SparseMatrix a = full.triangularView<Eigen::Upper>();
  a.makeCompressed();
  return a;
}

// A fresh analysis, factorisation and solve (from no guess) of A x = rhs by @p solver.
Eigen::VectorXd
solve_anew(LinearSolver& solver, const SparseMatrix& a, const Eigen::VectorXd& rhs) {
  EXPECT_EQ(solver.analyze(a), SolveStatus::ok);
  EXPECT_EQ(solver.factorize(a), SolveStatus::ok);
  Eigen::VectorXd x;
  EXPECT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  return x;
}

Eigen::VectorXd cholmod_solution(const SparseMatrix& a, const Eigen::VectorXd& rhs) {
  CholmodSolver direct;
  return solve_anew(direct, a, rhs);
}

TEST(PcgSolver, SolvesABlockSystemAsCholmodDoes) {
  // Springs 20 times the mass term: a condition number of about 80 (the block-Jacobi
  // preconditioned one lower), so the residual tolerance 1e-12 bounds the error by 1e-10 of
  // the solution, and CHOLMOD's own rounding is 1e-14 of it.
  const SparseMatrix a = upper(block_row(200, 6, 1.0, 20.0));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  PcgSolver solver(PcgOptions{.tolerance = 1e-12, .max_iterations = 1000});
  const Eigen::VectorXd x = solve_anew(solver, a, rhs);
  const Eigen::VectorXd expected = cholmod_solution(a, rhs);
  EXPECT_LT((x - expected).norm(), 1e-10 * expected.norm());
  EXPECT_EQ(solver.block_sizes(), std::vector<int>(200, 6));
  EXPECT_GT(solver.counters().iterations, 0);
  EXPECT_EQ(solver.counters().fallbacks, 0);
  EXPECT_EQ(solver.counters().factorizations, 0);
  EXPECT_EQ(solver.counters().solves, 1);
}

TEST(PcgSolver, ReadsOnlyTheUpperTriangle) {
  SparseMatrix full = block_row(30, 6, 1.0, 5.0);
  const SparseMatrix a = upper(full);
  for (int k = 0; k < full.outerSize(); ++k) { // a lower triangle that would be wrong
    for (SparseMatrix::InnerIterator it(full, k); it; ++it) {
      if (it.row() > it.col())
        it.valueRef() = 1e6;
    }
  }
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(a.rows());
  PcgSolver upper_solver;
  PcgSolver full_solver;
  const Eigen::VectorXd from_upper = solve_anew(upper_solver, a, rhs);
  const Eigen::VectorXd from_full = solve_anew(full_solver, full, rhs);
  EXPECT_EQ(upper_solver.counters().fallbacks + full_solver.counters().fallbacks, 0);
  EXPECT_EQ(from_upper, from_full); // the same arithmetic, to the last bit
}

TEST(PcgSolver, AProductOnTwoThreadsGivesTheSameSolutionToTheBit) {
  // The product's two halves on two threads (from 0 stored entries on) and on this one (never
  // on two): the same numbers, whatever the machine's threads.
  const SparseMatrix a = upper(block_row(3000, 6, 1.0, 20.0));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  PcgSolver threads(PcgOptions{.parallel_entries = 0});
  PcgSolver one(PcgOptions{.parallel_entries = a.nonZeros() + 1});
  const Eigen::VectorXd x = solve_anew(threads, a, rhs);
  EXPECT_EQ(x, solve_anew(one, a, rhs));
  EXPECT_EQ(threads.counters().iterations, one.counters().iterations);
  EXPECT_EQ(threads.counters().fallbacks, 0);
  const Eigen::VectorXd expected = cholmod_solution(a, rhs);
  EXPECT_LT((x - expected).norm(), 1e-8 * expected.norm()); // tolerance 1e-10, condition ~80
}

TEST(PcgSolver, SolvesAMatrixWithScatteredEntriesAsCholmodDoes) {
  // Blocks of 1 to 12 unknowns (the product's fixed-size paths for 2 and 6 and the general
  // one) coupled by single entries far apart, so that a column's entries above the diagonal
  // form runs of every length from 1 on, with gaps between them. A diagonal of 12 against
  // couplings of at most 0.5 with at most 6 a row: diagonally dominant, condition < 2.
  std::vector<Eigen::Triplet<double>> entries;
  int n = 0;
  std::vector<int> first;
  for (int b = 0; b < 60; ++b) {
    const int size = 1 + (b * 7) % 12;
    first.push_back(n);
    for (int i = 0; i < size; ++i) {
      for (int j = 0; j < size; ++j)
        entries.emplace_back(n + i, n + j, i == j ? 12.0 : 0.01 * (i + j + 1));
    }
    n += size;
  }
  for (int b = 0; b + 5 < 60; ++b) { // block b's first unknowns with parts of block b + 5
    const int far = first[static_cast<std::size_t>(b) + 5];
    for (int k = 0; k < 3; ++k) {
      const int r = first[static_cast<std::size_t>(b)];
      const int c = far + k * k; // rows 0, 1 and 4 of the far block: runs with a gap
      if (c >= (b + 6 < 60 ? first[static_cast<std::size_t>(b) + 6] : n))
        continue;
      entries.emplace_back(r, c, -0.5 + 0.1 * k);
      entries.emplace_back(c, r, -0.5 + 0.1 * k);
    }
  }
  SparseMatrix full(n, n);
  full.setFromTriplets(entries.begin(), entries.end());
  full.makeCompressed();
  const SparseMatrix a = upper(full);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(n, -2.0, 1.0);
  PcgSolver solver(PcgOptions{.tolerance = 1e-13, .max_iterations = 200});
  const Eigen::VectorXd x = solve_anew(solver, a, rhs);
  EXPECT_EQ(solver.counters().fallbacks, 0);
  // Residual 1e-13 of the right side, condition < 2: the error within 1e-12 of the solution.
  const Eigen::VectorXd expected = cholmod_solution(a, rhs);
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((full * x - rhs).norm(), 1e-12 * rhs.norm());
}

TEST(PcgSolver, AFactorisationOfChangedValuesSolvesAsAFreshSolverToTheBit) {
  // factorize() keeps the inverse of a diagonal block whose values did not change: after
  // the coupling of two blocks changes (the springs of an open-close iteration), and after
  // one block's own values do, the kept solver's solution and iterations are a fresh one's,
  // to the bit. A stale inverse would still converge, but not by the same iterations.
  const SparseMatrix a = upper(block_row(400, 6, 1.0, 20.0));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  PcgSolver kept;
  solve_anew(kept, a, rhs);
  SparseMatrix changed = a;
  for (int k = 0; k < changed.outerSize(); ++k) {
    for (SparseMatrix::InnerIterator it(changed, k); it; ++it) {
      if (it.row() / 6 == 100 && it.col() / 6 == 101) // the spring between blocks 100, 101
        it.valueRef() *= 3.0;
      if ((it.row() / 6 == 100 || it.row() / 6 == 101) && it.col() / 6 == it.row() / 6)
        it.valueRef() += it.row() == it.col() ? 2.0 * 20.0 : 0.0; // its share on their diagonals
      if (it.row() / 6 == 250 && it.col() / 6 == 250 && it.row() != it.col())
        it.valueRef() *= 0.5; // one block's own values
    }
  }
  for (const SparseMatrix* m : std::vector<const SparseMatrix*>{&changed, &a}) {
    ASSERT_EQ(kept.factorize(*m), SolveStatus::ok);
    Eigen::VectorXd x;
    const long before = kept.counters().iterations;
    ASSERT_EQ(kept.solve(rhs, x), SolveStatus::ok);
    PcgSolver fresh;
    EXPECT_EQ(x, solve_anew(fresh, *m, rhs));
    EXPECT_EQ(kept.counters().iterations - before, fresh.counters().iterations);
  }
}

TEST(PcgSolver, StartsFromTheGuessItIsGiven) {
  const SparseMatrix a = upper(block_row(50, 2, 1.0, 10.0));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), 1.0, 3.0);
  PcgSolver solver;
  Eigen::VectorXd x = solve_anew(solver, a, rhs);
  const long from_zero = solver.counters().iterations;
  EXPECT_GT(from_zero, 3);
  // A guess that solves the system already (to rounding) costs no iteration.
  const Eigen::VectorXd first = x;
  Eigen::VectorXd exact = cholmod_solution(a, rhs);
  const Eigen::VectorXd exact_guess = exact;
  ASSERT_EQ(solver.solve(rhs, exact), SolveStatus::ok);
  EXPECT_EQ(solver.counters().iterations, from_zero);
  EXPECT_EQ(exact, exact_guess);
  // A guess of the wrong size (or none) starts from zero: the same iterations again.
  Eigen::VectorXd wrong_size = Eigen::VectorXd::Ones(3);
  ASSERT_EQ(solver.solve(rhs, wrong_size), SolveStatus::ok);
  EXPECT_EQ(solver.counters().iterations, 2 * from_zero);
  EXPECT_EQ(wrong_size, first);
  // A zero right-hand side has the zero solution, whatever the guess.
  Eigen::VectorXd guess = Eigen::VectorXd::Ones(a.rows());
  ASSERT_EQ(solver.solve(Eigen::VectorXd::Zero(a.rows()), guess), SolveStatus::ok);
  EXPECT_EQ(guess, Eigen::VectorXd::Zero(a.rows()));
}

TEST(PcgSolver, LooseSolvesStopAtTheLooseToleranceAndTightOnesGoOnFromThem) {
  // What the open-close iteration does: modes decided on solves to loose_tolerance, the last
  // solve to tolerance from the loose solution. The residuals are measured here, not taken
  // from the solver: each solve ends within its own tolerance, the loose one not below a
  // hundredth of it (conjugate gradients on this matrix of condition ~41 gain less than two
  // orders an iteration), and the tight one from the loose guess takes fewer iterations
  // than one from zero.
  const SparseMatrix full = block_row(200, 3, 1.0, 10.0);
  const SparseMatrix a = upper(full);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  const auto relative_residual = [&](const Eigen::VectorXd& x) {
    return (full * x - rhs).norm() / rhs.norm();
  };
  PcgSolver tight_only(PcgOptions{.tolerance = 1e-10, .loose_tolerance = 1e-4});
  const Eigen::VectorXd reference = solve_anew(tight_only, a, rhs);
  const long from_zero = tight_only.counters().iterations;
  EXPECT_LE(relative_residual(reference), 1e-10);

  PcgSolver solver(PcgOptions{.tolerance = 1e-10, .loose_tolerance = 1e-4});
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
  EXPECT_TRUE(solver.set_loose(true));
  Eigen::VectorXd x;
  ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  const long loose = solver.counters().iterations;
  EXPECT_LE(relative_residual(x), 1e-4);
  EXPECT_GT(relative_residual(x), 1e-6);
  EXPECT_LT(loose, from_zero);
  EXPECT_TRUE(solver.set_loose(false));
  ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  EXPECT_LE(relative_residual(x), 1e-10);
  EXPECT_LT(solver.counters().iterations - loose, from_zero);
  EXPECT_LE((x - reference).norm(), 1e-8 * reference.norm());

  // A loose tolerance at or below the solver's own changes nothing, and says so.
  PcgSolver not_loose(PcgOptions{.tolerance = 1e-10, .loose_tolerance = 1e-12});
  EXPECT_FALSE(not_loose.set_loose(true));
  EXPECT_EQ(solve_anew(not_loose, a, rhs), reference);
  // A direct solver has no loose tolerance.
  CholmodSolver direct;
  EXPECT_FALSE(direct.set_loose(true));
}

TEST(PcgSolver, HandsWhatItDoesNotSolveToCholmodForTheRestOfTheStep) {
  // Springs 1e4 times the mass term: far more than 3 iterations.
  const SparseMatrix a = upper(block_row(100, 3, 1.0, 1e4));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -2.0, 1.0);
  PcgSolver solver(PcgOptions{.tolerance = 1e-12, .max_iterations = 3});
  auto expect_counts = [&](long iterations, long fallbacks, long factorizations) {
    EXPECT_EQ(solver.counters().iterations, iterations);
    EXPECT_EQ(solver.counters().fallbacks, fallbacks);
    EXPECT_EQ(solver.counters().factorizations, factorizations);
  };
  Eigen::VectorXd x = solve_anew(solver, a, rhs);
  // CHOLMOD's answer to the last bit: the fallback is its solve, nothing mixed in.
  EXPECT_EQ(x, cholmod_solution(a, rhs));
  expect_counts(3, 1, 1);
  // The next solve with the same values uses that factor: no iteration, no factorisation.
  ASSERT_EQ(solver.solve(2.0 * rhs, x), SolveStatus::ok);
  EXPECT_EQ(x, cholmod_solution(a, 2.0 * rhs));
  expect_counts(3, 2, 1); // every solve done by CHOLMOD
  EXPECT_EQ(solver.counters().solves, 2);
  // New values of the same pattern (a factorisation, then a solve from no guess) in the same
  // step: CHOLMOD at once, without futile iterations.
  auto factorize_and_solve = [&] {
    ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
    Eigen::VectorXd no_guess;
    ASSERT_EQ(solver.solve(rhs, no_guess), SolveStatus::ok);
  };
  factorize_and_solve();
  expect_counts(3, 3, 2);
  // The next step is done by CHOLMOD alone (a step they gave up in is followed by one
  // skipped), the one after goes back to conjugate gradients.
  solver.start_step();
  EXPECT_TRUE(solver.skipping());
  factorize_and_solve();
  expect_counts(3, 4, 3);
  solver.start_step();
  EXPECT_FALSE(solver.skipping());
  factorize_and_solve();
  expect_counts(6, 5, 4);
  // A new analysis tries conjugate gradients again (from zero, as before).
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  factorize_and_solve();
  expect_counts(9, 6, 5);
}

// One step of a run: start_step(), then the step's system solved from no guess.
// @return whether conjugate gradients were tried in it.
bool run_step(PcgSolver& solver, const SparseMatrix& a, const Eigen::VectorXd& rhs) {
  solver.start_step();
  const long before = solver.counters().iterations;
  EXPECT_EQ(solver.factorize(a), SolveStatus::ok);
  Eigen::VectorXd x;
  EXPECT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  return solver.counters().iterations > before;
}

TEST(PcgSolver, SkipsMoreStepsAfterEachStepItGaveUpInAndNoneAfterOneItSolved) {
  // The same pattern with springs 1e4 times the mass term (far more than 3 iterations) and
  // 1e-6 times it (2 iterations: the preconditioner is nearly the inverse).
  const SparseMatrix hard = upper(block_row(100, 3, 1.0, 1e4));
  const SparseMatrix easy = upper(block_row(100, 3, 1.0, 1e-6));
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(hard.rows(), -2.0, 1.0);
  const PcgOptions options{.tolerance = 1e-12, .max_iterations = 3, .max_skipped_steps = 4};
  PcgSolver solver(options);
  ASSERT_EQ(solver.analyze(hard), SolveStatus::ok);
  std::vector<int> tried;
  for (int step = 1; step <= 20; ++step) {
    if (run_step(solver, hard, rhs))
      tried.push_back(step);
  }
  // Given up in steps 1, 3, 6, 11, 16: then 1, 2, 4 and (at most) 4 steps skipped.
  EXPECT_EQ(tried, (std::vector<int>{1, 3, 6, 11, 16}));
  EXPECT_EQ(solver.counters().fallbacks, 20);
  EXPECT_EQ(solver.counters().iterations, 15);
  // A checkpoint between steps: a solver restored from it skips the same steps.
  PcgSolver restored(options);
  ASSERT_TRUE(restored.restore_carried(solver.carried()));
  ASSERT_EQ(restored.analyze(hard), SolveStatus::ok);
  // Step 21 is tried and given up in (4 steps skipped), 26 solves the easy system: after it
  // nothing is skipped, and the next give-up (27) skips one step again.
  std::vector<int> tried_after;
  std::vector<int> tried_restored;
  for (int step = 21; step <= 29; ++step) {
    const SparseMatrix& a = step == 26 ? easy : hard;
    if (run_step(solver, a, rhs))
      tried_after.push_back(step);
    if (run_step(restored, a, rhs))
      tried_restored.push_back(step);
  }
  EXPECT_EQ(tried_after, (std::vector<int>{21, 26, 27, 29}));
  EXPECT_EQ(tried_restored, tried_after);
  EXPECT_EQ(solver.carried(), restored.carried());
  // What is not a solver's state is refused; a checkpoint of a run by CHOLMOD (nothing
  // carried) skips nothing.
  PcgSolver other(options);
  EXPECT_FALSE(other.restore_carried({1, 2, 0, 0})); // more left than the run is long
  EXPECT_FALSE(other.restore_carried({1, 0, 2, 0}));
  EXPECT_FALSE(other.restore_carried({-1, 0, 0, 0}));
  EXPECT_FALSE(other.restore_carried({1, 0, 0}));
  EXPECT_TRUE(other.restore_carried({}));
  ASSERT_EQ(other.analyze(hard), SolveStatus::ok);
  EXPECT_TRUE(run_step(other, hard, rhs));
}

TEST(PcgSolver, ReportsAMatrixThatIsNotPositiveDefiniteWhereCholmodDoes) {
  // A diagonal block that is not positive definite: factorize() says so at once.
  SparseMatrix a = upper(block_row(20, 6, 1.0, 1.0));
  a.coeffRef(61, 61) = -1.0;
  PcgSolver solver;
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  EXPECT_EQ(solver.factorize(a), SolveStatus::not_positive_definite);
  CholmodSolver direct;
  ASSERT_EQ(direct.analyze(a), SolveStatus::ok);
  ASSERT_EQ(direct.factorize(a), SolveStatus::not_positive_definite);
  EXPECT_EQ(solver.failed_column(), direct.failed_column());
  EXPECT_GE(solver.failed_column(), 0);
  Eigen::VectorXd x;
  EXPECT_NE(solver.solve(Eigen::VectorXd::Ones(a.rows()), x), SolveStatus::ok);

  // Positive diagonal blocks, an indefinite whole (a ring of springs, less 0.01 on the
  // diagonal: eigenvalues -0.01 to 3.99): the solve finds it, through CHOLMOD.
  const int n = 40;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i, 2.0 - 0.01);
    entries.emplace_back(std::min(i, (i + 1) % n), std::max(i, (i + 1) % n), -1.0);
  }
  SparseMatrix ring(n, n);
  ring.setFromTriplets(entries.begin(), entries.end());
  ring.makeCompressed();
  PcgSolver ring_solver;
  ASSERT_EQ(ring_solver.analyze(ring), SolveStatus::ok);
  ASSERT_EQ(ring_solver.factorize(ring), SolveStatus::ok);
  EXPECT_EQ(ring_solver.solve(Eigen::VectorXd::Ones(n), x), SolveStatus::not_positive_definite);
  EXPECT_GE(ring_solver.failed_column(), 0);
  EXPECT_EQ(ring_solver.counters().fallbacks, 1);
}

TEST(PcgSolver, APatternWithoutADiagonalEntryIsSingularAsCholmodSays) {
  SparseMatrix a(3, 3);
  a.insert(0, 0) = 1.0;
  a.insert(0, 2) = 0.5;
  a.insert(2, 2) = 1.0; // no (1, 1)
  a.makeCompressed();
  PcgSolver solver;
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  EXPECT_EQ(solver.factorize(a), SolveStatus::not_positive_definite);
  EXPECT_EQ(solver.failed_column(), 1);
}

} // namespace
} // namespace nmm
