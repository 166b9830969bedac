// SPDX-License-Identifier: MIT
#include "mesh/error.hpp"
#include "solver/dof_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace nmm {
namespace {

double residual(const LinearConstraint& row, const Eigen::VectorXd& raw) {
  double v = -row.value;
  for (const auto& [i, c] : row.terms)
    v += c * raw(i);
  return v;
}

TEST(DofMap, WithoutConstraintsIsTheIdentity) {
  const DofMap map(5, {});
  EXPECT_EQ(map.n_reduced(), 5);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(5, 1.0, 5.0);
  EXPECT_EQ(map.expand(x), x);
  EXPECT_EQ(map.restrict(x), x);
}

TEST(DofMap, ChainOfConstraintsIsResolvedIntoFreeUnknownsOnly) {
  // d0 = 0.5 d1, d1 = 2 d2 + 1, d3 = d0: a chain that needs back-substitution.
  const std::vector<LinearConstraint> rows{{{{0, 1.0}, {1, -0.5}}, 0.0, 0, "a"},
                                           {{{1, 1.0}, {2, -2.0}}, 1.0, 1, "b"},
                                           {{{3, 1.0}, {0, -1.0}}, 0.0, 3, "c"}};
  const DofMap map(5, rows);
  EXPECT_EQ(map.n_reduced(), 2); // d2 and d4
  EXPECT_TRUE(map.is_slave(0) && map.is_slave(1) && map.is_slave(3));
  const Eigen::VectorXd raw = map.expand(Eigen::Vector2d(3.0, -7.0));
  EXPECT_DOUBLE_EQ(raw(2), 3.0);
  EXPECT_DOUBLE_EQ(raw(1), 7.0);
  EXPECT_DOUBLE_EQ(raw(0), 3.5);
  EXPECT_DOUBLE_EQ(raw(3), 3.5);
  EXPECT_DOUBLE_EQ(raw(4), -7.0);
  for (const int i : {0, 1, 3})
    for (const auto& [j, c] : map.expansion(i).terms)
      EXPECT_EQ(j, 0) << "slave " << i << " must depend on the free unknown d2 only, got " << c;
}

TEST(DofMap, RedundantConstraintsAreDroppedAndContradictionsReported) {
  std::vector<LinearConstraint> rows{{{{0, 1.0}, {1, 1.0}}, 0.0, -1, "p"},
                                     {{{0, 2.0}, {1, 2.0}}, 0.0, -1, "p twice"}};
  const DofMap map(3, rows);
  EXPECT_EQ(map.stats().redundant, 1);
  EXPECT_EQ(map.n_reduced(), 2);
  rows.push_back({{{0, 1.0}, {1, 1.0}}, 1.0, -1, "fixed curve top"});
  try {
    const DofMap bad(3, rows);
    FAIL() << "contradiction not detected";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("fixed curve top"), std::string::npos) << e.what();
  }
}

TEST(DofMap, RedundantRowsAgreeToTheRoundingOfTheModelsLength) {
  // Two supports of the same point that correct slightly different drifts (rounding of the
  // points' moves): a disagreement below 1e-9 of the model size is no contradiction; one of
  // 1e-6 of it is.
  const std::vector<LinearConstraint> rows{{{{0, 1.0}, {1, 1.0}}, 0.0, -1, "p"},
                                           {{{0, 1.0}, {1, 1.0}}, 4e-12, -1, "p again"}};
  EXPECT_EQ(DofMap(3, rows, 1e-12, 25.0).stats().redundant, 1);
  const std::vector<LinearConstraint> apart{{{{0, 1.0}, {1, 1.0}}, 0.0, -1, "p"},
                                            {{{0, 1.0}, {1, 1.0}}, 2.5e-5, -1, "p moved"}};
  EXPECT_THROW(DofMap(3, apart, 1e-12, 25.0), InputError);
}

TEST(DofMap, RandomLocalConstraintsHoldExactlyAfterExpansion) {
  // Property: whatever the order and overlap of the rows, every constraint holds for every
  // reduced vector (1e-12: a few eliminations of O(1) coefficients).
  // Rows on windows of 3 consecutive unknowns with distinct starts: k rows always span at
  // least k + 2 unknowns, so the system is consistent whatever the values.
  std::mt19937 random(11);
  std::uniform_real_distribution<double> coefficient(-1.0, 1.0);
  std::vector<int> starts(198);
  for (int i = 0; i < 198; ++i)
    starts[static_cast<std::size_t>(i)] = i;
  std::shuffle(starts.begin(), starts.end(), random);
  std::vector<LinearConstraint> rows;
  for (int r = 0; r < 120; ++r) {
    LinearConstraint row;
    const int base = starts[static_cast<std::size_t>(r)];
    for (int k = 0; k < 3; ++k)
      row.terms.emplace_back(base + k, coefficient(random));
    row.value = r % 3 == 0 ? coefficient(random) : 0.0;
    rows.push_back(row);
  }
  const DofMap map(200, rows, 1e-12);
  EXPECT_EQ(map.n_reduced(), 200 - map.stats().eliminated);
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd raw = map.expand(Eigen::VectorXd::Random(map.n_reduced()));
    for (const LinearConstraint& row : rows)
      EXPECT_NEAR(residual(row, raw), 0.0, 1e-12);
  }
  // restrict is the transpose of expand's linear part: <T x, y> = <x, T^T y>.
  const Eigen::VectorXd x = Eigen::VectorXd::Random(map.n_reduced());
  const Eigen::VectorXd y = Eigen::VectorXd::Random(200);
  const Eigen::VectorXd t0 = map.expand(Eigen::VectorXd::Zero(map.n_reduced()));
  EXPECT_NEAR((map.expand(x) - t0).dot(y), x.dot(map.restrict(y)), 1e-10);
}

TEST(DofMap, PreferredSlaveIsEliminated) {
  const std::vector<LinearConstraint> rows{{{{0, 1.0}, {1, -0.3}, {2, -0.7}}, 0.0, 0, "tiny"}};
  const DofMap map(3, rows);
  EXPECT_TRUE(map.is_slave(0));
  EXPECT_FALSE(map.is_slave(1));
}

TEST(DofMap, KeepsTheLastStepsSlavesWhereTheCoefficientsNearlyTie) {
  // A support row whose two coefficients swap order by rounding from one step to the next
  // (preferred slave -1: none). Alone, each map pivots on the larger one; given the last
  // step's map, the second keeps its slave, so the sparsity pattern stays the same.
  const std::vector<LinearConstraint> first{{{{0, 1.0}, {1, 1.0 + 1e-9}}, 0.0, -1, "point"}};
  const std::vector<LinearConstraint> second{{{{0, 1.0 + 1e-9}, {1, 1.0}}, 0.0, -1, "point"}};
  const DofMap last(2, first);
  ASSERT_TRUE(last.is_slave(1));
  EXPECT_TRUE(DofMap(2, second).is_slave(0));
  const DofMap next(2, second, 1e-12, 1.0, &last);
  EXPECT_TRUE(next.is_slave(1));
  EXPECT_FALSE(next.is_slave(0));
  // A last-step slave whose coefficient is below a tenth of the largest is not kept.
  const std::vector<LinearConstraint> third{{{{0, 1.0}, {1, 0.05}}, 0.0, -1, "point"}};
  EXPECT_TRUE(DofMap(2, third, 1e-12, 1.0, &last).is_slave(0));
}

} // namespace
} // namespace nmm
