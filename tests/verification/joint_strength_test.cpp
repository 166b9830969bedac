// SPDX-License-Identifier: MIT
// tests/verification/joint_strength_test.cpp — a bonded joint against limit equilibrium:
// a block on a cohesive joint holds at 1.05 c* and slides at 0.95 c*, with
// c* = W (sin a - tan phi cos a) / L, on several slopes, block sizes, cover sizes and orders
// of NMM, DDA and VEM blocks; the contacts along the joint represent its length once; and a
// block hanging under a ceiling by a joint's tensile strength T holds at W / L = 0.95 T and
// falls at 1.05 T (issue 42, item 1). Each block on a slope is low enough for its face to
// press all along (no tension at its upper end in the rigid statics: cos a > 3 sin a H / L),
// as c* assumes. All in Shi's static analysis but the last family: a dynamic start, whose
// sudden load overshoots 2x, holds at twice c* (docs/formulation.md, "Joint strength").
#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <tuple>
#include <utility>

namespace nmm {
namespace {

using testing::elastic;
using testing::line;

/// Runs @p steps steps of @p stepper; the displacement of its first monitor from @p centre
/// after them, and in their second half, m. @p energy_error: the largest of the steps'.
std::pair<double, double>
motion(TimeStepper& stepper, const Point2& centre, int steps, double* energy_error = nullptr) {
  Point2 half = centre;
  for (int k = 0; k < steps; ++k) {
    const StepReport report = stepper.step(1e30);
    if (energy_error != nullptr)
      *energy_error = std::max(*energy_error, report.energy_error);
    if (k + 1 == steps / 2)
      half = stepper.scene().monitors[0].position;
  }
  const Point2 end = stepper.scene().monitors[0].position;
  return {(end - centre).norm(), (end - half).norm()};
}

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
  /// Shi's static analysis, or a dynamic one (the load applied at once, velocities kept).
  TimeIntegration integration = TimeIntegration::static_reset;

