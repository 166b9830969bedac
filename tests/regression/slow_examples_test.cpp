// SPDX-License-Identifier: MIT
// The bundled examples that take more than 3 s in Release give the right answers their
// READMEs state (issue 4); labelled slow. The fast ones are in examples_test.cpp.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <cmath>

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
  // of rock (2600 kg/m^3) M (a t)^2 / 2 = 355 kJ at t = 1 s. Measured: 356.1 kJ (+0.3%,
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

} // namespace
} // namespace nmm
