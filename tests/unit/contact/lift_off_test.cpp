// SPDX-License-Identifier: MIT
// The search of an edge-to-edge contact's lift-off point (LiftOffEnd, docs/formulation.md,
// "Lift-off") on model functions wanted(x): where the edges would stop pressing if the
// springs ended at x. More springs, less pressed: wanted decreases, and the springs belong
// where wanted(x) = x.
#include "contact/contact_system.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

namespace nmm {
namespace {

/// Moves an end from @p start by @p wanted for @p calls searches; the places it took.
std::vector<double> search(double start, const std::function<double(double)>& wanted, int calls) {
  LiftOffEnd end;
  std::vector<double> places{start};
  for (int k = 0; k < calls; ++k)
    places.push_back(end.next(places.back(), wanted(places.back()), 1e-12));
  return places;
}

TEST(LiftOffEnd, SwingThatGrowsIsCaughtBetweenItsFirstTwoPlaces) {
  // wanted(x) = 0.3 - 3 (x - 0.3): moving to where the edges press overshoots three times
  // over, and those moves alone swing further out every time (0.25, 0.45, -0.15, ...): the
  // case of a block in a landing pile, whose short and long pressed parts alternate. The
  // first move is made, the second goes back, and false position between those two places
  // is exact for a linear wanted(x): 0.3 to rounding (1e-15 of the overlap) at the third.
  const auto wanted = [](double x) { return 0.3 - 3.0 * (x - 0.3); };
  const std::vector<double> places = search(0.25, wanted, 4);
  EXPECT_DOUBLE_EQ(places[1], 0.45);
  EXPECT_NEAR(places[2], 0.3, 1e-15);
  EXPECT_NEAR(places[3], 0.3, 1e-15);
  EXPECT_NEAR(places[4], 0.3, 1e-15);
}

TEST(LiftOffEnd, CurvedSwingConvergesInsideItsBracket) {
  // wanted(x) = 0.05 / x, the root sqrt(0.05) = 0.2236: from 0.1 the end moves to 0.5,
  // goes back, and from then on stays within [0.1, 0.5] and converges superlinearly
  // (Illinois): within 1e-10 of the overlap after ten searches, where plain false position
  // keeps one end fixed and crawls.
  const auto wanted = [](double x) { return 0.05 / x; };
  const std::vector<double> places = search(0.1, wanted, 12);
  EXPECT_DOUBLE_EQ(places[1], 0.5);
  for (std::size_t k = 2; k < places.size(); ++k) {
    EXPECT_GT(places[k], 0.1) << k;
    EXPECT_LT(places[k], 0.5) << k;
  }
  EXPECT_NEAR(places[10], std::sqrt(0.05), 1e-10);
}

TEST(LiftOffEnd, EndThatIsWhereTheEdgesStopPressingStays) {
  const std::vector<double> places = search(
      0.4, [](double) { return 0.4; }, 3);
  for (const double place : places)
    EXPECT_EQ(place, 0.4);
}

TEST(LiftOffEnd, BracketThatNoLongerHoldsThePlaceIsLeft) {
  // The root is bracketed in [0.1, 0.5] (wanted(x) = 0.05 / x), then the pair's motion
  // changes and the edges press up to 0.9 whatever the springs: the search closes in on the
  // bracket's end at 0.5 until the bracket is narrower than its negligible width and then
  // goes to 0.9; it never stays stuck inside the old bracket.
  LiftOffEnd end;
  double x = end.next(0.1, 0.5, 1e-12);
  x = end.next(x, 0.05 / x, 1e-12);
  ASSERT_TRUE(end.bracketed);
  int calls = 0;
  while (x != 0.9 && calls < 200) {
    x = end.next(x, 0.9, 1e-12);
    EXPECT_LE(x, 0.9);
    ++calls;
  }
  EXPECT_EQ(x, 0.9);
  EXPECT_LT(calls, 100);
  EXPECT_FALSE(end.bracketed);
}

} // namespace
} // namespace nmm
