// SPDX-License-Identifier: MIT
// The bundled examples that take more than 3 s in Release give the right answers their
// READMEs state (issue 4); labelled slow. The fast ones are in examples_test.cpp.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <vector>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;

TEST_F(Example, PlateWithCrackOpensNearTheGriffithProfile) {
  // examples/06_plate_with_crack: a partial joint of length 2a = 0.2 m in a plate 20a wide,
  // pulled across it by s = 1 MPa, plane strain. Griffith (Westergaard):
  // COD(x) = 4 (1 - nu²) s / E sqrt(a² - x²): 37.5 um at the centre, 32.48 um at a/2.
  const ExampleRun example = run("06_plate_with_crack");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  // The crack opens over its whole length: no contact is left closed on its faces.
  EXPECT_EQ(example.last("contacts"), 0.0);
  const double a = 0.1;
  const double poisson = 0.25;
  auto griffith = [&](double x) {
    return 4.0 * (1.0 - poisson * poisson) * 1.0e6 / 1.0e10 * std::sqrt(a * a - x * x);
  };
  const double centre = example.monitor("upper", "uy") - example.monitor("lower", "uy");
  const double half = example.monitor("upper_half", "uy") - example.monitor("lower_half", "uy");
  // The triangle holding the crack tip is not split (Shi's Figure 4.2), so the crack opens
  // only up to the last math edge it crosses and opens less than Griffith's: -5.0% at the
  // centre at h = a/10 in an infinite plate (tests/verification/plate_test.cpp measures
  // -4.4% with exact tractions on its boundary); the finite plate opens it 0.8% more
  // (README). Measured -4.17% at the centre and -6.08% at a/2; the bounds leave 0.4%.
  const double centre_error = centre / griffith(0.0) - 1.0;
  const double half_error = half / griffith(a / 2.0) - 1.0;
  EXPECT_LT(centre_error, 0.0);
  EXPECT_GT(centre_error, -0.045);
  EXPECT_LT(half_error, 0.0);
  EXPECT_GT(half_error, -0.065);
}

TEST_F(Example, PlateWithHoleConcentratesTheTensionThreeTimes) {
  // examples/05_plate_with_hole: Kirsch's hole of radius a in a plate under tension s, a
  // quarter of a plate 20a wide with symmetry rollers, order-1 covers of size a/10. Kirsch
  // (infinite plate): sxx = 3 s at the hole's top, syy = -s at its side, sxx = 1.21875 s one
  // radius above the hole. The finite width raises all three: the peak reads 3.375 s, 3.099 s
  // and 3.035 s for plates 5a, 10a and 20a wide (README), so this plate's own answer is about
  // 1% above Kirsch's. Bounds: the peak 0 to 1.5% above 3 s, the others within 1.5% of s.
  const ExampleRun example = run("05_plate_with_hole");
  const double s = 1.0e7;
  const double peak = example.monitor("top", "sxx") / s;
  EXPECT_GT(peak, 3.0);
  EXPECT_LT(peak, 3.0 * 1.015);
  EXPECT_NEAR(example.monitor("side", "syy") / s, -1.0, 0.015);
  EXPECT_NEAR(example.monitor("above", "sxx") / s, 1.21875, 0.015);
}

TEST_F(Example, MultiBlockSlopeSlidesAsOneBodyWithTheFrictionOfTheBedding) {
  // examples/08_multi_block_slope: five blocks on a bedding joint dipping 30 degrees with a
  // friction angle of 20 degrees slide as one rigid body would: a = g (sin 30 - tan 20
  // cos 30) = 1.813 m/s^2, s = a t^2 / 2 = 0.906 m and the kinetic energy of the 83.14 m^2
  // of rock (2600 kg/m^3) M (a t)^2 / 2 = 355 kJ at t = 1 s. Measured: 360.8 kJ (+1.6%,
  // with the base's elastic vibration) and the five blocks 0.891 to 0.942 m (-1.7% to
  // +3.9%: the cross joints open a little as the mass goes, README). Bounds: 2% on the
  // energy, 5% on each block.
  const ExampleRun example = run("08_multi_block_slope");
  const double pi = 3.14159265358979323846;
  const double a = 9.81 * (std::sin(pi / 6.0) - std::tan(pi / 9.0) * std::cos(pi / 6.0));
  const double t = example.last("time");
  EXPECT_NEAR(t, 1.0, 1e-9);
  const double exact = 0.5 * a * t * t;
  const double energy = 0.5 * 2600.0 * 83.1384 * (a * t) * (a * t);
  EXPECT_NEAR(example.last("kinetic_energy"), energy, 0.02 * energy);
  for (const char* block : {"toe_block", "block_2", "block_3", "block_4", "top_block"}) {
    const double slid = example.monitor(block, "ux") * std::cos(pi / 6.0) -
                        example.monitor(block, "uy") * std::sin(pi / 6.0);
    EXPECT_NEAR(slid, exact, 0.05 * exact) << block;
  }
}

