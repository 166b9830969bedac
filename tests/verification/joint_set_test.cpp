// SPDX-License-Identifier: MIT
// Joint sets (issue 46, item 1): the joints generate_joint_sets() makes against the set's
// own definition (counts, spacing normal to the joints, trace and gap lengths, clipping to
// the material and a region, seeds), the snapping and dropping rules on both sides of the
// tolerance, and a family of angles and spacings cut into blocks with no sliver among them.
#include "mesh/cover_mesher.hpp"
#include "mesh/error.hpp"
#include "mesh/joint_set.hpp"
#include "mesh/math_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace nmm {
namespace {

PhysicalMesh single_region(const Loop& outer, const std::vector<Loop>& holes = {}) {
  PhysicalMesh physical;
  physical.source = "test.geo";
  physical.regions.push_back({"rock", {Polygon{outer, holes}}});
  validate_physical_mesh(physical);
  return physical;
}

PhysicalMesh rectangle(double width, double height) {
  return single_region({{0.0, 0.0}, {width, 0.0}, {width, height}, {0.0, height}});
}

/// A road cut 40 m wide: the ground at y = 20 for x < 20, a face dipping 63.4 degrees down
/// to the toe at (26, 8), the road at y = 8 to x = 40, the base at y = 0.
PhysicalMesh road_cut() {
  return single_region(
      {{0.0, 0.0}, {40.0, 0.0}, {40.0, 8.0}, {26.0, 8.0}, {20.0, 20.0}, {0.0, 20.0}});
}

JointSetParameters persistent(double angle, double spacing, Point2 origin) {
  JointSetParameters set;
  set.where = "case.toml:7: [[joint_set]]";
  set.angle_degrees = angle;
  set.spacing = spacing;
  set.origin = origin;
  return set;
}

Point2 direction(double degrees) {
  const double a = degrees * std::numbers::pi / 180.0;
  return {std::cos(a), std::sin(a)};
}

double boundary_distance(const PhysicalMesh& physical, const Point2& p) {
  double best = 1e300;
  for (const Polygon& polygon : physical.regions[0].polygons) {
    std::vector<const Loop*> loops{&polygon.outer};
    for (const Loop& hole : polygon.holes)
      loops.push_back(&hole);
    for (const Loop* loop : loops) {
      for (std::size_t i = 0; i < loop->size(); ++i) {
        const Point2& a = (*loop)[i];
        const Point2& b = (*loop)[(i + 1) % loop->size()];
        const double s = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        best = std::min(best, (p - (a + s * (b - a))).norm());
      }
    }
  }
  return best;
}

TEST(JointSet, PersistentSetCrossesARectangleAtItsSpacingOnEveryLine) {
  // Persistent joints across a convex polygon: one joint per line of the set that crosses it,
  // the lines at p = k spacing from the origin along the normal n = (-sin a, cos a); every
  // joint from boundary to boundary (its ends within the overshoot, 1e-3 of the tolerance, of
  // the boundary), parallel to the set's angle, the distance between neighbours measured
  // normal to them equal to the spacing (to rounding: 1e-12 m on a 10 m model).
  // Several geometries: three angles (one negative) and two spacings on two rectangles.
  for (const auto& [width, height] : {std::pair{10.0, 5.0}, std::pair{4.0, 9.0}}) {
    const PhysicalMesh physical = rectangle(width, height);
    for (const double angle : {0.0, 30.0, -35.0, 90.0}) {
      for (const double spacing : {0.7, 1.1}) {
        const JointSetParameters set = persistent(angle, spacing, {0.37 * width, 0.41 * height});
        const JointSetResult result = generate_joint_sets(physical, {}, std::span(&set, 1));
        ASSERT_EQ(result.joints.size(), 1U);
        const double tolerance = result.snap_tolerance[0];
        const Point2 t = direction(angle);
        const Point2 n(-t.y(), t.x());
        // The lines of the set inside the box: those farther than 3 tolerances from every
        // corner must be there; those within one are dropped (they would cut a sliver off
        // it); between the two, a short chord is dropped when it lies everywhere within the
        // tolerance of the boundary.
        std::vector<double> required;
        std::vector<double> allowed;
        double low = 1e300;
        double high = -1e300;
        std::vector<double> corners;
        for (const Point2& c : physical.regions[0].polygons[0].outer) {
          corners.push_back((c - set.origin).dot(n));
          low = std::min(low, corners.back());
          high = std::max(high, corners.back());
        }
        for (long k = static_cast<long>(std::ceil(low / spacing)); k * spacing < high; ++k) {
          const double p = static_cast<double>(k) * spacing;
          double nearest = 1e300;
          for (const double c : corners)
            nearest = std::min(nearest, std::abs(c - p));
          if (nearest > 3.0 * tolerance)
            required.push_back(p);
          if (nearest > tolerance)
            allowed.push_back(p);
        }
        std::vector<double> measured;
        for (const JointSegment& joint : result.joints[0]) {
          const Point2 along = (joint.b - joint.a).normalized();
          EXPECT_NEAR(std::abs(along.dot(t)), 1.0, 1e-12);
          EXPECT_LT(boundary_distance(physical, joint.a), 2e-3 * tolerance);
          EXPECT_LT(boundary_distance(physical, joint.b), 2e-3 * tolerance);
          measured.push_back((joint.a - set.origin).dot(n));
        }
        const auto found = [&](double p) {
          return std::any_of(measured.begin(), measured.end(),
                             [&](double m) { return std::abs(m - p) < 1e-12 * width; });
        };
        for (const double p : required)
          EXPECT_TRUE(found(p)) << angle << " " << spacing << " line at " << p;
        for (const double m : measured)
          EXPECT_TRUE(std::any_of(allowed.begin(), allowed.end(),
                                  [&](double p) { return std::abs(m - p) < 1e-12 * width; }))
              << angle << " " << spacing << " joint at " << m;
        EXPECT_GE(measured.size(), required.size());
      }
    }
  }
}

TEST(JointSet, TracesAndGapsAlternateFromTheOriginAlongEachLine) {
  // trace = 2 m, gap = 1 m, angle 0 in a 20 m x 3 m rectangle, origin (0.5, 0.5): on each line
  // the traces start at x = 0.5 + 3 j; the last one (18.5 to 20.5) is clipped at x = 20. Every
  // joint is 2 m long (to rounding) except the clipped one, and the rock bridges between
  // consecutive joints of a line are 1 m.
  const PhysicalMesh physical = rectangle(20.0, 3.0);
  JointSetParameters set = persistent(0.0, 1.0, {0.5, 0.5});
  set.trace = 2.0;
  set.gap = 1.0;
  const JointSetResult result = generate_joint_sets(physical, {}, std::span(&set, 1));
  const double overshoot = 1e-3 * result.snap_tolerance[0];
  std::vector<std::vector<JointSegment>> lines(3);
  for (const JointSegment& joint : result.joints[0]) {
    const double y = joint.a.y();
    ASSERT_NEAR(joint.b.y(), y, 1e-15);
    const int line = static_cast<int>(std::lround(y - 0.5));
    ASSERT_TRUE(line >= 0 && line < 3) << y;
    lines[static_cast<std::size_t>(line)].push_back(joint);
  }
  for (auto& line : lines) {
    ASSERT_EQ(line.size(), 7U); // traces at 0.5, 3.5, ..., 18.5
    std::sort(line.begin(), line.end(),
              [](const JointSegment& p, const JointSegment& q) { return p.a.x() < q.a.x(); });
    for (std::size_t j = 0; j < line.size(); ++j) {
      const double start = std::min(line[j].a.x(), line[j].b.x());
      const double end = std::max(line[j].a.x(), line[j].b.x());
      EXPECT_NEAR(start, 0.5 + 3.0 * static_cast<double>(j), 1e-12);
      EXPECT_NEAR(end, j + 1 < line.size() ? start + 2.0 : 20.0 + overshoot, 1e-12);
      if (j > 0) {
        EXPECT_NEAR(start - std::max(line[j - 1].a.x(), line[j - 1].b.x()), 1.0, 1e-12);
      }
    }
  }
}

double mean(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values)
    sum += v;
  return sum / static_cast<double>(values.size());
}

