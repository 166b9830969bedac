// SPDX-License-Identifier: MIT
// Order-1 covers in contact scenes (issue 42, item 5): wherever order 0 meets its closed
// form, order 1 must too. A block on a 45 degree ramp slides Newton's distance and sticks
// above its friction angle; a tall block on a ramp topples exactly when its centroid lies
// beyond its downhill corner, b / h < tan(alpha), with order-0 and order-1 covers.
// The command-line side (the gmsh math mesh of examples/03 at order 1) is in cli tests.

#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {
namespace {

using testing::Incline;

TEST(OrderOneIncline, BlockSlidesTheExactDistanceForEveryFrictionAngle) {
  // s = g t² (sin a - tan phi cos a) / 2 at t = 1 s, the 0.1% of the order-0 family
  // (contact_test.cpp): the slide is a rigid motion that order-1 covers contain as order-0
  // covers do, so their extra freedom must not cost accuracy. Before the held points of the
  // ramp's base stayed where their supports hold them (hold_supported_points), the ramp
  // jacked the block off within 100 steps.
  for (const double phi : {15.0, 30.0, 40.0}) {
    Incline incline;
    incline.phi_degrees = phi;
    incline.dt = 1e-2;
    incline.order = 1;
    const Incline::Result r = incline.run();
    const double error = std::abs(r.distance - r.exact) / r.exact;
    std::printf("order-1 incline phi %4.1f dt 1e-2: slid %.6f m, exact %.6f m, error %.4f%%, "
                "max penetration %.2e m, %ld cuts\n",
                phi, r.distance, r.exact, 100.0 * error, r.max_penetration, r.cuts);
    EXPECT_LT(error, 1e-3) << "phi " << phi;
    EXPECT_LT(r.max_penetration, 1e-6) << "phi " << phi;
  }
}

TEST(OrderOneIncline, BlockWhoseFrictionAngleExceedsTheSlopeStaysPut) {
  // phi = 50 > 45 degrees: the order-0 bound of contact_test.cpp, 1e-5 m in 1 s.
  Incline incline;
  incline.phi_degrees = 50.0;
  incline.dt = 1e-2;
  incline.order = 1;
  const Incline::Result r = incline.run();
  std::printf("order-1 stick: moved %.3e m, max penetration %.2e m, %ld cuts\n", r.largest_motion,
              r.max_penetration, r.cuts);
  EXPECT_LT(r.largest_motion, 1e-5);
}

/// A b x h block standing on a ramp of angle alpha with friction enough to hold it from
/// sliding (phi = 45 > alpha): it topples when b / h < tan(alpha), its centroid then beyond
/// the downhill corner.
struct Topple {
  double alpha_degrees = 20.0;
  double width = 0.3;
  double height = 1.0;
  int order = 0;

  /// The block's rotation after @p duration s, rad (positive: downhill).
  [[nodiscard]] double rotation(double duration) const {
    const double alpha = alpha_degrees * std::numbers::pi / 180.0;
    const Point2 along(std::cos(alpha), std::sin(alpha)); // up the ramp
    const Point2 up(-std::sin(alpha), std::cos(alpha));
    const Point2 a = 2.0 * along; // the block's downhill corner
    const Point2 b = a + width * along;
    MaterialRegion block{"block", {{{a, b, b + height * up, a + height * up}, {}}}};
    const Point2 down = -0.5 * up;
    const Point2 end = 5.0 * along;
    MaterialRegion ramp{"ramp", {{{{0, 0}, down, end + down, end}, {}}}};
    const ElasticMaterial rock = testing::elastic(1e10, 0.25, 2500.0, PlaneCondition::strain);
    testing::Setup s = testing::make_setup(
        {ramp, block}, {testing::line("seat", a, b), testing::line("base", down, end + down)}, {0},
        nullptr, 0.1, rock, order);
    Scene scene;
    scene.supports = curve_support_points(s.model, 1, true, true, SupportMethod::exact, "base");
    scene.body_loads.push_back({{0.0, -9.81}, {}});
    // Two points of the block on its axis: their line turns with the block.
    const Point2 low = a + 0.5 * width * along + 0.1 * height * up;
    const Point2 high = a + 0.5 * width * along + 0.9 * height * up;
    scene.monitors.push_back({s.model.find_element(low, 1e-9), low});
    scene.monitors.push_back({s.model.find_element(high, 1e-9), high});
    StepperOptions options;
    options.time_step = 2e-3;
    TimeStepper stepper(
        s.model, scene, options,
        testing::contact_for(s.model, 40.0 * 1e10, {std::numbers::pi / 4, 0.0, 0.0}));
    const Point2 axis0 =
        stepper.scene().monitors[1].position - stepper.scene().monitors[0].position;
    while (stepper.time() < duration - 1e-9)
      stepper.step(duration);
    const Point2 axis = stepper.scene().monitors[1].position - stepper.scene().monitors[0].position;
    // Downhill is anticlockwise for a ramp rising to the right.
    return std::atan2(axis0.x() * axis.y() - axis0.y() * axis.x(), axis0.dot(axis));
  }