// examples/15_circular_sliding: the sliding mass of slope.geo (the polygon between the slip
// circle's polyline and the slope's surface) and what a rigid body on a circular arc does
// (README, limit_equilibrium.py). Per unit density and thickness.
struct SlidingMass {
  double xo = 20.0, yo = 30.0; // the circle's centre O
  double radius = 0.0;
  double a0 = 0.0, a1 = 0.0; // the arc's angles about O, from C on the top to the toe
  double area = 0.0;
  double gx = 0.0, gy = 0.0; // the centroid G relative to O
  double polar = 0.0;        // polar second moment about O (m^4)

  SlidingMass() {
    const double pi = 3.14159265358979323846;
    const double xt = 22.0, yt = 5.0; // the toe
    const int chords = 101;
    radius = std::hypot(xt - xo, yt - yo);
    const double xc = xo - std::sqrt(radius * radius - (15.0 - yo) * (15.0 - yo));
    a0 = std::atan2(15.0 - yo, xc - xo) + 2.0 * pi;
    a1 = std::atan2(yt - yo, xt - xo) + 2.0 * pi;
    std::vector<std::array<double, 2>> polygon; // about O, counter-clockwise
    for (int k = 0; k <= chords; ++k) {
      const double a = a0 + (a1 - a0) * k / chords;
      polygon.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
    polygon.push_back({14.0 - xo, 15.0 - yo}); // the crest
    double ixx = 0.0, iyy = 0.0;
    for (std::size_t k = 0; k < polygon.size(); ++k) {
      const auto [x0, y0] = polygon[k];
      const auto [x1, y1] = polygon[(k + 1) % polygon.size()];
      const double cross = x0 * y1 - x1 * y0;
      area += cross / 2.0;
      gx += (x0 + x1) * cross;
      gy += (y0 + y1) * cross;
      ixx += (y0 * y0 + y0 * y1 + y1 * y1) * cross;
      iyy += (x0 * x0 + x0 * x1 + x1 * x1) * cross;
    }
    gx /= 6.0 * area;
    gy /= 6.0 * area;
    polar = (ixx + iyy) / 12.0;
  }
  /// The weight's lever about O: it turns the mass counter-clockwise, towards the valley.
  [[nodiscard]] double lever() const { return -gx; }

  /// The angle the mass has turned about O when its centroid has moved by (ux, uy).
  [[nodiscard]] double turned(double ux, double uy) const {
    return std::atan2(gy + uy, gx + ux) - std::atan2(gy, gx);
  }

  /// Without friction every contact force passes through O: a pendulum about O from rest,
  /// J_O theta'' = -g A (x_G(theta) - x_O), by RK4; theta at @p time.
  [[nodiscard]] double pendulum(double time) const {
    const double k = 9.81 * area / polar;
    const double r = std::hypot(gx, gy);
    const double psi = std::atan2(gy, gx);
    auto acceleration = [&](double theta) { return -k * r * std::cos(psi + theta); };
    double theta = 0.0, omega = 0.0;
    const int steps = 10000;
    const double h = time / steps;
    for (int i = 0; i < steps; ++i) {
      const double k1 = acceleration(theta);
      const double k2 = acceleration(theta + h / 2.0 * omega);
      const double k3 = acceleration(theta + h / 2.0 * (omega + h / 2.0 * k1));
      const double k4 = acceleration(theta + h * (omega + h / 2.0 * k2));
      theta += h * (omega + h / 6.0 * (k1 + k2 + k3));
      omega += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return theta;
  }

  /// Bounds on the angular acceleration with which the mass starts to turn from rest with
  /// friction angle @p phi (radians): J_O alpha = W d - K R sin(phi) |F|, F = M a_G + W the
  /// arc's reaction, K between 1 and K_max (all the normal force at the arc's two ends).
  [[nodiscard]] std::array<double, 2> onset(double phi) const {
    const double pi = 3.14159265358979323846;
    const double beta = (a1 - a0) / 2.0;
    const double bisector = (a0 + a1) / 2.0 + pi;
    const double weight = 9.81 * area;
    auto reaction = [&](double alpha) {
      return std::array<double, 2>{-area * alpha * gy, weight + area * alpha * gx};
    };
    auto k_max = [&](double alpha) {
      const auto [fx, fy] = reaction(alpha);
      const double gamma = std::remainder(std::atan2(fy, fx) - phi - bisector, 2.0 * pi);
      return std::abs(gamma) <= beta ? std::cos(gamma) / std::cos(beta) : 1e30;
    };
    auto solve = [&](auto k) {
      double low = 0.0, high = weight * lever() / polar;
      for (int i = 0; i < 80; ++i) {
        const double mid = (low + high) / 2.0;
        const auto [fx, fy] = reaction(mid);
        const double excess =
            weight * lever() - k(mid) * radius * std::sin(phi) * std::hypot(fx, fy) - polar * mid;
        (excess > 0.0 ? low : high) = mid;
      }
      return low;
    };
    return {solve(k_max), solve([](double) { return 1.0; })};
  }
};

TEST_F(Example, CircularSlidingWithoutFrictionTurnsAboutTheCentreAsAPendulum) {
  // examples/15_circular_sliding/case_frictionless.toml: from rest at g A d / J_O =
  // 0.1749 rad/s^2, theta(1 s) = 0.08459 rad (2.12 m along the arc).
  const ExampleRun example = run_case(std::filesystem::path(NMM_EXAMPLES_DIR) /
                                          "15_circular_sliding" / "case_frictionless.toml",
                                      "15_frictionless");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  const SlidingMass mass;
  const double t = example.last("time");
  EXPECT_NEAR(t, 1.0, 1e-9);
  const double ux = example.monitor("mass", "ux");
  const double uy = example.monitor("mass", "uy");
  const double exact = mass.pendulum(t);
  // The slip surface is a polyline of 0.25 m chords: a mass turning on it has its corners
  // ride over the ground's chords (bumps of R delta^2 / 8 = 0.3 mm), which holds it back:
  // measured -0.35% at 1 s, -0.17% with chords half as long. 1% leaves room for that and
  // is a fifth of what a friction angle of 1 degree takes off its start (4.6% to 5.3%).
  EXPECT_NEAR(mass.turned(ux, uy), exact, 0.01 * exact);
  // It turns about O: its centroid stays on its circle of 21.36 m (measured 0.16 mm off at
  // 1 s, 0.52 mm at most, while it moves 1.8 m).
  EXPECT_NEAR(std::hypot(mass.gx + ux, mass.gy + uy), std::hypot(mass.gx, mass.gy), 1e-3);
}

TEST_F(Example, CircularSlidingSlidesBelowAndStandsAboveTheRigidMassLimits) {
  // examples/15_circular_sliding: whatever the normal stress along the arc, a rigid mass
  // turns when sin(phi) < d / (K_max R) (17.75 degrees) and cannot when sin(phi) >= d / R
  // (20.25 degrees). case.toml has 17 degrees, case_stands.toml 21 (README).
  const double pi = 3.14159265358979323846;
  const SlidingMass mass;
  EXPECT_GT(std::sin(21.0 * pi / 180.0), mass.lever() / mass.radius);
  const std::array<double, 2> rate = mass.onset(17.0 * pi / 180.0);
  EXPECT_GT(rate[0], 0.0); // no normal stress distribution holds it
  {
    const ExampleRun example = run("15_circular_sliding");
    EXPECT_TRUE(example.summary.at("warnings").items.empty());
    const double t = example.last("time");
    EXPECT_NEAR(t, 1.0, 1e-9);
    const double theta = mass.turned(example.monitor("mass", "ux"), example.monitor("mass", "uy"));
    // Its mean angular acceleration lies between the onset rates for K = K_max and K = 1:
    // measured 2 theta / t^2 = 0.0242 in [0.0084, 0.0309] rad/s^2. The bounds are for the
    // start; by 1 s the mass has turned 0.012 rad, which shortens its weight's lever by 2%
    // (0.004 rad/s^2 off the rate at the end, less on average), and spins at 0.02 rad/s (a
    // centripetal force of 1e-3 of its weight): the measured rate stays 0.0067 inside both.
    EXPECT_GT(2.0 * theta / (t * t), rate[0]);
    EXPECT_LT(2.0 * theta / (t * t), rate[1]);
  }
  {
    const ExampleRun example = run_case(std::filesystem::path(NMM_EXAMPLES_DIR) /
                                            "15_circular_sliding" / "case_stands.toml",
                                        "15_stands");
    EXPECT_TRUE(example.summary.at("warnings").items.empty());
    // Measured: it turns 9e-6 rad in 1 s (0.2 mm along the arc, the springs of the joint
    // taking up the load) against 0.010 rad at 17 degrees; 1e-4 rad is a hundredth of that.
    EXPECT_LT(std::abs(mass.turned(example.monitor("mass", "ux"), example.monitor("mass", "uy"))),
              1e-4);
  }
}

} // namespace
} // namespace nmm
