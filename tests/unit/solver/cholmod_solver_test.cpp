// SPDX-License-Identifier: MIT
#include "solver/cholmod_solver.hpp"
#include "solver/threads.hpp"

#include "laplacian.hpp"
#include <Eigen/SparseCholesky>
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace nmm {
namespace {

using testing::laplacian;

TEST(CholmodSolver, SolvesSpdSystemLikeEigenLdlt) {
  const SparseMatrix a = laplacian(40, 0.0);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  CholmodSolver solver;
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
  Eigen::VectorXd x;
  ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  const Eigen::SimplicialLDLT<SparseMatrix> reference(a);
  const Eigen::VectorXd expected = reference.solve(rhs);
  // Condition number of this Laplacian is ~700: 1e-12 relative is far above rounding.
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
  EXPECT_LT((a * x - rhs).norm(), 1e-12 * rhs.norm());
}

TEST(CholmodSolver, ReadsOnlyTheUpperTriangle) {
  const SparseMatrix full = laplacian(10, 0.5);
  const SparseMatrix upper = full.triangularView<Eigen::Upper>();
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(full.rows());
  CholmodSolver solver;
  ASSERT_EQ(solver.analyze(upper), SolveStatus::ok);
  ASSERT_EQ(solver.factorize(upper), SolveStatus::ok);
  Eigen::VectorXd x;
  ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
  EXPECT_LT((full * x - rhs).norm(), 1e-13 * rhs.norm());
}

TEST(CholmodSolver, IgnoresWhatALowerTriangleHolds) {
  // The solver gives CHOLMOD the permuted lower triangle it builds from the matrix's upper
  // one: entries below the diagonal are not read, whatever they hold (here 7 times their
  // symmetric value; taking them instead of the upper ones fails this). The same values
  // reach CHOLMOD, so the answer is the same to the last bit as with the upper triangle alone.
  const SparseMatrix full = laplacian(12, 0.5);
  const SparseMatrix upper = full.triangularView<Eigen::Upper>();
  SparseMatrix skewed = full;
  for (Eigen::Index j = 0; j < skewed.outerSize(); ++j)
    for (SparseMatrix::InnerIterator it(skewed, j); it; ++it)
      if (it.row() > it.col())
        it.valueRef() *= 7.0;
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(full.rows(), -1.0, 2.0);
  std::vector<Eigen::VectorXd> solutions;
  for (const SparseMatrix* a : std::vector<const SparseMatrix*>{&upper, &skewed}) {
    CholmodSolver solver;
    ASSERT_EQ(solver.analyze(*a), SolveStatus::ok);
    ASSERT_EQ(solver.factorize(*a), SolveStatus::ok);
    Eigen::VectorXd x;
    ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
    solutions.push_back(x);
  }
  EXPECT_EQ(solutions[0], solutions[1]);
  EXPECT_LT((full * solutions[0] - rhs).norm(), 1e-13 * rhs.norm());
}

TEST(CholmodSolver, RefactorizesNewValuesWithoutNewAnalysis) {
  CholmodSolver solver;
  const SparseMatrix first = laplacian(20, 0.0);
  ASSERT_EQ(solver.analyze(first), SolveStatus::ok);
  Eigen::VectorXd x;
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(first.rows());
  for (double shift : {0.0, 1.0, 10.0}) {
    const SparseMatrix a = laplacian(20, shift);
    ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
    ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
    EXPECT_LT((a * x - rhs).norm(), 1e-12 * rhs.norm());
  }
  EXPECT_EQ(solver.counters().symbolic_analyses, 1);
  EXPECT_EQ(solver.counters().factorizations, 3);
  EXPECT_EQ(solver.counters().solves, 3);
}

TEST(CholmodSolver, ReportsIndefiniteMatrixAsStatus) {
  // Shift -4 leaves the Laplacian's negative eigenvalues: a pivot fails.
  const SparseMatrix a = laplacian(6, -4.0);
  CholmodSolver solver;
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  EXPECT_EQ(solver.factorize(a), SolveStatus::not_positive_definite);
  EXPECT_GE(solver.failed_column(), 0);
  Eigen::VectorXd x;
  EXPECT_EQ(solver.solve(Eigen::VectorXd::Ones(a.rows()), x), SolveStatus::failed);
}

TEST(CholmodSolver, FailedColumnIsTheMatrixsOwnColumnNotThePermutedOne) {
  // A positive definite Laplacian whose diagonal at one column is made hugely negative: the
  // pivots eliminated before it do not depend on its diagonal, so the factorisation fails
  // exactly there. CHOLMOD reports the failure in its fill-reducing order; the solver must
  // name the column of the matrix it was given (the stepper turns it into a cover and a
  // place). Several columns, so that an unmapped report cannot match them all by chance.
  for (const int column : {0, 37, 123, 250, 399}) {
    SparseMatrix a = laplacian(20, 1.0);
    a.coeffRef(column, column) = -1.0e6;
    CholmodSolver solver;
    ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
    EXPECT_EQ(solver.factorize(a), SolveStatus::not_positive_definite);
    EXPECT_EQ(solver.failed_column(), column);
  }
}

TEST(CholmodSolver, FactorizeBeforeAnalyzeFails) {
  CholmodSolver solver;
  EXPECT_EQ(solver.factorize(laplacian(3, 0.0)), SolveStatus::failed);
}

TEST(CholmodSolver, FactorFlopsAreCholmodsCountOfTheAnalysedFactor) {
  CholmodSolver solver;
  EXPECT_EQ(solver.factor_flops(), 0.0);
  // A diagonal matrix: one entry per column of L, CHOLMOD counts sum_j Lnz(j)^2 = n.
  SparseMatrix diagonal(50, 50);
  diagonal.setIdentity();
  diagonal.makeCompressed();
  ASSERT_EQ(solver.analyze(diagonal), SolveStatus::ok);
  EXPECT_EQ(solver.factor_flops(), 50.0);
  // A 2D Laplacian fills in: more than its n columns, less than a dense factor's n^3 / 3.
  const SparseMatrix a = laplacian(20, 0.0);
  ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
  EXPECT_GT(solver.factor_flops(), 400.0 * 10);
  EXPECT_LT(solver.factor_flops(), 400.0 * 400.0 * 400.0 / 3.0);
}

TEST(CholmodSolver, SmallFactorizationsGiveTheSameAnswerOnOneThread) {
  limit_threads(available_cores());
  const SparseMatrix a = laplacian(30, 0.0);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  Eigen::VectorXd every_thread;
  Eigen::VectorXd one_thread;
  for (const double single_thread_flops : {0.0, 1e300}) {
    CholmodSolver solver;
    solver.set_single_thread_flops(single_thread_flops);
    ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
    ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
    ASSERT_EQ(solver.solve(rhs, single_thread_flops == 0.0 ? every_thread : one_thread),
              SolveStatus::ok);
    // The thread count is back where limit_threads() put it after the factorization.
    EXPECT_EQ(blas_threads(), available_cores());
  }
  // Same algorithm, possibly another summation order in BLAS: rounding only (condition ~400).
  EXPECT_LT((every_thread - one_thread).norm(), 1e-13 * every_thread.norm());
}

TEST(CholmodSolver, SmallFactorsAreSolvedOnOneThreadAsWell) {
  // A factor made on one thread (below single_thread_flops) is solved on one thread too:
  // OpenBLAS split the larger dgemv calls of the triangular solves between two threads, and
  // the second then spun in sched_yield between calls (docs/benchmarks.md, "Blocks: DDA, VEM, NMM
  // and conjugate gradients"). The answer is then the same to the last bit whatever limit_threads()
  // allows (a solve split between threads sums in another order, and the open-close decisions of a
  // rock mass follow its last bits). 6.25e4 unknowns (below 2e9 flops): the top separators give
  // dgemv calls of about 250 x 500, which OpenBLAS runs on two threads (with 1.4e4 unknowns the
  // answers agreed even before).
  const SparseMatrix a = laplacian(250, 1e-3);
  const Eigen::VectorXd rhs = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
  std::vector<Eigen::VectorXd> solutions;
  for (const int threads : {1, 2}) {
    limit_threads(threads);
    CholmodSolver solver;
    ASSERT_EQ(solver.analyze(a), SolveStatus::ok);
    ASSERT_LT(solver.factor_flops(), default_single_thread_flops);
    ASSERT_EQ(solver.factorize(a), SolveStatus::ok);
    Eigen::VectorXd x;
    ASSERT_EQ(solver.solve(rhs, x), SolveStatus::ok);
    solutions.push_back(x);
    EXPECT_EQ(blas_threads(), threads); // and the count is restored after the solve
  }
  limit_threads(available_cores());
  EXPECT_EQ(solutions[0], solutions[1]);
}

TEST(Threads, SingleBlasThreadRunsOneThreadAndRestoresTheCount) {
  limit_threads(2);
  {
    const SingleBlasThread single;
    EXPECT_EQ(blas_threads(), 1);
  }
  EXPECT_EQ(blas_threads(), 2);
  limit_threads(available_cores());
}

TEST(Threads, OpenMpRegionsOfEveryLibraryRunNmmsOneThreadEntry) {
  // CHOLMOD (a shared library) finds GOMP_parallel where the dynamic linker looks first: the
  // executable's own definition (threads.hpp), not libgomp's team with a system call at its
  // end. Not exported from the executable, this lookup would give libgomp's.
  void* const found = dlsym(RTLD_DEFAULT, "GOMP_parallel");
  ASSERT_NE(found, nullptr);
  EXPECT_EQ(found, reinterpret_cast<void*>(&GOMP_parallel));
  // And it runs the body once, with its data. (Every factorization of the tests above went
  // through it: SolvesSpdSystemLikeEigenLdlt checks the answer.)
  int runs = 0;
  GOMP_parallel([](void* data) { ++*static_cast<int*>(data); }, &runs, 4, 0);
  EXPECT_EQ(runs, 1);
}

TEST(Threads, CapsAtUsableCoresAndLinksOpenBlas) {
  const int cores = available_cores();
  EXPECT_GE(cores, 1);
  limit_threads(cores);
  const std::string blas = blas_description();
  EXPECT_NE(blas.find("OpenBLAS"), std::string::npos) << blas;
  std::string threads = "(";
  threads += std::to_string(cores);
  threads += " threads)";
  EXPECT_NE(blas.find(threads), std::string::npos) << blas;
}

} // namespace
} // namespace nmm
