// SPDX-License-Identifier: MIT
// The bundled examples give the right answers their READMEs state (issue 4), run end to end
// by the `nmm` program as a user runs them. The slow ones are in slow_examples_test.cpp.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;

TEST_F(Example, GravityColumnSettlesByTheExactQuadratic) {
  // examples/07_gravity_column: a column of height H under its own weight between smooth
  // walls on a smooth base, plane strain. Exact: u_x = 0, u_y = -rho g (H y - y²/2) / M with
  // the constrained modulus M = E (1 - nu) / ((1 + nu) (1 - 2 nu)) = 1.2e9 Pa,
  // syy = -rho g (H - y), sxx = nu / (1 - nu) syy, sxy = 0 (README).
  const ExampleRun example = run("07_gravity_column");
  EXPECT_TRUE(example.summary.at("warnings").items.empty());
  const double rho_g = 2500.0 * 9.81;
  const double height = 10.0;
  const double young = 1.0e9;
  const double poisson = 0.25;
  const double modulus = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
  auto settlement = [&](double y) { return -rho_g * (height * y - y * y / 2.0) / modulus; };
  const double top = settlement(height); // -1.021875 mm
  // The field is quadratic and order-1 covers hold every quadratic, so what is left is the
  // rounding of the solve: measured 7e-13 (top) and 5e-13 (middle) relative. 1e-10 leaves
  // room for another BLAS or thread count and is five orders below the error of order-0
  // covers on this mesh (1.3e-5).
  EXPECT_NEAR(example.monitor("top", "uy"), top, 1e-10 * std::abs(top));
  EXPECT_NEAR(example.monitor("middle", "uy"), settlement(5.0), 1e-10 * std::abs(top));
  EXPECT_EQ(example.last("top.uy"), example.monitor("top", "uy")); // both %.17g
  for (const char* monitor : {"top", "middle", "bottom"})
    EXPECT_NEAR(example.monitor(monitor, "ux"), 0.0, 1e-10 * std::abs(top)) << monitor;
  // Stresses: the element's linear stress read at the monitor's current position. The stress
  // field moves with the element's origin and the monitor with its own point; the two moves
  // differ by the strain times their distance (2e-4 x 0.25 m at most), which the gradient
  // rho g turns into 1.2 Pa = 5e-6 rho g H. Measured at most 1.5e-6 rho g H (at the base).
  const double weight = rho_g * height; // 245.25 kPa
  const double k0 = poisson / (1.0 - poisson);
  for (const auto& [monitor, y] : {std::pair{"middle", 5.0}, std::pair{"bottom", 0.0}}) {
    EXPECT_NEAR(example.monitor(monitor, "syy"), -rho_g * (height - y), 5e-6 * weight) << monitor;
    EXPECT_NEAR(example.monitor(monitor, "sxx"), -k0 * rho_g * (height - y), 5e-6 * weight)
        << monitor;
    EXPECT_NEAR(example.monitor(monitor, "sxy"), 0.0, 5e-6 * weight) << monitor;
  }
  EXPECT_NEAR(example.monitor("top", "syy"), 0.0, 5e-6 * weight);
}

} // namespace
} // namespace nmm