TEST(JointSet, DeviationsStayInTheirRangeAverageToTheMeanAndFollowTheSeed) {
  // spacing 0.5 +- 0.2 m, trace 1 +- 0.4 m, gap 0.5 +- 0.3 m, angle 0: each value uniform in
  // its range, so the measured spacings, traces and gaps lie in it and their means are the
  // set's within 4 standard errors (deviation / sqrt(3 N)); the same seed gives the same
  // joints to the bit, another seed others.
  const PhysicalMesh physical = rectangle(40.0, 40.0);
  JointSetParameters set = persistent(0.0, 0.5, {20.0, 20.0});
  set.trace = 1.0;
  set.gap = 0.5;
  set.spacing_deviation = 0.2;
  set.trace_deviation = 0.4;
  set.gap_deviation = 0.3;
  set.seed = 46;
  set.snap_tolerance = 0.01;
  set.max_joints = 100'000;
  set.max_blocks = 1'000'000;
  const JointSetResult result = generate_joint_sets(physical, {}, std::span(&set, 1));
  std::vector<double> ys;
  std::vector<double> traces;
  std::vector<double> gaps;
  std::vector<JointSegment> joints = result.joints[0];
  std::sort(joints.begin(), joints.end(), [](const JointSegment& p, const JointSegment& q) {
    return p.a.y() != q.a.y() ? p.a.y() < q.a.y() : p.a.x() < q.a.x();
  });
  for (std::size_t i = 0; i < joints.size(); ++i) {
    const JointSegment& j = joints[i];
    if (ys.empty() || j.a.y() != ys.back())
      ys.push_back(j.a.y());
    const bool inside = j.a.x() > 0.0 && j.b.x() < 40.0;
    if (inside)
      traces.push_back(j.b.x() - j.a.x());
    if (i > 0 && joints[i - 1].a.y() == j.a.y() && inside && joints[i - 1].a.x() > 0.0)
      gaps.push_back(j.a.x() - joints[i - 1].b.x());
  }
  std::vector<double> spacings;
  for (std::size_t i = 1; i < ys.size(); ++i)
    spacings.push_back(ys[i] - ys[i - 1]);
  const auto check = [](const std::vector<double>& values, double m, double d, const char* what) {
    ASSERT_GT(values.size(), 50U) << what;
    for (const double v : values) {
      EXPECT_GE(v, m - d - 1e-12) << what;
      EXPECT_LE(v, m + d + 1e-12) << what;
    }
    const double error = d / std::sqrt(3.0 * static_cast<double>(values.size()));
    EXPECT_NEAR(mean(values), m, 4.0 * error) << what;
  };
  check(spacings, 0.5, 0.2, "spacing");
  // Gaps narrower than the tolerance join two traces (a sliver bridge), so a few traces are
  // longer and a few gaps are missing; those are left out of the statistics.
  std::erase_if(traces, [](double v) { return v > 1.4 + 1e-12; });
  check(traces, 1.0, 0.4, "trace");
  check(gaps, 0.5, 0.3, "gap");

  const JointSetResult again = generate_joint_sets(physical, {}, std::span(&set, 1));
  ASSERT_EQ(again.joints[0].size(), result.joints[0].size());
  for (std::size_t i = 0; i < again.joints[0].size(); ++i) {
    EXPECT_EQ(again.joints[0][i].a, result.joints[0][i].a);
    EXPECT_EQ(again.joints[0][i].b, result.joints[0][i].b);
  }
  set.seed = 47;
  const JointSetResult other = generate_joint_sets(physical, {}, std::span(&set, 1));
  bool differs = other.joints[0].size() != result.joints[0].size();
  for (std::size_t i = 0; !differs && i < other.joints[0].size(); ++i)
    differs = other.joints[0][i].b != result.joints[0][i].b;
  EXPECT_TRUE(differs);
}

