// SPDX-License-Identifier: MIT
#include "solver/sparsity.hpp"

#include "random_groups.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <stdexcept>
#include <vector>

namespace nmm {
namespace {

SparsityPattern build_pattern(int n_dofs, const std::vector<std::vector<int>>& groups) {
  SparsityBuilder builder(n_dofs);
  for (const std::vector<int>& dofs : groups)
    builder.add(dofs);
  return builder.build();
}

// The structure Eigen's setFromTriplets gives for the same groups.
SparsityPattern reference_pattern(int n_dofs, const std::vector<std::vector<int>>& groups) {
  std::vector<Eigen::MatrixXd> ones;
  for (const std::vector<int>& dofs : groups) {
    const auto k = static_cast<Eigen::Index>(dofs.size());
    ones.push_back(Eigen::MatrixXd::Ones(k, k));
  }
  const SparseMatrix reference = testing::assemble_by_triplets(n_dofs, groups, ones);
  const int* outer = reference.outerIndexPtr();
  const int* inner = reference.innerIndexPtr();
  return {n_dofs, std::vector<int>(outer, outer + n_dofs + 1),
          std::vector<int>(inner, inner + reference.nonZeros())};
}

TEST(SparsityBuilder, WithoutGroupsHoldsEveryDiagonal) {
  const SparsityPattern pattern = SparsityBuilder(4).build();
  EXPECT_EQ(pattern.n_dofs(), 4);
  EXPECT_EQ(pattern.n_nonzeros(), 4);
  for (int dof = 0; dof < 4; ++dof) {
    ASSERT_EQ(pattern.rows_of_column(dof).size(), 1U);
    EXPECT_EQ(pattern.rows_of_column(dof)[0], dof);
  }
  EXPECT_EQ(SparsityBuilder(0).build(), SparsityPattern());
}

TEST(SparsityBuilder, OneGroupGivesItsDenseUpperTriangle) {
  SparsityBuilder builder(6);
  const std::array<int, 3> dofs{4, 1, 2};
  builder.add(dofs);
  const SparsityPattern pattern = builder.build();
  const std::vector<int> starts(pattern.column_starts().begin(), pattern.column_starts().end());
  const std::vector<int> rows(pattern.row_indices().begin(), pattern.row_indices().end());
  EXPECT_EQ(starts, (std::vector<int>{0, 1, 2, 4, 5, 8, 9}));
  EXPECT_EQ(rows, (std::vector<int>{0, 1, 1, 2, 3, 1, 2, 4, 5}));
}

TEST(SparsityBuilder, MatchesTripletPatternForRandomOverlappingGroups) {
  for (const unsigned seed : {1U, 2U, 3U, 4U}) {
    const int n_dofs = 97 + 50 * static_cast<int>(seed);
    const auto groups = testing::make_random_groups(n_dofs, 120, 72, seed);
    EXPECT_EQ(build_pattern(n_dofs, groups), reference_pattern(n_dofs, groups)) << seed;
  }
}

TEST(SparsityBuilder, NegativeDofsAreIgnored) {
  const std::vector<std::vector<int>> with_eliminated{{3, -1, 5, -7, 0}, {-1}, {2, -1}};
  const std::vector<std::vector<int>> without{{3, 5, 0}, {}, {2}};
  EXPECT_EQ(build_pattern(8, with_eliminated), build_pattern(8, without));
}

TEST(SparsityBuilder, OrderOfGroupsAndOfDofsDoesNotMatter) {
  auto groups = testing::make_random_groups(300, 80, 40, 7);
  const SparsityPattern expected = build_pattern(300, groups);
  std::mt19937 random(11);
  std::shuffle(groups.begin(), groups.end(), random);
  for (std::vector<int>& dofs : groups)
    std::shuffle(dofs.begin(), dofs.end(), random);
  EXPECT_EQ(build_pattern(300, groups), expected);
}

TEST(SparsityBuilder, ClearForgetsGroupsAndCanBeReused) {
  SparsityBuilder builder(5);
  builder.add(std::vector<int>{0, 4});
  EXPECT_EQ(builder.n_groups(), 1U);
  builder.clear();
  EXPECT_EQ(builder.n_groups(), 0U);
  EXPECT_EQ(builder.build(), SparsityBuilder(5).build());
  builder.add(std::vector<int>{1, 3});
  EXPECT_TRUE(builder.build().contains(1, 3));
  EXPECT_FALSE(builder.build().contains(0, 4));
}

TEST(SparsityBuilder, RepeatedBuildsMatchAFreshBuilder) {
  // A time-step loop: clear, add this step's groups, build; scratch storage is reused.
  SparsityBuilder reused(500);
  for (const unsigned seed : {21U, 22U, 23U}) {
    const auto groups =
        testing::make_random_groups(500, 100 + 60 * static_cast<int>(seed % 3), 72, seed);
    reused.clear();
    for (const auto& dofs : groups)
      reused.add(dofs);
    EXPECT_EQ(reused.build(), build_pattern(500, groups)) << seed;
    EXPECT_EQ(reused.build(), build_pattern(500, groups)) << seed;
  }
}

TEST(SparsityPattern, ColumnsAreSortedAndEndWithTheDiagonal) {
  const auto groups = testing::make_random_groups(400, 200, 72, 5);
  const SparsityPattern pattern = build_pattern(400, groups);
  for (int column = 0; column < pattern.n_dofs(); ++column) {
    const auto rows = pattern.rows_of_column(column);
    ASSERT_FALSE(rows.empty());
    EXPECT_EQ(rows.back(), column);
    EXPECT_TRUE(std::adjacent_find(rows.begin(), rows.end(), std::greater_equal<>()) == rows.end());
  }
}

TEST(SparsityPattern, PositionFindsAnEntryFromEitherTriangle) {
  SparsityBuilder builder(6);
  builder.add(std::vector<int>{4, 1, 2});
  const SparsityPattern pattern = builder.build();
  // Column 4 holds rows 1, 2, 4 at positions 5, 6, 7.
  EXPECT_EQ(pattern.position(1, 4), 5);
  EXPECT_EQ(pattern.position(4, 1), 5);
  EXPECT_EQ(pattern.position(2, 4), 6);
  EXPECT_EQ(pattern.position(4, 4), 7);
  EXPECT_EQ(pattern.position(0, 4), -1);
  EXPECT_EQ(pattern.position(3, 4), -1);
  EXPECT_FALSE(pattern.contains(5, 4));
  EXPECT_TRUE(pattern.contains(5, 5));
}

TEST(SparsityPattern, RejectsMalformedArraysWhenAssertsAreOn) {
#if defined(NDEBUG) && !defined(NMM_ENABLE_ASSERTS)
  GTEST_SKIP() << "NMM_ASSERT is compiled out in this build";
#else
  // Column 1 lacks its diagonal.
  EXPECT_THROW(SparsityPattern(2, {0, 1, 2}, {0, 0}), std::logic_error);
  // A repeated row.
  EXPECT_THROW(SparsityPattern(2, {0, 1, 3}, {0, 1, 1}), std::logic_error);
  SparsityBuilder builder(3);
  EXPECT_THROW(builder.add(std::vector<int>{0, 3}), std::logic_error);
#endif
}

} // namespace
} // namespace nmm
