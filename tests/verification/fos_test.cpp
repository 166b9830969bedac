// SPDX-License-Identifier: MIT
// tests/verification/fos_test.cpp — the factor of safety by strength reduction (`nmm fos`,
// issue 46, item 7) against limit equilibrium: a block of weight W on a plane of angle
// alpha, its base a joint of friction angle phi and cohesion c over its length L, stands
// while tan(phi) / F and c / F hold it, so F = (c L + W cos(alpha) tan(phi)) / (W sin(alpha))
// (tan(phi) / tan(alpha) without cohesion). DDA, VEM and NMM blocks, several slopes,
// friction angles, block and cover sizes, with and without cohesion, factors above and below
// 1; each within 1%. The search stops when its bracket is at most 1% wide
// ([fos] tolerance = 0.01); its middle is then within 0.5% of every factor in it, and the
// model adds its own error (penalty springs, an elastic block whose base does not press
// evenly) of a few tenths of a percent: measured at most 0.32% here. (NMM bodies, order 0,
// take a shorter [fos] time_step, and one with cohesion is not yet among them: below.)
#include "io/case_file.hpp"
#include "io/fos.hpp"
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

/// One block on a plane.
struct PlaneCase {
  const char* model;        ///< of the block and the ramp: "dda", "nmm" or "vem"
  double alpha_degrees;     ///< the plane's angle
  double phi_degrees;       ///< the joint's friction angle
  double cohesion = 0.0;    ///< Pa
  double length = 1.0;      ///< of the block along the plane, m
  double height = 0.5;      ///< across it, m
  double cover_size = 0.25; ///< m (nmm only)

  /// Limit equilibrium: (c L + W cos a tan phi) / (W sin a), W = density g L H.
  [[nodiscard]] double expected() const {
    const double a = alpha_degrees * degrees;
    const double weight = density * gravity * length * height;
    return (cohesion * length + weight * std::cos(a) * std::tan(phi_degrees * degrees)) /
           (weight * std::sin(a));
  }
};

std::ostream& operator<<(std::ostream& out, const PlaneCase& c) {
  return out << c.model << " alpha " << c.alpha_degrees << " phi " << c.phi_degrees << " c "
             << c.cohesion << " L " << c.length << " H " << c.height;
}

/// A ramp 6 m long and 0.5 m thick along the angle alpha, its underside "base" held, and a
/// block L x H on it 2.5 m up; the block's underside is the joint "slip" (as
/// examples/03_block_on_incline/incline.geo, for any angle).
std::string plane_geo(const PlaneCase& c) {
  const double a = c.alpha_degrees * degrees;
  const Eigen::Vector2d along(std::cos(a), std::sin(a));
  const Eigen::Vector2d up(-std::sin(a), std::cos(a));
  const Eigen::Vector2d points[] = {Eigen::Vector2d::Zero(),
                                    -0.5 * up,
                                    6.0 * along - 0.5 * up,
                                    6.0 * along,
                                    2.5 * along,
                                    (2.5 + c.length) * along,
                                    (2.5 + c.length) * along + c.height * up,
                                    2.5 * along + c.height * up};
  std::ostringstream geo;
  geo.precision(17);
  for (int k = 0; k < 8; ++k)
    geo << "Point(" << k + 1 << ") = {" << points[k].x() << ", " << points[k].y() << ", 0};\n";
  geo << "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 6};\n"
      << "Line(5) = {6, 5};\nLine(6) = {5, 1};\nLine(7) = {6, 7};\nLine(8) = {7, 8};\n"
      << "Line(9) = {8, 5};\nCurve Loop(1) = {1, 2, 3, 4, 5, 6};\nPlane Surface(1) = {1};\n"
      << "Curve Loop(2) = {-5, 7, 8, 9};\nPlane Surface(2) = {2};\n"
      << "Physical Surface(\"ramp\") = {1};\nPhysical Surface(\"block\") = {2};\n"
      << "Physical Curve(\"slip\") = {5};\nPhysical Curve(\"base\") = {2};\n";
  return geo.str();
}

/// The case: the joint's phi and c, [contact] (the ramp's free surface the block slides
/// onto) with the same friction, gravity, Shi's static steps from the initial equilibrium.
std::string plane_case(const PlaneCase& c) {
  std::ostringstream text;
  text.precision(17);
  text << "geometry = \"plane.geo\"\n[cover_mesh]\nsize = " << c.cover_size << "\n";
  for (const char* material : {"ramp", "block"})
    text << "[materials." << material << "]\nmodel = \"" << c.model << "\"\ndensity = " << density
         << "\nyoung = 1.0e9\npoisson = 0.25\n";
  text << "[joints.slip]\nfriction_angle = " << c.phi_degrees << "\ncohesion = " << c.cohesion
       << "\n[contact]\nfriction_angle = " << c.phi_degrees << "\n"
       << "[[boundary]]\ncurve = \"base\"\nfix = \"xy\"\n"
       << "[[load]]\ngravity = [0.0, " << -gravity << "]\n"
       << "[analysis]\nkind = \"static\"\nsteps = 1\ninitial_equilibrium = true\n"
       << "[fos]\nsteps = 100\n";
  // NMM bodies take static steps of 0.01 s (below): with the automatic step they creep.
  if (std::string(c.model) == "nmm")
    text << "time_step = 0.01\n";
  return text.str();
}