  /// The rigid block's rotation about its downhill corner after @p duration s from rest:
  /// I theta'' = m g r sin(delta0 + theta), I = m (b² + h²) / 3 about the corner, r the
  /// corner's distance to the centroid, delta0 the centroid's angle beyond the vertical
  /// through the corner (RK4 in steps of 1e-5 s, converged to 1e-9 rad).
  [[nodiscard]] double rigid_rotation(double duration) const {
    const double alpha = alpha_degrees * std::numbers::pi / 180.0;
    const double x = 0.5 * width * std::cos(alpha) - 0.5 * height * std::sin(alpha);
    const double y = 0.5 * width * std::sin(alpha) + 0.5 * height * std::cos(alpha);
    const double delta0 = std::atan2(-x, y);
    const double r = 0.5 * std::hypot(width, height);
    const double inertia = (width * width + height * height) / 3.0; // per unit mass
    auto acceleration = [&](double theta) { return 9.81 * r * std::sin(delta0 + theta) / inertia; };
    double theta = 0.0;
    double omega = 0.0;
    const double h = 1e-5;
    for (int i = 0; i < static_cast<int>(std::lround(duration / h)); ++i) {
      const double k1 = omega, l1 = acceleration(theta);
      const double k2 = omega + 0.5 * h * l1, l2 = acceleration(theta + 0.5 * h * k1);
      const double k3 = omega + 0.5 * h * l2, l3 = acceleration(theta + 0.5 * h * k2);
      const double k4 = omega + h * l3, l4 = acceleration(theta + h * k3);
      theta += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
      omega += h / 6.0 * (l1 + 2.0 * l2 + 2.0 * l3 + l4);
    }
    return theta;
  }
};

TEST(Topple, TallBlockTopplesExactlyWhenItsCentroidIsBeyondItsCorner) {
  // Both sides of b / h = tan(alpha), at 0.85 and 1.15 of it, on two ramp angles, with
  // order-0 and order-1 covers. Toppling, the block turns as the rigid block about its
  // corner does, to 8%: toppling from rest grows as cosh(t / tau), tau = sqrt(I / (m g r))
  // about 0.27 s here, so the 1e-3 rad or so by which the block tilts as it settles into
  // its seat's springs in the first steps (it starts on unloaded springs: an initial
  // equilibrium has no solution for a block that must topple) grows about twentyfold by
  // 0.8 s, 0.02 of some 0.5 rad. Standing, it turns only by that settlement, below 1e-3 rad.
  for (const int order : {0, 1}) {
    for (const double alpha : {20.0, 30.0}) {
      for (const double ratio : {0.85, 1.15}) {
        Topple t;
        t.alpha_degrees = alpha;
        t.order = order;
        t.width = ratio * std::tan(alpha * std::numbers::pi / 180.0) * t.height;
        const double turned = t.rotation(0.8);
        std::printf("order %d alpha %.0f b/h = %.2f tan(alpha): turned %.4g rad in 0.8 s\n", order,
                    alpha, ratio, turned);
        if (ratio < 1.0) {
          const double rigid = t.rigid_rotation(0.8);
          std::printf("  the rigid block about its corner: %.4g rad\n", rigid);
          EXPECT_NEAR(turned, rigid, 0.08 * rigid) << "order " << order << " alpha " << alpha;
        } else {
          EXPECT_LT(std::abs(turned), 1e-3) << "order " << order << " alpha " << alpha;
        }
      }
    }
  }
}

} // namespace
} // namespace nmm
