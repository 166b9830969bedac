// SPDX-License-Identifier: MIT
// Joint sets through the case file (issue 46, item 1): a slope cut by a generated joint set
// into DDA blocks slides at a friction angle below the set's dip and stands above it (limit
// equilibrium of a block on a plane), on two geometries; and `[[joint_set]]`'s bad input.
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../support/case_fixtures.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace nmm {
namespace {

using testing::TempDir;
using testing::write_text;

/// A slope: the top at y = 12 from x = 0 to the crest (10, 12), a face dipping 59 degrees
/// down to the toe (16, 2), the floor at y = 2 to x = 24, the base at y = 0 (held).
constexpr const char* slope_geo = R"(Point(1) = {0, 0, 0};
Point(2) = {24, 0, 0};
Point(3) = {24, 2, 0};
Point(4) = {16, 2, 0};
Point(5) = {10, 12, 0};
Point(6) = {0, 12, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Physical Surface("rock") = {1};
Physical Curve("base") = {1};
)";

/// The face point the joint daylights at.
const Point2 daylight(14.8, 4.0);

/// One joint set of a single line (spacing 100 m) dipping @p dip degrees out of the face
/// through `daylight`, friction @p phi on it and on the face; 300 dynamic steps of 1 ms from
/// the initial equilibrium; a monitor at the centroid of the wedge above the joint.
std::string slope_case(double dip, double phi, const Point2& centroid) {
  std::ostringstream c;
  c.precision(17);
  c << "geometry = \"slope.geo\"\n[cover_mesh]\nsize = 2.0\n"
    << "[materials.rock]\nmodel = \"dda\"\ndensity = 2600.0\nyoung = 5.0e9\npoisson = 0.25\n"
    << "[joints.set]\nfriction_angle = " << phi << "\n[contact]\nfriction_angle = " << phi
    << "\n[[joint_set]]\njoint = \"set\"\nangle = " << -dip << "\nspacing = 100.0\n"
    << "origin = [" << daylight.x() << ", " << daylight.y() << "]\n"
    << "[[boundary]]\ncurve = \"base\"\nfix = \"xy\"\n[[load]]\ngravity = [0.0, -9.81]\n"
    << "[analysis]\nkind = \"dynamic\"\nsteps = 300\ntime_step = 1.0e-3\n"
    << "initial_equilibrium = true\n"
    << "[[monitor]]\nname = \"wedge\"\npoint = [" << centroid.x() << ", " << centroid.y()
    << "]\n[output]\ndir = \"out\"\nevery = 300\n";
  return c.str();
}

TEST(JointSetCase, AWedgeCutByAGeneratedSetSlidesBelowTheDipAndStandsAbove) {
  // The wedge above the joint is a rigid block on a plane of dip d: with friction phi < d it
  // slides with a = g (sin d - tan phi cos d), s = a t^2 / 2 after t = 0.3 s; with phi > d
  // it stands. phi = d -+ 3 degrees, d = 30 and 40 degrees (two wedges: the joint meets the
  // top at x = 0.94 m and 5.27 m).
  const TempDir dir("nmm_joint_set_case");
  write_text(dir.path() / "slope.geo", slope_geo);
  for (const double dip : {30.0, 40.0}) {
    const double d = dip * std::numbers::pi / 180.0;
    const Point2 top(daylight.x() - (12.0 - daylight.y()) / std::tan(d), 12.0);
    const Point2 centroid = (daylight + top + Point2(10.0, 12.0)) / 3.0;
    for (const double phi : {dip - 3.0, dip + 3.0}) {
      write_text(dir.path() / "case.toml", slope_case(dip, phi, centroid));
      CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
      // The wedge, the rest of the slope, and the piece of the floor the line cuts where it
      // comes back into the material beyond the toe (held by the base).
      EXPECT_EQ(analysis.geometry().covers.n_blocks(), 3) << dip;
      RunOptions options;
      options.output_dir = dir.path() / "out";
      const RunResult result = run_case(analysis, options);
      ASSERT_EQ(result.steps, 300);
      const MonitorValues wedge = analysis.monitor_values().at(0);
      const double slid = wedge.ux * std::cos(d) - wedge.uy * std::sin(d);
      const double t = result.time;
      const double a =
          9.81 * (std::sin(d) - std::tan(phi * std::numbers::pi / 180.0) * std::cos(d));
      if (phi < dip) {
        // A DDA block on penalty springs: measured -0.019% (d = 30) and -0.025% (d = 40).
        // 0.5% is 20 times that and a sixth of what 0.1 degree more friction changes (3.2%
        // at d = 30: a falls by 32% per degree at phi = d - 3).
        EXPECT_NEAR(slid, 0.5 * a * t * t, 0.005 * 0.5 * a * t * t) << dip << " " << phi;
      } else {
        // Stands: only the springs' settling, measured 1.8e-9 m and 2.8e-9 m; 1e-6 m is four
        // orders below the 26 mm and 29 mm the wedges slide at phi = d - 3.
        EXPECT_LT(std::abs(slid), 1e-6) << dip << " " << phi;
      }
    }
  }
}

/// The message of the InputError reading @p text throws, or "" when none.
std::string error_of(const TempDir& dir, const std::string& text) {
  write_text(dir.path() / "slope.geo", slope_geo);
  write_text(dir.path() / "case.toml", text);
  try {
    CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JointSetCase, BadJointSetsAreRefusedNamingTheFileTheLineAndWhatToDo) {
  const TempDir dir("nmm_joint_set_errors");
  const std::string good = slope_case(30.0, 20.0, {10.0, 10.0});
  // The [[joint_set]] header is line 13 of slope_case(); joint, angle, spacing follow.
  const auto expect = [&](const std::string& from, const std::string& to, const std::string& where,
                          const std::string& what) {
    std::string text = good;
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    const std::string message = error_of(dir, text);
    EXPECT_NE(message.find(where), std::string::npos) << message;
    EXPECT_NE(message.find(what), std::string::npos) << message;
  };
  expect("spacing = 100.0", "spacing = 0.0", "case.toml:16", "spacing = 0 is out of range");
  expect("spacing = 100.0", "spacing = -2.0", "case.toml:16", "it must be > 0");
  expect("joint = \"set\"", "joint = \"bedding\"", "case.toml:14",
         "is not a [joints.NAME] table of the case");
  expect("spacing = 100.0", "spacing = 100.0\ngap = 1.0", "case.toml:17", "gap needs a trace");
  expect("spacing = 100.0", "spacing = 100.0\nspacing_deviation = 100.0", "case.toml:17",
         "below spacing");
  expect("spacing = 100.0", "spacing = 100.0\nregion = \"clay\"", "case.toml:13",
         "region = \"clay\" is not a Physical Surface");
  expect("spacing = 100.0", "spacing = 100.0\nspacings = 2.0", "case.toml:17",
         "has no key spacings");
  expect("spacing = 100.0", "spacing = 0.1\nmax_joints = 50", "case.toml:13", "raise `max_joints`");
  expect("spacing = 100.0", "spacing = 0.2\nmax_blocks = 20", "case.toml:13", "raise `max_blocks`");
  // Good input is not refused.
  EXPECT_EQ(error_of(dir, good), "");
}

TEST(JointSetCase, ATraceWithoutAGapWarnsThatTheJointsActAsPersistentOnes) {
  const TempDir dir("nmm_joint_set_trace_warning");
  const std::string good = slope_case(30.0, 20.0, {10.0, 10.0});
  const auto warnings_of = [&](const std::string& to) {
    std::string text = good;
    text.replace(text.find("spacing = 100.0"), 15, to);
    return parse_case_text(text, dir.path() / "case.toml").warnings;
  };
  // Line 17 is the first line after spacing (line 16) of slope_case()'s [[joint_set]].
  const std::vector<std::string> without_gap = warnings_of("spacing = 100.0\ntrace = 5.0");
  ASSERT_EQ(without_gap.size(), 1u);
  EXPECT_NE(without_gap[0].find("case.toml:17: [[joint_set]] (joint = \"set\") trace = 5 "
                                "without gap"),
            std::string::npos)
      << without_gap[0];
  EXPECT_NE(without_gap[0].find("add gap = 1.0"), std::string::npos) << without_gap[0];
  // A gap given, even 0, is the user's choice: no warning.
  EXPECT_TRUE(warnings_of("spacing = 100.0\ntrace = 5.0\ngap = 0.0").empty());
  EXPECT_TRUE(warnings_of("spacing = 100.0\ntrace = 5.0\ngap = 1.0").empty());
  EXPECT_TRUE(warnings_of("spacing = 100.0").empty());
}

} // namespace
} // namespace nmm
