// SPDX-License-Identifier: MIT
// tests/verification/joint_strength_test.cpp — a bonded joint against limit equilibrium:
// a block on a cohesive joint holds at 1.05 c* and slides at 0.95 c*, with
// c* = W (sin a - tan phi cos a) / L, on several slopes, block sizes, cover sizes and orders
// of NMM blocks; the contacts along the joint represent its length once (issue 42, item 1).
// DDA and VEM blocks slide below c*, as they should, but also just above it (the disabled
// test below). Each block is low enough for its face to press all along (no tension at its
// upper end in the rigid statics: cos a > 3 sin a H / L), as c* assumes.
#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {
namespace {

using testing::elastic;
using testing::line;

/// A block L x H on a slope of angle alpha (a band 0.5 m thick, 6 m along the slope, its
/// base held), its bottom face a bonded joint of friction angle phi and cohesion
/// ratio x c*. Shi's static analysis (velocities reset every step) from unloaded springs,
/// so that the load comes on without the overshoot of a sudden load in a dynamic step.
struct CohesiveIncline {
  double alpha_degrees = 30.0;
  double length = 1.2;
  double height = 0.6;
  double cover_size = 0.2;
  int order = 0;
  ElementKind kind = ElementKind::nmm; ///< of the block (the ramp is NMM)
  double phi_degrees = 20.0;
  double ratio = 1.0; ///< cohesion over c*

  struct Result {
    double moved = 0.0;          ///< the block centre's displacement after the steps, m
    double late = 0.0;           ///< its displacement in the second half of the steps, m
    double friction_slide = 0.0; ///< what friction alone lets it slide in one step, m
    double joint_length = 0.0;   ///< length the contacts represent, m
    double normal = 0.0;         ///< summed normal force of the contacts, N
    double shear = 0.0;          ///< summed shear force along the slope, N
    double weight = 0.0;         ///< W, N
    long bonds_broken = 0;
  };

