// SPDX-License-Identifier: MIT
#include "mesh/curve_resolution.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace nmm {
namespace {

/// A regular n-gon of circumradius r about the origin, counter-clockwise.
std::vector<Point2> regular_polygon(int n, double r) {
  std::vector<Point2> points;
  for (int i = 0; i < n; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n;
    points.emplace_back(r * std::cos(angle), r * std::sin(angle));
  }
  return points;
}

TEST(CurveResolution, AutomaticToleranceIsTheFinerOfTheModelAndTheCoverSizeRule) {
  EXPECT_DOUBLE_EQ(automatic_curve_tolerance(22.6, 0.5), 0.005);
  EXPECT_DOUBLE_EQ(automatic_curve_tolerance(2.0, 0.5), 0.002);
  EXPECT_DOUBLE_EQ(automatic_curve_tolerance(22.6, 0.0), 0.0226);
}

TEST(CurveResolution, OctagonOfASixMetreTunnelIsCoarseAtCoverSizeHalfAMetre) {
  const std::vector<CoarseSegment> coarse = coarse_segments(regular_polygon(8, 3.0), true, 0.5);
  ASSERT_EQ(coarse.size(), 8U);
  // Chords of 2 r sin(22.5°) = 2.30 m, estimated 2.30 × (π/4) / 8 = 0.225 m off the circle
  // (the sagitta is 0.228 m).
  EXPECT_NEAR(coarse[0].length, 6.0 * std::sin(std::numbers::pi / 8.0), 1e-12);
  EXPECT_NEAR(coarse[0].deviation, coarse[0].length * std::numbers::pi / 4.0 / 8.0, 1e-12);
  // Sampled for the cover size: no coarse segment; nor at a cover size above the chords.
  EXPECT_TRUE(coarse_segments(regular_polygon(64, 3.0), true, 0.5).empty());
  EXPECT_TRUE(coarse_segments(regular_polygon(8, 3.0), true, 2.5).empty());
}

TEST(CurveResolution, PolygonsStraightRunsAndSingleSegmentsAreNeverCoarse) {
  // A hexagon turns by 60° at each corner: a polygon, not a sampled curve.
  EXPECT_TRUE(coarse_segments(regular_polygon(6, 3.0), true, 0.5).empty());
  // A square with collinear mesh nodes along its sides.
  EXPECT_TRUE(coarse_segments({{0, 0}, {2, 0}, {4, 0}, {4, 4}, {0, 4}}, true, 0.5).empty());
  // One long straight segment, and a straight run.
  EXPECT_TRUE(coarse_segments({{0, 0}, {10, 0}}, false, 0.5).empty());
  EXPECT_TRUE(coarse_segments({{0, 0}, {5, 0}, {10, 0}}, false, 0.5).empty());
  // A zigzag turns both ways: its inner segments are no bend (the end segments, which turn
  // at one end only, are taken for the chords of an arc).
  const std::vector<CoarseSegment> zigzag =
      coarse_segments({{0, 0}, {2, 0.3}, {4, 0}, {6, 0.3}, {8, 0}}, false, 0.5);
  ASSERT_EQ(zigzag.size(), 2U);
  EXPECT_EQ(zigzag[0].a, Point2(0, 0));
  EXPECT_EQ(zigzag[1].b, Point2(8, 0));
  // The straight sides next to a coarse rounded corner are not coarse; the arc is.
  const std::vector<Point2> rounded{{-5, 0},  {-2.5, 0}, {0, 0},   {2, 0.5},
                                    {3.5, 2}, {4, 4},    {4, 6.5}, {4, 9}};
  const std::vector<CoarseSegment> coarse = coarse_segments(rounded, false, 0.5);
  ASSERT_EQ(coarse.size(), 3U);
  EXPECT_EQ(coarse.front().a, Point2(0, 0));
  EXPECT_EQ(coarse.back().b, Point2(4, 4));
}

TEST(CurveResolution, OpenArcWithOneSegmentPerHalfIsCoarseAtItsInteriorTurn) {
  // A quarter of the octagon's circle, as a .msh gives it: two chords meeting at 45°.
  const double r = 3.0;
  const std::vector<Point2> quarter{
      {r, 0}, {r * std::cos(std::numbers::pi / 4), r * std::sin(std::numbers::pi / 4)}, {0, r}};
  EXPECT_EQ(coarse_segments(quarter, false, 0.5).size(), 2U);
}

} // namespace
} // namespace nmm
