// SPDX-License-Identifier: MIT
// tests/verification/bolt_test.cpp — rock bolts (`[[bolt]]`, issue 46 item 5) against limit
// equilibrium: a block of weight W on a plane of angle alpha steeper than its joint's
// friction angle phi, held by one bolt along the slide to an anchor up the slope. Shi's
// static steps from rest let it slide until the bolt holds what friction cannot, so at rest
// the bolt pulls T = W (sin alpha - tan phi cos alpha) while the base slides at its limit.
// Within 1%: the block's springs and the bolt's stretch settle geometrically from step to step
// (the last step moves < 1e-6 of the first), the penalty springs add a few 1e-4. A bolt whose
// yield force is 0.9 T yields and the block slides on (its force stays at the yield force); at
// 1.1 T it holds. DDA, VEM and NMM blocks (order 0 and 1), several angles, block sizes and
// bolt stiffnesses, end-anchored and grouted.
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

namespace nmm {
namespace {

using testing::TempDir;
using testing::write_text;

constexpr double degrees = std::numbers::pi / 180.0;
constexpr double density = 2500.0; // kg/m^3
constexpr double gravity = 9.81;   // m/s^2

/// One bolted block on a plane.
struct BoltedBlock {
  const char* model;        ///< of the block, the ramp and the anchor
  double alpha_degrees;     ///< the plane's angle
  double phi_degrees;       ///< the joint's friction angle
  double length = 1.0;      ///< of the block along the plane, m
  double height = 0.5;      ///< across it, m
  double stiffness = 2.0e8; ///< the bolt's axial stiffness, N/m
  const char* kind = "end_anchored";
  int order = 0;                ///< NMM covers
  double cover_size = 0.25;     ///< m (nmm only)
  const char* mesh = "regular"; ///< [cover_mesh] kind