TEST(JointSet, AngleDeviationTurnsEachTraceWithinItsRange) {
  const PhysicalMesh physical = rectangle(30.0, 30.0);
  JointSetParameters set = persistent(20.0, 2.0, {15.0, 15.0});
  set.trace = 3.0;
  set.gap = 2.0;
  set.angle_deviation_degrees = 10.0;
  set.seed = 3;
  const JointSetResult result = generate_joint_sets(physical, {}, std::span(&set, 1));
  ASSERT_GT(result.joints[0].size(), 50U);
  double lowest = 90.0;
  double highest = -90.0;
  for (const JointSegment& j : result.joints[0]) {
    const Point2 d = j.b - j.a;
    const double angle = std::atan(d.y() / d.x()) * 180.0 / std::numbers::pi;
    lowest = std::min(lowest, angle);
    highest = std::max(highest, angle);
  }
  // Uniform in [10, 30] degrees: the extremes of 50 and more draws come within 2 degrees of
  // the ends (each misses by more with probability 0.9^50 = 0.5%).
  EXPECT_GE(lowest, 10.0 - 1e-9);
  EXPECT_LE(highest, 30.0 + 1e-9);
  EXPECT_LT(lowest, 12.0);
  EXPECT_GT(highest, 28.0);
}

TEST(JointSet, JointsAreClippedToTheMaterialAndTheirRegion) {
  // A 10 m square with a 4 m square hole, and a second region beside it: a set limited to
  // the second region lies in it only; a set over all material keeps out of the hole. Every
  // point of every joint (sampled at 21 points, ends within the overshoot) is in the material.
  PhysicalMesh physical;
  physical.source = "test.geo";
  physical.regions.push_back(
      {"rock",
       {Polygon{{{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{3, 3}, {3, 7}, {7, 7}, {7, 3}}}}}});
  physical.regions.push_back({"clay", {Polygon{{{10, 0}, {16, 0}, {16, 10}, {10, 10}}, {}}}});
  validate_physical_mesh(physical);
  for (const bool clay_only : {false, true}) {
    JointSetParameters set = persistent(25.0, 0.9, {5.1, 1.3});
    if (clay_only)
      set.regions = {1};
    const JointSetResult result = generate_joint_sets(physical, {}, std::span(&set, 1));
    ASSERT_GT(result.joints[0].size(), 5U);
    const double overshoot = 1e-3 * result.snap_tolerance[0];
    for (const JointSegment& j : result.joints[0]) {
      for (int i = 1; i < 20; ++i) {
        const Point2 p = j.a + i / 20.0 * (j.b - j.a);
        const bool in_hole = p.x() > 3 && p.x() < 7 && p.y() > 3 && p.y() < 7;
        EXPECT_FALSE(in_hole);
        EXPECT_TRUE(p.x() > -overshoot && p.x() < 16 + overshoot && p.y() > -overshoot &&
                    p.y() < 10 + overshoot);
        if (clay_only) {
          EXPECT_GT(p.x(), 10.0 - overshoot);
        }
      }
    }
  }
}