  [[nodiscard]] Result run(int steps) const {
    const double alpha = alpha_degrees * std::numbers::pi / 180.0;
    const Point2 along(std::cos(alpha), std::sin(alpha));
    const Point2 up(-std::sin(alpha), std::cos(alpha));
    const Point2 a = 2.0 * along;
    const Point2 down = -0.5 * up;
    const Point2 b = a + length * along;
    // The ramp's top passes through the block's lower corners exactly (at 30 degrees a point
    // computed along the slope lies off the line from the origin by rounding).
    MaterialRegion ramp{"ramp", {{{{0, 0}, down, 6.0 * along + down, 6.0 * along, b, a}, {}}}};
    MaterialRegion block{"block", {{{a, b, b + height * up, a + height * up}, {}}}};
    const double rho = 2500.0;
    const double g = 9.81;
    const double phi = phi_degrees * std::numbers::pi / 180.0;
    const double weight = rho * g * length * height;
    const double c_star = weight * (std::sin(alpha) - std::tan(phi) * std::cos(alpha)) / length;
    const ElasticMaterial rock = elastic(1e10, 0.25, rho, PlaneCondition::strain);
    testing::Setup s = testing::make_setup(
        {ramp, block}, {line("slip", a, b), line("base", down, 6.0 * along + down)}, {0}, nullptr,
        cover_size, rock, order, {ElementKind::nmm, kind});
    Scene scene;
    scene.supports = curve_support_points(s.model, 1, true, true, SupportMethod::exact, "base");
    scene.body_loads.push_back({{0.0, -g}, {}});
    const Point2 centre = a + 0.5 * length * along + 0.5 * height * up;
    scene.monitors.push_back({s.model.find_element(centre, 1e-9), centre});
    StepperOptions options;
    options.integration = TimeIntegration::static_reset;
    const double dt = 1e-3;
    options.time_step = dt;
    TimeStepper stepper(
        s.model, scene, options,
        testing::contact_for(s.model, 40.0 * rock.young, {phi, ratio * c_star, 0.0}, true));
    Point2 half = centre;
    for (int k = 0; k < steps; ++k) {
      stepper.step(1e30);
      if (k + 1 == steps / 2)
        half = stepper.scene().monitors[0].position;
    }
    Result r;
    r.moved = (stepper.scene().monitors[0].position - centre).norm();
    r.late = (stepper.scene().monitors[0].position - half).norm();
    // Static steps of dt from rest: each slides a dt^2 / 2 with friction alone.
    r.friction_slide = 0.5 * g * (std::sin(alpha) - std::tan(phi) * std::cos(alpha)) * dt * dt;
    r.weight = weight;
    const ContactSystem& contact = *stepper.contact();
    for (const ContactPoint& p : contact.points()) {
      r.joint_length += p.length;
      if (p.mode == ContactMode::open)
        continue;
      r.normal += p.normal_force;
      r.shear += p.shear_force;
    }
    r.bonds_broken = contact.counters().bonds_broken;
    return r;
  }
};

/// One geometry of the families below: slope (degrees), block length and height (m), cover
/// size (m), order and kind of the block.
struct Geometry {
  double alpha = 30.0;
  double length = 1.2;
  double height = 0.6;
  double size = 0.2;
  int order = 0;
  ElementKind kind = ElementKind::nmm;
};

/// The incline of @p g with cohesion @p ratio x c*.
CohesiveIncline incline_of(const Geometry& g, double ratio) {
  CohesiveIncline incline;
  incline.alpha_degrees = g.alpha;
  incline.length = g.length;
  incline.height = g.height;
  incline.cover_size = g.size;
  incline.order = g.order;
  incline.kind = g.kind;
  incline.ratio = ratio;
  return incline;
}

TEST(JointStrength, BlockOnACohesiveJointHoldsJustAboveTheLimitEquilibriumCohesion) {
  // Tolerances: at 1.05 c* the block holds, moving only by the elastic settling of the
  // block and its springs (measured at most 3.4e-6 m; 1e-5 m is a ninth to a quarter of what
  // friction alone would let it slide in these 100 steps), and it has settled in the second
  // half of them (measured 0 to 2.4e-11 m there on order-0 covers, 9.6e-8 m on order 1, whose
  // block is still settling; 1e-6 m is 1/45 to 1/180 of friction's slide in 50 steps: a bond
  // that broke on the way would show); the contacts along the joint
  // represent its length once, never more and, while no part of it has opened by tension at a
  // corner, all of it to 1e-6 (the detection leaves out a pair whose overlap is under 1e-6 of its
  // master edge: the sliver a settled corner moves onto the free surface, measured 4.2e-7 m of 1.2
  // m), and their summed forces are the statics of the block, W cos a and W sin a, to 0.5%.
  for (const Geometry& g : {Geometry{30.0, 1.2, 0.6, 0.2, 0}, Geometry{30.0, 1.2, 0.6, 0.1, 0},
                            Geometry{30.0, 3.0, 1.0, 0.3, 0}, Geometry{30.0, 1.2, 0.6, 0.2, 1},
                            Geometry{25.0, 2.0, 0.5, 0.25, 0}, Geometry{40.0, 1.2, 0.3, 0.2, 0}}) {
    const auto& [alpha, length, height, size, order, kind] = g;
    const CohesiveIncline incline = incline_of(g, 1.05);
    const int steps = 100;
    const CohesiveIncline::Result r = incline.run(steps);
    const double a = alpha * std::numbers::pi / 180.0;
    std::printf(
        "1.05 c*, %g deg, %g x %g m, cover %g, order %d, kind %d: moved %.3e m (friction alone "
        "%.3e; %.1e in the second half), length %.12f m, N %.1f (W cos a %.1f), S %.1f (W sin a "
        "%.1f), %ld "
        "parts broken\n",
        alpha, length, height, size, order, static_cast<int>(kind), r.moved,
        steps * r.friction_slide, r.late, r.joint_length, r.normal, r.weight * std::cos(a), r.shear,
        r.weight * std::sin(a), r.bonds_broken);
    EXPECT_LT(r.moved, 1e-5) << alpha << " deg, " << length << " m, order " << order;
    EXPECT_LT(r.late, 1e-6) << alpha << " deg, " << length << " m, order " << order;
    // Never more than the joint; all of it while no part has opened (an opened part far
    // enough apart is no longer detected).
    EXPECT_LE(r.joint_length, length * (1.0 + 1e-6));
    if (r.bonds_broken == 0) {
      EXPECT_NEAR(r.joint_length, length, 1e-6 * length);
    }
    EXPECT_NEAR(r.normal, r.weight * std::cos(a), 5e-3 * r.weight * std::cos(a));
    EXPECT_NEAR(std::abs(r.shear), r.weight * std::sin(a), 5e-3 * r.weight * std::sin(a));
  }
}

// Not yet met (issue 42): a DDA or VEM block slides at 1.05 c*. Its face is one edge, and
// the angle contact of its lower corner, where the face ends at the joint's end, keeps a
// point spring (examples/10's pivot needs it) that takes 30% of the normal force: the block
// turns on it, the upper end of the face lifts by tension, its bond breaks there and the
// rest cannot hold (measured: 0 -> 15 parts broken by step 12, the block then slides at
// friction alone). Run with --gtest_also_run_disabled_tests.
TEST(JointStrength, DISABLED_DdaAndVemBlocksOnACohesiveJointHoldJustAboveTheLimitCohesion) {
  for (const ElementKind kind : {ElementKind::dda, ElementKind::vem}) {
    const CohesiveIncline::Result r =
        incline_of(Geometry{30.0, 1.2, 0.6, 0.2, 0, kind}, 1.05).run(100);
    EXPECT_LT(r.moved, 1e-5) << "kind " << static_cast<int>(kind);
  }
}

TEST(JointStrength, BlockOnACohesiveJointSlidesJustBelowTheLimitEquilibriumCohesion) {
  // At 0.95 c* the whole joint yields, its bond breaks, and the block slides on friction
  // alone: in the second half of the steps each static step slides a dt^2 / 2, to 1% (the
  // block's elastic settling is over by then; measured equal to 6 digits).
  for (const Geometry& g :
       {Geometry{30.0, 1.2, 0.6, 0.2, 0}, Geometry{30.0, 3.0, 1.0, 0.3, 0},
        Geometry{30.0, 1.2, 0.6, 0.2, 1}, Geometry{25.0, 2.0, 0.5, 0.25, 0},
        Geometry{40.0, 1.2, 0.3, 0.2, 0}, Geometry{30.0, 1.2, 0.6, 0.2, 0, ElementKind::dda},
        Geometry{30.0, 1.2, 0.6, 0.2, 0, ElementKind::vem}}) {
    const auto& [alpha, length, height, size, order, kind] = g;
    const CohesiveIncline incline = incline_of(g, 0.95);
    const int steps = 60;
    const CohesiveIncline::Result r = incline.run(steps);
    const double expected = (steps - steps / 2) * r.friction_slide;
    std::printf(
        "0.95 c*, %g deg, %g x %g m, cover %g, order %d, kind %d: moved %.4e m, in the second "
        "half %.5e m, friction alone %.5e m, parts broken %ld\n",
        alpha, length, height, size, order, static_cast<int>(kind), r.moved, r.late, expected,
        r.bonds_broken);
    EXPECT_GT(r.bonds_broken, 0);
    EXPECT_NEAR(r.late, expected, 0.01 * expected)
        << alpha << " deg, " << length << " m, order " << order;
  }
}

} // namespace
} // namespace nmm