  struct Result {
    double moved = 0.0;          ///< the block centre's displacement after the steps, m
    double late = 0.0;           ///< its displacement in the second half of the steps, m
    double friction_slide = 0.0; ///< what friction alone lets it slide in one step, m
    double joint_length = 0.0;   ///< length the contacts represent, m
    double normal = 0.0;         ///< summed normal force of the contacts, N
    double shear = 0.0;          ///< summed shear force along the slope, N
    double weight = 0.0;         ///< W, N
    long bonds_broken = 0;
    double energy_error = 0.0; ///< the largest of the steps' (StepReport::energy_error)
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
    options.integration = integration;
    const double dt = 1e-3;
    options.time_step = dt;
    TimeStepper stepper(
        s.model, scene, options,
        testing::contact_for(s.model, 40.0 * rock.young, {phi, ratio * c_star, 0.0}, true));
    Result r;
    std::tie(r.moved, r.late) = motion(stepper, centre, steps, &r.energy_error);
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
  // block and its springs (measured at most 3.3e-6 m; 1e-5 m is a ninth to a quarter of what
  // friction alone would let it slide in these 100 steps), and it has settled in the second
  // half of them (measured 0 to 1.3e-15 m there, 1.9e-11 m on order 1 and 1.5e-7 m on the
  // order-0 NMM block at 40 degrees, whose upper end has yielded open; 1e-6 m is 1/45 to 1/180
  // of friction's slide in 50 steps: a bond that broke on the way would show); the contacts
  // along the joint represent its length once, never more and, while no part of it has
  // broken, all of it to 1e-6 (the detection leaves out a pair whose overlap is under 1e-6 of
  // its master edge: the sliver a settled corner moves onto the free surface, measured 1.0e-6
  // m of 3 m), and their summed forces are the statics of the block, W cos a and W sin a, to
  // 0.5% (measured 0 to 0.08%: the 40 degree NMM block's creep).
  // DDA and VEM blocks (one edge for the face, against the ramp's pieces) on the same slopes:
  // the corner that ends the bonded face has no spring of its own (the face's pair represents
  // the joint up to it); with one, it took 30% of the normal force on no length, dented the
  // ramp so that the parts next to it lifted off and broke, and the block slid at 1.05 c*.
  constexpr ElementKind dda = ElementKind::dda;
  constexpr ElementKind vem = ElementKind::vem;
  for (const Geometry& g :
       {Geometry{30.0, 1.2, 0.6, 0.2, 0}, Geometry{30.0, 1.2, 0.6, 0.1, 0},
        Geometry{30.0, 3.0, 1.0, 0.3, 0}, Geometry{30.0, 1.2, 0.6, 0.2, 1},
        Geometry{25.0, 2.0, 0.5, 0.25, 0}, Geometry{40.0, 1.2, 0.3, 0.2, 0},
        Geometry{30.0, 1.2, 0.6, 0.2, 0, dda}, Geometry{30.0, 1.2, 0.6, 0.2, 0, vem},
        Geometry{30.0, 3.0, 1.0, 0.3, 0, dda}, Geometry{25.0, 2.0, 0.5, 0.25, 0, dda},
        Geometry{25.0, 2.0, 0.5, 0.25, 0, vem}, Geometry{40.0, 1.2, 0.3, 0.2, 0, dda},
        Geometry{40.0, 1.2, 0.3, 0.2, 0, vem}}) {
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

TEST(JointStrength, BlockOnACohesiveJointSlidesJustBelowTheLimitEquilibriumCohesion) {
  // At 0.95 c* the whole joint yields, its bond breaks, and the block slides on friction
  // alone: in the second half of the steps each static step slides a dt^2 / 2, to 1% (the
  // block's elastic settling is over by then; measured equal to 6 digits).
  for (const Geometry& g :
       {Geometry{30.0, 1.2, 0.6, 0.2, 0}, Geometry{30.0, 3.0, 1.0, 0.3, 0},
        Geometry{30.0, 1.2, 0.6, 0.2, 1}, Geometry{25.0, 2.0, 0.5, 0.25, 0},
        Geometry{40.0, 1.2, 0.3, 0.2, 0}, Geometry{30.0, 1.2, 0.6, 0.2, 0, ElementKind::dda},
        Geometry{30.0, 1.2, 0.6, 0.2, 0, ElementKind::vem},
        Geometry{25.0, 2.0, 0.5, 0.25, 0, ElementKind::dda},
        Geometry{40.0, 1.2, 0.3, 0.2, 0, ElementKind::vem}}) {
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

TEST(JointStrength, DynamicStartHoldsAtTwiceTheStaticLimitCohesion) {
  // In a dynamic analysis the load comes on at once on unloaded springs, and the block's
  // undamped response overshoots its static state by 2x: the shear springs reach 2 W sin a
  // and the normal ones 2 W cos a, so the joint holds only with c >= 2 c*. That is physics
  // (a load applied suddenly), not the contact model: at 1.05 c* the bond breaks in the first
  // steps and the block slides (measured, NMM and DDA blocks at 30 degrees: broken at 1.05,
  // 1.5 and 1.9 c*, held at 2.0, 2.1 and 2.5 c*). So the dynamic family is tested at the
  // dynamic limit 2 c*: it holds at 1.05 x 2 c* (tolerances as in the static holding test;
  // measured moved 1.6e-6 to 1.9e-6 m, 1.2e-11 to 1.8e-11 m in the second half) and breaks at
  // 0.95 x 2 c*, after which it slides at friction alone: over the 0.1 s it moves more than
  // half of what friction alone lets it slide from rest, g t^2 (sin a - tan phi cos a) / 2
  // (measured 94% to 95%; the bond holds for the first steps), and never more than that
  // (0.1% for the elastic settling). A VEM block overshoots less
  // (its stabilisation): it holds at 1.9 c* too, and breaks at 1.5 c* (measured; also at
  // 1.05 c*), where it is tested.
  for (const ElementKind kind : {ElementKind::nmm, ElementKind::dda, ElementKind::vem}) {
    for (const double ratio : {2.1, kind == ElementKind::vem ? 1.5 : 1.9}) {
      const Geometry g{30.0, 1.2, 0.6, 0.2, 0, kind};
      CohesiveIncline incline = incline_of(g, ratio);
      incline.integration = TimeIntegration::dynamic;
      const int steps = 100;
      const CohesiveIncline::Result r = incline.run(steps);
      const double t = 1e-3 * steps;
      const double a = g.alpha * std::numbers::pi / 180.0;
      const double free_slide =
          0.5 * 9.81 * (std::sin(a) - std::tan(20.0 * std::numbers::pi / 180.0) * std::cos(a)) * t *
          t;
      std::printf("dynamic, %.2f c*, kind %d: moved %.3e m (%.1e in the second half; friction "
                  "alone from rest %.3e), %ld parts broken, worst energy_error %.2e\n",
                  ratio, static_cast<int>(kind), r.moved, r.late, free_slide, r.bonds_broken,
                  r.energy_error);
      // The energy balance closes to 1% where the bond holds (measured 2.4e-3 NMM, 1.8e-5
      // DDA, 5.0e-5 VEM) and where it breaks (4e-7).
      EXPECT_LT(r.energy_error, 0.01) << "kind " << static_cast<int>(kind);
      if (ratio > 2.0) {
        EXPECT_LT(r.moved, 1e-5) << "kind " << static_cast<int>(kind);
        EXPECT_LT(r.late, 1e-6) << "kind " << static_cast<int>(kind);
        EXPECT_EQ(r.bonds_broken, 0);
      } else {
        EXPECT_GT(r.bonds_broken, 0);
        EXPECT_GT(r.moved, 0.5 * free_slide) << "kind " << static_cast<int>(kind);
        EXPECT_LT(r.moved, free_slide * 1.001) << "kind " << static_cast<int>(kind);
      }
    }
  }
}

/// A block L x H hanging under a fixed ceiling (1 m wider on either side, 0.5 m thick, held
/// along its top) by a bonded joint of tensile strength T = W / (ratio L) (cohesion as much,
/// friction angle 20 degrees), in Shi's static analysis from unloaded springs.
struct HangingBlock {
  Geometry g;         ///< block size, cover size, order and kind (the slope unused)
  double ratio = 1.0; ///< W / L over T

  struct Result {
    double moved = 0.0;  ///< the block centre's displacement after the steps, m
    double late = 0.0;   ///< its displacement in the second half of the steps, m
    double fall = 0.0;   ///< what a free fall moves in one static step (from rest), m
    double normal = 0.0; ///< summed normal force of the contacts (compressive positive), N
    double weight = 0.0; ///< W, N
    double joint_length = 0.0;
    long bonds_broken = 0;
  };

  [[nodiscard]] Result run(int steps) const {
    const double length = g.length;
    const double height = g.height;
    MaterialRegion ceiling{"ceiling",
                           {{{{-1.0, 0.0},
                              {0.0, 0.0},
                              {length, 0.0},
                              {length + 1.0, 0.0},
                              {length + 1.0, 0.5},
                              {-1.0, 0.5}},
                             {}}}};
    MaterialRegion block{"block",
                         {{{{0.0, -height}, {length, -height}, {length, 0.0}, {0.0, 0.0}}, {}}}};
    const double rho = 2500.0;
    const double gravity = 9.81;
    const double weight = rho * gravity * length * height;
    const double tensile = weight / (ratio * length);
    const ElasticMaterial rock = elastic(1e10, 0.25, rho, PlaneCondition::strain);
    testing::Setup s = testing::make_setup(
        {ceiling, block},
        {line("glue", {0.0, 0.0}, {length, 0.0}), line("top", {-1.0, 0.5}, {length + 1.0, 0.5})},
        {0}, nullptr, g.size, rock, g.order, {ElementKind::nmm, g.kind});
    Scene scene;
    scene.supports = curve_support_points(s.model, 1, true, true, SupportMethod::exact, "top");
    scene.body_loads.push_back({{0.0, -gravity}, {}});
    const Point2 centre(0.5 * length, -0.5 * height);
    scene.monitors.push_back({s.model.find_element(centre, 1e-9), centre});
    StepperOptions options;
    options.integration = TimeIntegration::static_reset;
    const double dt = 1e-3;
    options.time_step = dt;
    const double phi = 20.0 * std::numbers::pi / 180.0;
    TimeStepper stepper(
        s.model, scene, options,
        testing::contact_for(s.model, 40.0 * rock.young, {phi, tensile, tensile}, true));
    Result r;
    std::tie(r.moved, r.late) = motion(stepper, centre, steps);
    r.fall = 0.5 * gravity * dt * dt;
    r.weight = weight;
    const ContactSystem& contact = *stepper.contact();
    for (const ContactPoint& p : contact.points()) {
      r.joint_length += p.length;
      r.normal += p.normal_force; // an open bond pulls with its tensile strength
    }
    r.bonds_broken = contact.counters().bonds_broken;
    return r;
  }
};

TEST(JointStrength, BlockHangingByTensileStrengthHoldsJustBelowItAndFallsJustAbove) {
  // Tolerances: at W / L = 0.95 T the block holds, moving only by the elastic settling of the
  // block, the ceiling and the springs (measured at most 1.7e-6 m; 1e-5 m is 1/30 of a free
  // fall in these 60 static steps) and settled in the second half (measured 0 to 5e-15 m; 1e-6
  // m is 1/150 of the free fall there), no bond broken, the contacts represent the joint's
  // length once (to 1e-6, as on the slope), and their summed normal force is -W to 0.5% (the
  // ends of the face, where the elastic bodies concentrate the pull beyond T, pull with T:
  // plastic yield). At 1.05 T every part has yielded in the first step, the bond breaks, and
  // the block falls: each static step of the second half moves it g dt^2 / 2, to 1%.
  for (const Geometry& g : {Geometry{0.0, 1.2, 0.6, 0.2, 0}, Geometry{0.0, 2.0, 0.5, 0.25, 0},
                            Geometry{0.0, 1.2, 0.6, 0.1, 0}, Geometry{0.0, 1.2, 0.6, 0.2, 1},
                            Geometry{0.0, 1.2, 0.6, 0.2, 0, ElementKind::dda},
                            Geometry{0.0, 2.0, 0.5, 0.25, 0, ElementKind::dda},
                            Geometry{0.0, 1.2, 0.6, 0.2, 0, ElementKind::vem},
                            Geometry{0.0, 3.0, 1.0, 0.3, 0, ElementKind::vem}}) {
    for (const double ratio : {0.95, 1.05}) {
      const int steps = 60;
      const HangingBlock::Result r = HangingBlock{g, ratio}.run(steps);
      const double fall = (steps - steps / 2) * r.fall;
      std::printf("W/L = %.2f T, %g x %g m, cover %g, order %d, kind %d: moved %.3e m, in the "
                  "second half %.5e m (free fall %.5e), N %.1f (W %.1f), length %.9f m, %ld "
                  "parts broken\n",
                  ratio, g.length, g.height, g.size, g.order, static_cast<int>(g.kind), r.moved,
                  r.late, fall, r.normal, r.weight, r.joint_length, r.bonds_broken);
      if (ratio < 1.0) {
        EXPECT_LT(r.moved, 1e-5) << g.length << " m, kind " << static_cast<int>(g.kind);
        EXPECT_LT(r.late, 1e-6) << g.length << " m, kind " << static_cast<int>(g.kind);
        EXPECT_EQ(r.bonds_broken, 0);
        EXPECT_NEAR(r.joint_length, g.length, 1e-6 * g.length);
        EXPECT_NEAR(r.normal, -r.weight, 5e-3 * r.weight);
      } else {
        EXPECT_GT(r.bonds_broken, 0);
        EXPECT_NEAR(r.late, fall, 0.01 * fall)
            << g.length << " m, kind " << static_cast<int>(g.kind);
      }
    }
  }
}

} // namespace
} // namespace nmm