TEST(JointSet, EndsWithinTheToleranceSnapOntoTheBoundaryAndDrawnJointsOthersDoNot) {
  // Horizontal traces from x = 0 in a 10 m x 1 m rectangle, tolerance 0.05 m: a trace ending
  // 0.03 m short of the right side is moved onto it (and 1e-3 of the tolerance beyond);
  // one ending 0.08 m short is not. The same against a drawn joint at x = 6.
  const PhysicalMesh plain = rectangle(10.0, 1.0);
  for (const auto& [short_by, snaps] : {std::pair{0.03, true}, std::pair{0.08, false}}) {
    JointSetParameters set = persistent(0.0, 10.0, {0.0, 0.5});
    set.trace = 10.0 - short_by;
    set.gap = 20.0;
    set.snap_tolerance = 0.05;
    const JointSetResult result = generate_joint_sets(plain, {}, std::span(&set, 1));
    ASSERT_EQ(result.joints[0].size(), 1U);
    EXPECT_NEAR(result.joints[0][0].b.x(), snaps ? 10.0 + 5e-5 : 10.0 - short_by, 1e-12);
    EXPECT_EQ(result.notes.size(), snaps ? 1U : 0U);
  }
  PhysicalMesh drawn = rectangle(10.0, 1.0);
  drawn.curves.push_back({"fault", {{{6.0, -1.0}, {6.0, 2.0}}}});
  const std::vector<int> drawn_joints{0};
  for (const auto& [short_by, snaps] : {std::pair{0.03, true}, std::pair{0.08, false}}) {
    JointSetParameters set = persistent(0.0, 10.0, {1.0, 0.5});
    set.trace = 5.0 - short_by;
    set.gap = 20.0;
    set.snap_tolerance = 0.05;
    const JointSetResult result = generate_joint_sets(drawn, drawn_joints, std::span(&set, 1));
    ASSERT_EQ(result.joints[0].size(), 1U);
    EXPECT_NEAR(result.joints[0][0].b.x(), snaps ? 6.0 + 5e-5 : 6.0 - short_by, 1e-12);
  }
}

