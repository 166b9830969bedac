// SPDX-License-Identifier: MIT
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace nmm {
namespace {

TEST(Geometry, SignedAreaIsPositiveCounterClockwiseAndNegativeClockwise) {
  const Loop ccw{{0, 0}, {2, 0}, {2, 1}, {0, 1}};
  const Loop cw(ccw.rbegin(), ccw.rend());
  EXPECT_DOUBLE_EQ(signed_area(ccw), 2.0);
  EXPECT_DOUBLE_EQ(signed_area(cw), -2.0);
  EXPECT_TRUE(is_counter_clockwise(ccw));
  EXPECT_FALSE(is_counter_clockwise(cw));
}

TEST(Geometry, AreaOfPolygonWithHoleIgnoresLoopOrientation) {
  // Outer 4x4 clockwise, hole 1x1 counter-clockwise: 16 - 1 whatever the orientations.
  const Polygon polygon{{{0, 0}, {0, 4}, {4, 4}, {4, 0}}, {{{1, 1}, {2, 1}, {2, 2}, {1, 2}}}};
  EXPECT_DOUBLE_EQ(area(polygon), 15.0);
}

TEST(Geometry, SmallLoopFarFromOriginKeepsItsArea) {
  // Cross products of absolute coordinates near 1e6 would cancel to ~1e-4 relative error;
  // the first-vertex fan keeps the exact value of this binary-representable square.
  const double x0 = 1.0e6;
  const double h = 1.0 / 1024.0;
  const Loop loop{{x0, x0}, {x0 + h, x0}, {x0 + h, x0 + h}, {x0, x0 + h}};
  EXPECT_EQ(signed_area(loop), h * h);
}

TEST(Geometry, BoundingBoxGrowsFromEmpty) {
  BoundingBox box;
  EXPECT_TRUE(box.is_empty());
  const Loop points{{1, 5}, {-2, 3}, {4, -1}};
  box = bounding_box(points);
  EXPECT_FALSE(box.is_empty());
  EXPECT_EQ(box.min, Point2(-2, -1));
  EXPECT_EQ(box.max, Point2(4, 5));
}

TEST(Error, InputErrorNamesFileLineAndColumn) {
  const InputError e("case.toml", 12, 3, "unknown key 'densty'; did you mean 'density'?");
  EXPECT_STREQ(e.what(), "case.toml:12:3: unknown key 'densty'; did you mean 'density'?");
  EXPECT_EQ(e.file(), "case.toml");
  EXPECT_EQ(e.line(), 12);
}

#ifndef NDEBUG
TEST(Error, FailedAssertionThrowsInsteadOfAborting) {
  EXPECT_THROW(NMM_ASSERT(1 + 1 == 3, "arithmetic"), std::logic_error);
}
#endif

} // namespace
} // namespace nmm
