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
  EXPECT_EQ(example.last_row.at("contacts"), 0.0);
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

} // namespace
} // namespace nmm