TEST(JointSet, JointsPassingByACornerOrAlongAnotherJointAreDroppedOthersKept) {
  // A 10 m square, tolerance 0.05 m; a set of one horizontal line at y = 0.03 lies everywhere
  // within the tolerance of the base: dropped; at y = 0.08: kept. A set at 45 degrees
  // through (0.5, 0) passes the corner (0, 0) at 0.354 m: kept; through (0.05, 0), at
  // 0.035 m: dropped (it would cut a triangle of 1.25e-3 m^2 off the corner).
  const PhysicalMesh physical = rectangle(10.0, 10.0);
  const auto count = [&](double angle, Point2 origin) {
    JointSetParameters set = persistent(angle, 100.0, origin);
    set.snap_tolerance = 0.05;
    return generate_joint_sets(physical, {}, std::span(&set, 1)).joints[0].size();
  };
  EXPECT_EQ(count(0.0, {5.0, 0.03}), 0U);
  EXPECT_EQ(count(0.0, {5.0, 0.08}), 1U);
  EXPECT_EQ(count(45.0, {0.5, 0.0}), 1U);
  EXPECT_EQ(count(45.0, {0.05, 0.0}), 0U);
  // A second set crossing the first's joint where it meets the boundary: a line through
  // (0.03, 5) crossing a line at y = 5 which meets x = 0: dropped.
  JointSetParameters sets[2] = {persistent(0.0, 100.0, {5.0, 5.0}),
                                persistent(80.0, 100.0, {0.04, 5.0})};
  sets[0].snap_tolerance = sets[1].snap_tolerance = 0.05;
  EXPECT_EQ(generate_joint_sets(physical, {}, sets).joints[1].size(), 0U);
  sets[1].origin = {0.3, 5.0};
  EXPECT_EQ(generate_joint_sets(physical, {}, sets).joints[1].size(), 1U);
}

TEST(JointSet, MoreJointsOrBlocksThanTheLimitsAreRefusedNamingTheTable) {
  const PhysicalMesh physical = rectangle(10.0, 10.0);
  JointSetParameters set = persistent(0.0, 1.0, {0.5, 0.5});
  set.max_joints = 10; // the set makes 10 joints (y = 0.5 ... 9.5): allowed
  EXPECT_EQ(generate_joint_sets(physical, {}, std::span(&set, 1)).joints[0].size(), 10U);
  set.max_joints = 9;
  try {
    (void)generate_joint_sets(physical, {}, std::span(&set, 1));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("case.toml:7: [[joint_set]]"), std::string::npos) << text;
    EXPECT_NE(text.find("max_joints = 9"), std::string::npos) << text;
    EXPECT_NE(text.find("raise `max_joints`"), std::string::npos) << text;
  }
  // Two persistent sets of 10 lines crossing in a square: 1 + 10 + 10 x 11 = 121 blocks.
  JointSetParameters sets[2] = {persistent(0.0, 1.0, {0.5, 0.5}),
                                persistent(90.0, 1.0, {0.5, 0.5})};
  sets[1].max_blocks = 121;
  EXPECT_EQ(generate_joint_sets(physical, {}, sets).block_bound, 121);
  sets[1].max_blocks = 120;
  EXPECT_THROW((void)generate_joint_sets(physical, {}, sets), InputError);
}