  [[nodiscard]] double weight() const { return density * gravity * length * height; }
  /// Limit equilibrium: the bolt's force when the base slides at its limit.
  [[nodiscard]] double bolt_force() const {
    const double a = alpha_degrees * degrees;
    return weight() * (std::sin(a) - std::tan(phi_degrees * degrees) * std::cos(a));
  }
};

std::ostream& operator<<(std::ostream& out, const BoltedBlock& c) {
  return out << c.model << " order " << c.order << " alpha " << c.alpha_degrees << " phi "
             << c.phi_degrees << " L " << c.length << " H " << c.height << " k " << c.stiffness
             << " " << c.kind << " " << c.mesh << " mesh";
}

/// A point at @p s along the plane and @p n across it (from its foot).
Eigen::Vector2d on_plane(const BoltedBlock& c, double s, double n) {
  const double a = c.alpha_degrees * degrees;
  return s * Eigen::Vector2d(std::cos(a), std::sin(a)) +
         n * Eigen::Vector2d(-std::sin(a), std::cos(a));
}

/// A ramp 6 m long and 0.5 m thick, its underside "base" held; the block L x H on it 1.5 m
/// up (its underside the joint "slip"); 0.5 m above the block an anchor 0.5 m x H, its top
/// "anchor_top" held.
std::string bolted_geo(const BoltedBlock& c) {
  const double s0 = 1.5;
  const double s1 = s0 + c.length;
  const double a0 = s1 + 0.5;
  const double a1 = a0 + 0.5;
  const Eigen::Vector2d points[] = {
      on_plane(c, 0, 0),         on_plane(c, 0, -0.5),      on_plane(c, 6, -0.5),
      on_plane(c, 6, 0),         on_plane(c, s0, 0),        on_plane(c, s1, 0),
      on_plane(c, s1, c.height), on_plane(c, s0, c.height), on_plane(c, a0, 0),
      on_plane(c, a1, 0),        on_plane(c, a1, c.height), on_plane(c, a0, c.height)};
  std::ostringstream geo;
  geo.precision(17);
  for (int k = 0; k < 12; ++k)
    geo << "Point(" << k + 1 << ") = {" << points[k].x() << ", " << points[k].y() << ", 0};\n";
  // The ramp's top runs 1 -> 5 -> 6 -> 9 -> 10 -> 4 so that the block and the anchor sit on
  // pieces of it.
  geo << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 10};\n"
      << "Line(5) = {10, 9};\nLine(6) = {9, 6};\nLine(7) = {6, 5};\nLine(8) = {5, 1};\n"
      << "Line(9) = {6, 7};\nLine(10) = {7, 8};\nLine(11) = {8, 5};\n"
      << "Line(12) = {10, 11};\nLine(13) = {11, 12};\nLine(14) = {12, 9};\n"
      << "Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};\nPlane Surface(1) = {1};\n"
      << "Curve Loop(2) = {-7, 9, 10, 11};\nPlane Surface(2) = {2};\n"
      << "Curve Loop(3) = {-5, 12, 13, 14};\nPlane Surface(3) = {3};\n"
      << "Physical Surface(\"ramp\") = {1};\nPhysical Surface(\"block\") = {2};\n"
      << "Physical Surface(\"anchor\") = {3};\nPhysical Curve(\"slip\") = {7};\n"
      << "Physical Curve(\"base\") = {2};\nPhysical Curve(\"anchor_top\") = {13};\n";
  return geo.str();
}

/// The case: Shi's static steps from rest; the bolt from the block's centre to the anchor's,
/// along the slide; @p bolt_extra adds keys to [[bolt]].
std::string bolted_case(const BoltedBlock& c,
                        int steps,
                        const std::string& bolt_extra,
                        const std::string& analysis) {
  const Eigen::Vector2d from = on_plane(c, 1.5 + 0.5 * c.length, 0.5 * c.height);
  const Eigen::Vector2d to = on_plane(c, 1.5 + c.length + 0.75, 0.5 * c.height);
  std::ostringstream text;
  text.precision(17);
  text << "geometry = \"bolted.geo\"\n[cover_mesh]\nkind = \"" << c.mesh
       << "\"\nsize = " << c.cover_size << "\norder = " << c.order << "\n";
  for (const char* material : {"ramp", "block", "anchor"})
    text << "[materials." << material << "]\nmodel = \"" << c.model << "\"\ndensity = " << density
         << "\nyoung = 1.0e9\npoisson = 0.25\n";
  text << "[joints.slip]\nfriction_angle = " << c.phi_degrees << "\n"
       << "[contact]\nfriction_angle = " << c.phi_degrees << "\n"
       << "[[boundary]]\ncurve = \"base\"\nfix = \"xy\"\n"
       << "[[boundary]]\ncurve = \"anchor_top\"\nfix = \"xy\"\n"
       << "[[load]]\ngravity = [0.0, " << -gravity << "]\n"
       << "[[bolt]]\nname = \"B1\"\nfrom = [" << from.x() << ", " << from.y() << "]\nto = ["
       << to.x() << ", " << to.y() << "]\nkind = \"" << c.kind << "\"\nstiffness = " << c.stiffness
       << "\n"
       << bolt_extra << "[analysis]\n"
       << analysis << "steps = " << steps << "\n[[monitor]]\nname = \"block\"\npoint = ["
       << from.x() << ", " << from.y() << "]\n";
  return text.str();
}

struct BoltRun {
  double force = 0.0;      ///< the bolt's force at the end, N
  double first_step = 0.0; ///< the block's displacement in the first step, m
  double last_step = 0.0;  ///< ... in the last, m
  double slide = 0.0;      ///< its total displacement down the slope, m
  BoltState state = BoltState::elastic;
  double energy_error = 0.0; ///< the largest of the steps' (StepReport::energy_error)
};

/// Shi's static steps of 0.01 s.
const std::string static_steps = "kind = \"static\"\ntime_step = 0.01\n";

BoltRun run_bolted(const BoltedBlock& c,
                   int steps,
                   const std::string& bolt_extra = "",
                   const std::string& analysis_keys = static_steps) {
  const TempDir dir("nmm_bolt");
  write_text(dir.path() / "bolted.geo", bolted_geo(c));
  write_text(dir.path() / "case.toml", bolted_case(c, steps, bolt_extra, analysis_keys));
  CaseAnalysis analysis(read_case_file(dir.path() / "case.toml"));
  TimeStepper& stepper = analysis.stepper();
  BoltRun run;
  Point2 last = analysis.monitor_values().front().x * Point2::UnitX() +
                analysis.monitor_values().front().y * Point2::UnitY();
  for (int k = 0; k < steps; ++k) {
    const StepReport report = stepper.step(std::numeric_limits<double>::infinity());
    run.energy_error = std::max(run.energy_error, report.energy_error);
    const MonitorValues m = analysis.monitor_values().front();
    const Point2 now(m.x, m.y);
    if (k == 0)
      run.first_step = (now - last).norm();
    run.last_step = (now - last).norm();
    const double a = c.alpha_degrees * degrees;
    run.slide = -(m.ux * std::cos(a) + m.uy * std::sin(a));
    last = now;
  }
  const Bolt& bolt = stepper.scene().bolts.front();
  run.force = bolt.force();
  run.state = bolt.state();
  return run;
}

class BoltAlongTheSlide : public ::testing::TestWithParam<BoltedBlock> {};

TEST_P(BoltAlongTheSlide, HoldsWithLimitEquilibriumsForceToOnePercent) {
  const BoltedBlock& c = GetParam();
  const BoltRun run = run_bolted(c, 300);
  const double expected = c.bolt_force();
  EXPECT_NEAR(run.force, expected, 0.01 * expected)
      << c << ": first step " << run.first_step << " m, last " << run.last_step << " m";
  EXPECT_EQ(run.state, BoltState::elastic) << c;
  // At rest: the last step moves a millionth of the first.
  EXPECT_LT(run.last_step, 1e-6 * run.first_step) << c;
  std::printf("[bolt] %s %s %s alpha %g phi %g: T = %.6g N (limit equilibrium %.6g, "
              "%+.3f%%), slid %.4g m\n",
              c.model, c.mesh, c.kind, c.alpha_degrees, c.phi_degrees, run.force, expected,
              100.0 * (run.force / expected - 1.0), run.slide);
}

// Order-1 covers are not among them: an order-1 block held at its friction limit creeps on
// (the bolt's force rises 0.1% a step from the limit's, reached after 6 steps, to +11% after
// 300 at alpha 35, phi 25; +3% at alpha 40, phi 20), as the same block without a bolt on a
// plane one degree flatter than its friction angle creeps with contacts held beyond their
// limit (issue 42's order-1 contact, not the bolt's).
INSTANTIATE_TEST_SUITE_P(
    Blocks,
    BoltAlongTheSlide,
    ::testing::Values(BoltedBlock{"dda", 35.0, 20.0},
                      BoltedBlock{"dda", 45.0, 30.0, 0.6, 0.4, 5.0e7},
                      BoltedBlock{"dda", 30.0, 15.0, 1.2, 0.6, 1.0e9, "grouted"},
                      BoltedBlock{"vem", 40.0, 25.0},
                      BoltedBlock{"vem", 30.0, 10.0, 0.8, 0.8, 1.0e8, "grouted"},
                      BoltedBlock{"nmm", 35.0, 25.0},
                      BoltedBlock{"nmm", 35.0, 25.0, 1.0, 0.5, 2.0e8, "grouted"},
                      BoltedBlock{"nmm", 40.0, 20.0, 0.8, 0.4, 2.0e8, "end_anchored", 0, 0.2},
                      BoltedBlock{"nmm", 30.0, 20.0, 1.0, 0.5, 2.0e8, "grouted", 0, 0.2, "gmsh"},
                      BoltedBlock{"nmm", 45.0, 35.0, 0.6, 0.6, 1.0e8, "end_anchored", 0, 0.15,
                                  "gmsh"}));

/// Both sides of the yield force: at 1.1 T the bolt holds elastic; at 0.9 T it yields, its
/// force stays at the yield force, and the block slides on.
TEST(BoltYield, HoldsAboveTheLimitForceAndYieldsBelowIt) {
  const BoltedBlock c{"dda", 35.0, 20.0};
  const double t = c.bolt_force();
  const BoltRun holds = run_bolted(c, 300, "yield_force = " + std::to_string(1.1 * t) + "\n");
  EXPECT_EQ(holds.state, BoltState::elastic);
  EXPECT_NEAR(holds.force, t, 0.01 * t);
  EXPECT_LT(holds.last_step, 1e-6 * holds.first_step);
  const BoltRun yields = run_bolted(c, 300, "yield_force = " + std::to_string(0.9 * t) + "\n");
  EXPECT_EQ(yields.state, BoltState::yielding);
  EXPECT_NEAR(yields.force, 0.9 * t, 1e-9 * t);
  // Sliding on: the last step moves as far as the first steps did, and it has slid much
  // farther than the held block.
  EXPECT_GT(yields.last_step, 0.1 * yields.first_step);
  EXPECT_GT(yields.slide, 10.0 * holds.slide);
  std::printf("[bolt] yield 1.1 T: %.6g N, slid %.4g m; yield 0.9 T: %.6g N, slid %.4g m\n",
              holds.force, holds.slide, yields.force, yields.slide);
}

/// A brittle bolt (rupture_force below T) breaks, and the block slides away.
TEST(BoltRupture, ABoltWeakerThanTheLimitForceBreaks) {
  const BoltedBlock c{"dda", 35.0, 20.0};
  const double t = c.bolt_force();
  const BoltRun run = run_bolted(c, 100, "rupture_force = " + std::to_string(0.8 * t) + "\n");
  EXPECT_EQ(run.state, BoltState::ruptured);
  EXPECT_EQ(run.force, 0.0);
  EXPECT_GT(run.last_step, 0.1 * run.first_step);
}

/// A pretension below the limit force: the block slides until the bolt pulls T all the same,
/// less far. One above it: the bolt holds with its pretension (0.25% more: the ends' elastic
/// give) and the block moves only by the elastic strain of itself and the anchor (a quarter of
/// the free block's slide).
TEST(BoltPretension, BelowTheLimitForceTheBlockSlidesToItAboveItHolds) {
  const BoltedBlock c{"dda", 35.0, 20.0};
  const double t = c.bolt_force();
  const BoltRun free = run_bolted(c, 300);
  const BoltRun below = run_bolted(c, 300, "pretension = " + std::to_string(0.5 * t) + "\n");
  EXPECT_NEAR(below.force, t, 0.01 * t);
  EXPECT_LT(below.slide, 0.75 * free.slide);
  const BoltRun above = run_bolted(c, 300, "pretension = " + std::to_string(1.5 * t) + "\n");
  EXPECT_NEAR(above.force, 1.5 * t, 0.005 * t);
  EXPECT_LT(above.slide, 0.5 * free.slide);
  std::printf("[bolt] pretension 0.5 T: %.6g N, slid %.4g m; 1.5 T: %.6g N, moved %.4g m "
              "(none: slid %.4g m)\n",
              below.force, below.slide, above.force, above.slide, free.slide);
}

/// The energy balance of a dynamic run keeps the bolt's elastic energy, its plastic work and
/// the time integration's k d^2 / 2 (docs/formulation.md, "Rock bolts"): an elastic bolt
/// stopping the sliding block, and one yielding while it slides on. The balance of the same
/// runs without bolts is as close (a DDA block sliding: 1e-6).
TEST(BoltEnergy, ADynamicRunKeepsItsBalance) {
  const BoltedBlock c{"dda", 35.0, 20.0};
  const std::string dynamic = "kind = \"dynamic\"\ntime_step = 0.001\n";
  const BoltRun elastic = run_bolted(c, 1000, "", dynamic);
  EXPECT_LT(elastic.energy_error, 1e-4);
  EXPECT_EQ(elastic.state, BoltState::elastic);
  // Stopped from a slide, the bolt is stretched by the block's momentum beyond the static
  // limit force, friction keeping it there.
  EXPECT_GT(elastic.force, 1.2 * c.bolt_force());
  const BoltRun yielding =
      run_bolted(c, 1000, "yield_force = " + std::to_string(0.9 * c.bolt_force()) + "\n", dynamic);
  EXPECT_EQ(yielding.state, BoltState::yielding);
  EXPECT_LT(yielding.energy_error, 1e-3);
  std::printf("[bolt] dynamic: elastic %.6g N, balance %.2e; yielding %.6g N, balance %.2e\n",
              elastic.force, elastic.energy_error, yielding.force, yielding.energy_error);
}

} // namespace
} // namespace nmm