FosResult factor_of_safety(const PlaneCase& c) {
  const TempDir dir("nmm_fos");
  write_text(dir.path() / "plane.geo", plane_geo(c));
  write_text(dir.path() / "case.toml", plane_case(c));
  return find_factor_of_safety(read_case_file(dir.path() / "case.toml"));
}

/// The trials of @p result, one a line, for the message of a failed expectation.
std::string trials_text(const FosResult& result) {
  std::ostringstream text;
  for (const FosTrial& t : result.trials)
    text << "\n  F = " << t.factor << (t.failed ? " fails" : " stands") << ": first "
         << t.first_displacement << " m, last " << t.last_displacement << " m, measure "
         << t.measure << ", lock excess " << t.lock_excess << (t.error.empty() ? "" : " (")
         << t.error << (t.error.empty() ? "" : ")");
  return text.str();
}

class BlockOnAPlane : public ::testing::TestWithParam<PlaneCase> {};

TEST_P(BlockOnAPlane, FactorOfSafetyIsLimitEquilibriumsToOnePercent) {
  const PlaneCase& c = GetParam();
  const FosResult result = factor_of_safety(c);
  const double expected = c.expected();
  ASSERT_EQ(result.status, FosStatus::found) << c;
  EXPECT_NEAR(result.factor_of_safety, expected, 0.01 * expected)
      << c << ": bracket " << result.stable << " to " << result.failing << " in "
      << result.trials.size() << " trials:" << trials_text(result);
  // Both sides: it stood below the closed form and failed above it (within the 1%).
  EXPECT_LE(result.stable, expected * 1.01) << c;
  EXPECT_GE(result.failing, expected * 0.99) << c;
  EXPECT_LE(result.failing - result.stable, 0.01 * result.stable + 1e-12) << c;
  // The block is what fails, the ramp (held along its base) is not.
  EXPECT_EQ(result.failing_blocks.size(), 1u) << c;
  // A block sliding on a plane is a mechanism the criterion tells from rest.
  EXPECT_TRUE(result.warnings.empty()) << c << ": " << result.warnings.front();
  std::printf("[fos] %s alpha %g phi %g c %g: F = %.5g (limit equilibrium %.5g, %+.2f%%), "
              "%zu trials\n",
              c.model, c.alpha_degrees, c.phi_degrees, c.cohesion, result.factor_of_safety,
              expected, 100.0 * (result.factor_of_safety / expected - 1.0), result.trials.size());
}

INSTANTIATE_TEST_SUITE_P(
    DdaBlocks,
    BlockOnAPlane,
    ::testing::Values(PlaneCase{"dda", 20.0, 30.0},                     // 1.5863
                      PlaneCase{"dda", 30.0, 40.0, 0.0, 0.6, 0.4},      // 1.4534
                      PlaneCase{"dda", 35.0, 20.0},                     // 0.5198: fails unreduced
                      PlaneCase{"dda", 30.0, 25.0, 4000.0},             // with cohesion: 1.4601
                      PlaneCase{"dda", 40.0, 15.0, 1000.0, 1.2, 0.4})); // 0.4779

// VEM blocks (elastic, vertex covers): the same limit.
INSTANTIATE_TEST_SUITE_P(VemBlocks,
                         BlockOnAPlane,
                         ::testing::Values(PlaneCase{"vem", 20.0, 25.0}, // 1.2812
                                           PlaneCase{"vem", 35.0, 30.0, 2000.0, 0.8,
                                                     0.4})); // with cohesion: 1.1800

// NMM bodies (order 0, several covers a block): the same limit, with [fos] time_step = 0.01 s.
// With Shi's automatic static step (0.05 s and more here) an NMM block on an NMM ramp keeps
// creeping at strengths it stands at, about 1e-7 m a step (last over first tenth 0.44 at
// F = 1.125, alpha 25, phi 30, limit 1.238), and the search ends 10% low without a warning;
// with 2 ms or 10 ms it meets the limit (docs/case-file.md, [fos] time_step). Not among them:
// an NMM block on a cohesive joint (alpha 30, phi 25, c = 3000 Pa, 0.8 m x 0.4 m, covers of
// 0.2 m; limit 1.419) creeps at 1.9e-7 m a step at F = 1.25, where it stands, with 2 ms as
// with 10 ms, and the search ends 12% low: a finding of issue 42, not hidden here.
INSTANTIATE_TEST_SUITE_P(NmmBlocks,
                         BlockOnAPlane,
                         ::testing::Values(PlaneCase{"nmm", 25.0, 30.0}, // 1.2381
                                           PlaneCase{"nmm", 20.0, 15.0, 0.0, 1.0, 0.5,
                                                     0.5})); // 0.7362

} // namespace
} // namespace nmm
