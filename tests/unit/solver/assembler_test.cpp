// SPDX-License-Identifier: MIT
#include "solver/assembler.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/sparsity.hpp"

#include "random_groups.hpp"
#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace nmm {
namespace {

// Random couplings with their local matrices and local vectors.
struct Problem {
  int n_dofs = 0;
  std::vector<std::vector<int>> groups;
  std::vector<Eigen::MatrixXd> locals;
  std::vector<Eigen::VectorXd> vectors;
  SparsityPattern pattern;
};

Problem make_problem(int n_dofs, int n_groups, unsigned seed, bool with_eliminated = true) {
  Problem problem;
  problem.n_dofs = n_dofs;
  problem.groups = testing::make_random_groups(n_dofs, n_groups, 72, seed, with_eliminated);
  SparsityBuilder builder(n_dofs);
  for (std::size_t g = 0; g < problem.groups.size(); ++g) {
    const auto k = static_cast<int>(problem.groups[g].size());
    problem.locals.push_back(testing::make_random_symmetric(k, seed * 1000U + g));
    problem.vectors.push_back(Eigen::VectorXd::LinSpaced(k, -1.0, 1.0 + g));
    builder.add(problem.groups[g]);
  }
  problem.pattern = builder.build();
  return problem;
}

// Largest entry difference relative to the largest reference entry; the patterns must match.
double relative_difference(const SparseMatrix& assembled, const SparseMatrix& reference) {
  EXPECT_EQ(assembled.nonZeros(), reference.nonZeros());
  EXPECT_TRUE(std::equal(reference.outerIndexPtr(),
                         reference.outerIndexPtr() + reference.outerSize() + 1,
                         assembled.outerIndexPtr()));
  EXPECT_TRUE(std::equal(reference.innerIndexPtr(),
                         reference.innerIndexPtr() + reference.nonZeros(),
                         assembled.innerIndexPtr()));
  const Eigen::Map<const Eigen::VectorXd> a(assembled.valuePtr(), assembled.nonZeros());
  const Eigen::Map<const Eigen::VectorXd> r(reference.valuePtr(), reference.nonZeros());
  return (a - r).lpNorm<Eigen::Infinity>() / r.lpNorm<Eigen::Infinity>();
}

Eigen::VectorXd reference_rhs(const Problem& problem) {
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(problem.n_dofs);
  for (std::size_t g = 0; g < problem.groups.size(); ++g) {
    for (std::size_t a = 0; a < problem.groups[g].size(); ++a) {
      if (problem.groups[g][a] >= 0)
        rhs[problem.groups[g][a]] += problem.vectors[g][static_cast<Eigen::Index>(a)];
    }
  }
  return rhs;
}

TEST(Assembler, SearchAddEqualsTripletReference) {
  for (const unsigned seed : {1U, 2U, 3U}) {
    const Problem problem = make_problem(250, 150, seed);
    Assembler assembler(problem.pattern);
    for (std::size_t g = 0; g < problem.groups.size(); ++g) {
      assembler.add(problem.groups[g], problem.locals[g]);
      assembler.add_vector(problem.groups[g], problem.vectors[g]);
    }
    const SparseMatrix reference =
        testing::assemble_by_triplets(problem.n_dofs, problem.groups, problem.locals);
    EXPECT_LT(relative_difference(assembler.matrix(), reference), 1e-14) << seed;
    EXPECT_LT((assembler.rhs() - reference_rhs(problem)).lpNorm<Eigen::Infinity>(), 1e-14);
  }
}

TEST(Assembler, PlanAddEqualsSearchAddAndTripletReference) {
  for (const unsigned seed : {4U, 5U, 6U}) {
    const Problem problem = make_problem(300, 200, seed);
    Assembler by_search(problem.pattern);
    Assembler by_plan(problem.pattern);
    std::vector<int> plans;
    for (const std::vector<int>& dofs : problem.groups)
      plans.push_back(by_plan.plan(dofs));
    EXPECT_EQ(by_plan.n_plans(), static_cast<int>(problem.groups.size()));
    for (std::size_t g = 0; g < problem.groups.size(); ++g) {
      by_search.add(problem.groups[g], problem.locals[g]);
      by_search.add_vector(problem.groups[g], problem.vectors[g]);
      by_plan.add(plans[g], problem.locals[g]);
      by_plan.add_vector(plans[g], problem.vectors[g]);
    }
    // Repeated dofs are summed in another order by the two paths: rounding may differ.
    EXPECT_LT(relative_difference(by_plan.matrix(), by_search.matrix()), 1e-15) << seed;
    const SparseMatrix reference =
        testing::assemble_by_triplets(problem.n_dofs, problem.groups, problem.locals);
    EXPECT_LT(relative_difference(by_plan.matrix(), reference), 1e-14) << seed;
    EXPECT_EQ(by_plan.rhs(), by_search.rhs());
  }
}

TEST(Assembler, PlanAddEqualsSearchAddBitwiseWithoutRepeatsOrEliminations) {
  std::vector<std::vector<int>> groups{{7, 2, 9, 0}, {1, 2, 3}, {9, 8, 7, 6, 5, 4}};
  SparsityBuilder builder(10);
  for (const auto& dofs : groups)
    builder.add(dofs);
  const SparsityPattern pattern = builder.build();
  Assembler by_search(pattern);
  Assembler by_plan(pattern);
  for (std::size_t g = 0; g < groups.size(); ++g) {
    const Eigen::MatrixXd local =
        testing::make_random_symmetric(static_cast<int>(groups[g].size()), 40U + g);
    by_search.add(groups[g], local);
    by_plan.add(by_plan.plan(groups[g]), local);
  }
  const Eigen::Map<const Eigen::VectorXd> a(by_plan.matrix().valuePtr(), pattern.n_nonzeros());
  const Eigen::Map<const Eigen::VectorXd> b(by_search.matrix().valuePtr(), pattern.n_nonzeros());
  EXPECT_EQ(a, b);
}

TEST(Assembler, NegativeDofsSkipTheirRowAndColumn) {
  SparsityBuilder builder(5);
  builder.add(std::vector<int>{4, 1, 2});
  const SparsityPattern pattern = builder.build();
  Eigen::MatrixXd local(4, 4);
  local << 10, 1, 2, 3, //
      1, 20, 4, 5,      //
      2, 4, 30, 6,      //
      3, 5, 6, 40;
  const std::vector<int> dofs{4, -1, 1, 2}; // local 1 is eliminated
  Eigen::MatrixXd reduced(3, 3);
  reduced << 10, 2, 3, //
      2, 30, 6,        //
      3, 6, 40;
  const std::vector<int> reduced_dofs{4, 1, 2};

  for (const bool use_plan : {false, true}) {
    Assembler eliminated(pattern);
    Assembler expected(pattern);
    if (use_plan) {
      eliminated.add(eliminated.plan(dofs), local);
    } else {
      eliminated.add(dofs, local);
    }
    expected.add(reduced_dofs, reduced);
    EXPECT_EQ(Eigen::MatrixXd(eliminated.matrix()), Eigen::MatrixXd(expected.matrix()));
  }
  // Upper triangle only: (1, 4) holds local(2, 0) = 2, (4, 4) holds 10.
  Assembler assembler(pattern);
  assembler.add(assembler.plan(dofs), local);
  EXPECT_EQ(assembler.matrix().coeff(1, 4), 2.0);
  EXPECT_EQ(assembler.matrix().coeff(4, 1), 0.0);
  EXPECT_EQ(assembler.matrix().coeff(4, 4), 10.0);

  const Eigen::Vector4d vector(1.0, 2.0, 3.0, 4.0);
  assembler.add_vector(dofs, vector);
  assembler.add_vector(assembler.plan(dofs), vector);
  EXPECT_EQ(assembler.rhs(), (Eigen::VectorXd(5) << 0.0, 6.0, 8.0, 0.0, 2.0).finished());
}

TEST(Assembler, RepeatedDofsSumLikeTheFullProduct) {
  // P^T L P with dofs {3, 3}: the diagonal gets L00 + L01 + L10 + L11.
  SparsityBuilder builder(4);
  builder.add(std::vector<int>{3});
  const SparsityPattern pattern = builder.build();
  const Eigen::Matrix2d local{{1.0, 2.0}, {2.0, 5.0}};
  const std::vector<int> dofs{3, 3};
  Assembler assembler(pattern);
  assembler.add(dofs, local);
  EXPECT_EQ(assembler.matrix().coeff(3, 3), 10.0);
  assembler.zero();
  assembler.add(assembler.plan(dofs), local);
  EXPECT_EQ(assembler.matrix().coeff(3, 3), 10.0);
}

TEST(Assembler, ReadsOnlyTheUpperTriangleOfLocal) {
  SparsityBuilder builder(3);
  builder.add(std::vector<int>{0, 2});
  Assembler assembler(builder.build());
  const Eigen::Matrix2d local{{1.0, 2.0}, {-99.0, 3.0}};
  assembler.add(assembler.plan(std::vector<int>{2, 0}), local);
  EXPECT_EQ(assembler.matrix().coeff(0, 2), 2.0);
  EXPECT_EQ(assembler.matrix().coeff(2, 2), 1.0);
  EXPECT_EQ(assembler.matrix().coeff(0, 0), 3.0);
}

TEST(Assembler, AddDiagonalHitsTheDiagonalOfAnyDof) {
  SparsityBuilder builder(4);
  builder.add(std::vector<int>{0, 2, 3});
  Assembler assembler(builder.build());
  for (int dof = 0; dof < 4; ++dof)
    assembler.add_diagonal(dof, 1.5 * (dof + 1));
  assembler.add_diagonal(2, 1.0);
  const Eigen::MatrixXd dense(assembler.matrix());
  EXPECT_EQ(dense.diagonal(), Eigen::Vector4d(1.5, 3.0, 5.5, 6.0));
  EXPECT_EQ(dense.sum(), dense.diagonal().sum());
}

TEST(Assembler, ZeroThenReassemblyGivesIdenticalValues) {
  const Problem problem = make_problem(200, 100, 9);
  Assembler assembler(problem.pattern);
  std::vector<int> plans;
  for (const auto& dofs : problem.groups)
    plans.push_back(assembler.plan(dofs));
  auto assemble = [&] {
    for (std::size_t g = 0; g < problem.groups.size(); ++g) {
      assembler.add(plans[g], problem.locals[g]);
      assembler.add_vector(plans[g], problem.vectors[g]);
    }
  };
  assemble();
  const SparseMatrix first = assembler.matrix();
  const Eigen::VectorXd first_rhs = assembler.rhs();
  assemble(); // doubles every value
  EXPECT_GT(relative_difference(assembler.matrix(), first), 0.5);
  assembler.zero();
  EXPECT_EQ(assembler.rhs(), Eigen::VectorXd::Zero(problem.n_dofs));
  assemble();
  EXPECT_EQ(relative_difference(assembler.matrix(), first), 0.0);
  EXPECT_EQ(assembler.rhs(), first_rhs);
}

TEST(Assembler, ResetBindsToTheNextPatternAndDropsPlans) {
  const Problem first = make_problem(150, 60, 12);
  const Problem second = make_problem(180, 90, 13);
  Assembler assembler(first.pattern);
  for (const auto& dofs : first.groups)
    static_cast<void>(assembler.plan(dofs));
  assembler.reset(second.pattern);
  EXPECT_EQ(assembler.n_plans(), 0);
  EXPECT_EQ(assembler.n_dofs(), 180);
  for (std::size_t g = 0; g < second.groups.size(); ++g)
    assembler.add(assembler.plan(second.groups[g]), second.locals[g]);
  const SparseMatrix reference =
      testing::assemble_by_triplets(second.n_dofs, second.groups, second.locals);
  EXPECT_LT(relative_difference(assembler.matrix(), reference), 1e-14);
}

TEST(Assembler, TruncatedPlansKeepTheFirstAndNewOnesFollowThem) {
  // The time stepper keeps the element plans and makes the contacts' again: planning the
  // last groups anew (in another order) after a truncation assembles the same matrix.
  const Problem problem = make_problem(200, 100, 21, false);
  Assembler assembler(problem.pattern);
  for (const auto& dofs : problem.groups)
    static_cast<void>(assembler.plan(dofs));
  auto assemble = [&](const std::vector<std::size_t>& order) {
    assembler.zero();
    for (std::size_t p = 0; p < order.size(); ++p)
      assembler.add(static_cast<int>(p), problem.locals[order[p]]);
    return SparseMatrix(assembler.matrix());
  };
  std::vector<std::size_t> order(problem.groups.size());
  for (std::size_t g = 0; g < order.size(); ++g)
    order[g] = g;
  const SparseMatrix all = assemble(order);
  assembler.truncate_plans(60);
  EXPECT_EQ(assembler.n_plans(), 60);
  std::reverse(order.begin() + 60, order.end());
  for (std::size_t p = 60; p < order.size(); ++p)
    EXPECT_EQ(assembler.plan(problem.groups[order[p]]), static_cast<int>(p));
  // Other order of the last 40: the sums of an entry may differ in rounding only.
  EXPECT_LT(relative_difference(assemble(order), all), 1e-14);
  assembler.truncate_plans(assembler.n_plans()); // nothing to drop
  EXPECT_EQ(assembler.n_plans(), 100);
  assembler.truncate_plans(0);
  EXPECT_EQ(assembler.n_plans(), 0);
}

TEST(Assembler, APlanAsAnotherSharesItsPositionsAndSurvivesTruncation) {
  // Each group planned, then each planned again as its first plan (contacts between the same
  // two elements): adding a group's local matrix through either plan is the same as through
  // plan(), bit for bit; after truncating among the shared plans (whose data are those of
  // early plans) or among the first ones, the plans made again do the same.
  const Problem problem = make_problem(200, 50, 29, true);
  const auto n = static_cast<int>(problem.groups.size());
  Assembler shared(problem.pattern);
  Assembler once(problem.pattern);
  auto plan_firsts = [&](int from) {
    for (int g = from; g < n; ++g)
      EXPECT_EQ(shared.plan_if_in_pattern(problem.groups[static_cast<std::size_t>(g)]), g);
  };
  auto plan_shared = [&](int from) {
    for (int g = from; g < n; ++g)
      EXPECT_EQ(shared.plan_as(g), n + g);
  };
  plan_firsts(0);
  plan_shared(0);
  for (const auto& dofs : problem.groups)
    static_cast<void>(once.plan(dofs));
  auto same_sums = [&] {
    shared.zero();
    once.zero();
    for (int g = 0; g < n; ++g) {
      const auto k = static_cast<std::size_t>(g);
      shared.add(g, problem.locals[k]);
      shared.add(n + g, 0.5 * problem.locals[k]);
      once.add(g, problem.locals[k]);
      once.add(g, 0.5 * problem.locals[k]);
      shared.add_vector(n + g, problem.vectors[k]);
      once.add_vector(g, problem.vectors[k]);
    }
    EXPECT_EQ(relative_difference(shared.matrix(), once.matrix()), 0.0);
    EXPECT_EQ(shared.rhs(), once.rhs());
  };
  same_sums();
  shared.truncate_plans(n + 25); // the last kept plan shares plan 24's data, not the last's
  EXPECT_EQ(shared.n_plans(), n + 25);
  plan_shared(25);
  same_sums();
  shared.truncate_plans(30);
  EXPECT_EQ(shared.n_plans(), 30);
  plan_firsts(30);
  plan_shared(0);
  same_sums();
}

TEST(Assembler, PlansMadeAgainTakeTheKeptPositionsAndAssembleTheSameBitForBit) {
  // The time stepper drops the contacts' plans every step and plans the next step's, mostly
  // the same couplings: a window of 300 groups moving by 200 each "step" searches at most
  // the 200 new to it (the 100 it shares with the last window take their kept positions),
  // and assembles what an assembler that searched every plan does, to the bit. The kept
  // positions grow by up to 200 plans a step past the threshold of compaction (twice the
  // 300 plans before a drop, plus 1024) at about the seventh step; the later steps check
  // that compaction kept the plans it had to.
  const Problem problem = make_problem(2000, 3000, 41, true);
  Assembler reused(problem.pattern);
  constexpr int window = 300;
  constexpr int shift = 200;
  for (int step = 0; step < 14; ++step) {
    const long before = reused.searches();
    reused.truncate_plans(0);
    Assembler searched(problem.pattern);
    const auto first = static_cast<std::size_t>(step * shift);
    for (std::size_t g = first; g < first + window; ++g) {
      const int id = reused.plan_if_in_pattern(problem.groups[g]);
      ASSERT_EQ(id, static_cast<int>(g - first));
      ASSERT_EQ(searched.plan(problem.groups[g]), id);
      reused.add(id, problem.locals[g]);
      reused.add_vector(id, problem.vectors[g]);
      searched.add(id, problem.locals[g]);
      searched.add_vector(id, problem.vectors[g]);
    }
    EXPECT_LE(reused.searches() - before, step == 0 ? window : shift) << step;
    EXPECT_EQ(relative_difference(reused.matrix(), searched.matrix()), 0.0) << step;
    EXPECT_EQ(reused.rhs(), searched.rhs()) << step;
    reused.zero();
  }
  // Every plan of the 14 windows was either searched or taken: 300 + 13 x 200 searches at
  // most, fewer than the 4,200 plans made.
  EXPECT_LE(reused.searches(), window + 13 * shift);
  // clear_plans() forgets the kept positions too: the first group is searched again.
  const long searches = reused.searches();
  reused.clear_plans();
  EXPECT_EQ(reused.plan(problem.groups[0]), 0);
  EXPECT_EQ(reused.searches(), searches + 1);
}

TEST(Assembler, PlanIfInPatternRefusesACouplingOutsideItAndKeepsTheOtherPlans) {
  // The time stepper plans a step's contacts in the last pattern when they fit it, and
  // builds a new pattern when one does not: a refused coupling leaves no trace.
  const Problem problem = make_problem(200, 100, 23, true);
  Assembler assembler(problem.pattern);
  for (std::size_t g = 0; g < 60; ++g)
    EXPECT_EQ(assembler.plan_if_in_pattern(problem.groups[g]), static_cast<int>(g));
  // Dofs 0 and 199 are coupled by no group of the pattern (checked), in any order, with
  // an eliminated dof and a coupled pair beside them.
  ASSERT_FALSE(problem.pattern.contains(0, 199));
  for (const std::vector<int>& outside :
       {std::vector<int>{0, 199}, std::vector<int>{199, -1, 0}, std::vector<int>{5, 5, 199, 0}}) {
    EXPECT_EQ(assembler.plan_if_in_pattern(outside), -1);
    EXPECT_EQ(assembler.n_plans(), 60);
  }
  for (std::size_t g = 60; g < problem.groups.size(); ++g)
    EXPECT_EQ(assembler.plan_if_in_pattern(problem.groups[g]), static_cast<int>(g));
  // The same matrix as with plan(), bit for bit (the same positions, the same order).
  Assembler reference(problem.pattern);
  for (const auto& dofs : problem.groups)
    static_cast<void>(reference.plan(dofs));
  for (std::size_t g = 0; g < problem.groups.size(); ++g) {
    assembler.add(static_cast<int>(g), problem.locals[g]);
    reference.add(static_cast<int>(g), problem.locals[g]);
  }
  EXPECT_EQ(relative_difference(assembler.matrix(), reference.matrix()), 0.0);
}

// P1-like couplings on a grid with 2 dofs per node, SPD local matrices: CHOLMOD must factor
// the assembled upper triangle and solve to rounding.
TEST(Assembler, AssembledMatrixFactorsWithCholmodAndSolves) {
  const int n = 12; // nodes per side
  const int n_dofs = 2 * n * n;
  std::vector<std::vector<int>> groups;
  auto node_dofs = [n](int i, int j, std::vector<int>& dofs) {
    dofs.push_back(2 * (i * n + j));
    dofs.push_back(2 * (i * n + j) + 1);
  };
  for (int i = 0; i + 1 < n; ++i) {
    for (int j = 0; j + 1 < n; ++j) {
      std::vector<int> lower;
      node_dofs(i, j, lower);
      node_dofs(i, j + 1, lower);
      node_dofs(i + 1, j, lower);
      std::vector<int> upper;
      node_dofs(i + 1, j + 1, upper);
      node_dofs(i + 1, j, upper);
      node_dofs(i, j + 1, upper);
      groups.push_back(lower);
      groups.push_back(upper);
    }
  }
  SparsityBuilder builder(n_dofs);
  for (const auto& dofs : groups)
    builder.add(dofs);
  Assembler assembler(builder.build());
  for (std::size_t g = 0; g < groups.size(); ++g) {
    assembler.add(assembler.plan(groups[g]), testing::make_random_symmetric(6, 70U + g));
    assembler.add_vector(assembler.plan(groups[g]), Eigen::VectorXd::Ones(6));
  }
  CholmodSolver solver;
  ASSERT_EQ(solver.analyze(assembler.matrix()), SolveStatus::ok);
  ASSERT_EQ(solver.factorize(assembler.matrix()), SolveStatus::ok);
  Eigen::VectorXd x;
  ASSERT_EQ(solver.solve(assembler.rhs(), x), SolveStatus::ok);
  const SparseMatrix full = assembler.matrix().selfadjointView<Eigen::Upper>();
  EXPECT_LT((full * x - assembler.rhs()).norm(), 1e-12 * assembler.rhs().norm());
  const Eigen::SimplicialLDLT<SparseMatrix> reference(full);
  const Eigen::VectorXd expected = reference.solve(assembler.rhs());
  EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm());
}

TEST(Assembler, EntryOutsideThePatternFailsWhenAssertsAreOn) {
#if defined(NDEBUG) && !defined(NMM_ENABLE_ASSERTS)
  GTEST_SKIP() << "NMM_ASSERT is compiled out in this build";
#else
  SparsityBuilder builder(4);
  builder.add(std::vector<int>{0, 1});
  Assembler assembler(builder.build());
  const std::vector<int> dofs{1, 3};
  EXPECT_THROW(static_cast<void>(assembler.plan(dofs)), std::logic_error);
  EXPECT_THROW(assembler.add(dofs, Eigen::Matrix2d::Identity()), std::logic_error);
  const std::vector<int> fits{0, 1};
  const int plan = assembler.plan(fits);
  EXPECT_THROW(assembler.add(plan, Eigen::Matrix3d::Identity()), std::logic_error);
  EXPECT_THROW(assembler.add_diagonal(4, 1.0), std::logic_error);
#endif
}

} // namespace
} // namespace nmm