double perimeter(const CoverSystem& covers, const Block& block) {
  double total = 0.0;
  for (const int l : block.loops) {
    const auto& v = covers.loops[static_cast<std::size_t>(l)].vertices;
    for (std::size_t i = 0; i < v.size(); ++i)
      total += (v[(i + 1) % v.size()] - v[i]).norm();
  }
  return total;
}

TEST(JointSet, AFamilyOfAnglesAndSpacingsCutsTheRoadCutIntoNoSliverBlocks) {
  // The road cut of examples/18 cut by two persistent sets, over angles (negative ones too:
  // the daylighting set dips out of the face at -35 degrees) and spacings, into DDA blocks.
  // A sliver block of width w has 2 area / perimeter of about w. Without the snapping rules a
  // line passing by a corner at a rounding error cuts a block of 1e-15 m there; with them no
  // line passes within the tolerance h of a corner or a crossing, so the thinnest block left
  // is a wedge of the smallest angle theta between two of the lines (sets and boundary
  // edges) with a height of at least h: 2 area / perimeter >= h sin(theta/2) / (1 +
  // sin(theta/2)) (the isosceles wedge, the thinnest of that height and angle).
  const PhysicalMesh physical = road_cut();
  for (const double first : {-35.0, -20.0, -50.0}) {
    for (const double second : {60.0, 75.0, 100.0}) {
      for (const double spacing : {1.3, 2.1, 3.0}) {
        JointSetParameters sets[2] = {persistent(first, spacing, {23.0, 14.0}),
                                      persistent(second, 1.3 * spacing, {23.0, 14.0})};
        const JointSetResult result = generate_joint_sets(physical, {}, sets);
        PhysicalMesh cut = physical;
        std::vector<int> joints;
        for (const auto& set : result.joints) {
          NamedCurve curve{"set" + std::to_string(joints.size()), {}};
          for (const JointSegment& j : set)
            curve.polylines.push_back({j.a, j.b});
          if (curve.polylines.empty())
            continue;
          joints.push_back(static_cast<int>(cut.curves.size()));
          cut.curves.push_back(curve);
        }
        CoverMesherOptions options;
        options.block_regions = {0};
        const MathMesh math = make_regular_math_mesh(material_bounding_box(cut), 2.0);
        const CoverSystem covers = build_cover_system(math, cut, joints, options);
        EXPECT_LE(covers.n_blocks(), result.block_bound);
        double thinnest = 1e300;
        for (const Block& block : covers.blocks)
          thinnest = std::min(thinnest, 2.0 * block.area / perimeter(covers, block));
        double theta = std::numbers::pi;
        const Loop& outer = cut.regions[0].polygons[0].outer;
        std::vector<double> lines{first, second};
        for (std::size_t i = 0; i < outer.size(); ++i) {
          const Point2 d = outer[(i + 1) % outer.size()] - outer[i];
          lines.push_back(std::atan2(d.y(), d.x()) * 180.0 / std::numbers::pi);
        }
        for (std::size_t i = 0; i < 2; ++i) {
          for (std::size_t j = i + 1; j < lines.size(); ++j) {
            const double a = std::remainder(lines[i] - lines[j], 180.0);
            theta = std::min(theta, std::abs(a) * std::numbers::pi / 180.0);
          }
        }
        const double s = std::sin(0.5 * theta);
        EXPECT_GT(thinnest, result.snap_tolerance[0] * s / (1.0 + s))
            << first << " " << second << " " << spacing;
      }
    }
  }
}

} // namespace
} // namespace nmm
