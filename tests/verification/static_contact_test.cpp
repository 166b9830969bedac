// SPDX-License-Identifier: MIT
// Verification of Shi's static analysis with contact (examples/02_jointed_slope): a rock wedge
// cut off by a joint that meets the free surface at 20 degrees stands under gravity when the
// joint's friction angle exceeds its dip. It must settle in a few steps with no step cut, and
// move no more than the rock beneath it settles.
#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {
namespace {

using testing::contact_for;
using testing::elastic;
using testing::line;

using std::numbers::pi;

/// A block of rock 20 m x 10 m on a held base, plane strain, E = 10 GPa, under gravity. A
/// joint dipping 20 degrees leaves the top surface at (4, 10) (a 20 degree wedge tip) and the
/// right face at y = 4.18: the wedge above it is free but for the joint (phi = 25 degrees).
/// With @p cross, a steep joint (70 degrees) runs from the top surface through the wedge and
/// across the bedding and ends inside the rock below it: two joints crossing, a crack tip.
struct StandingWedge {
  bool cross = false;
  int steps = 10;

  struct Result {
    long cuts = 0;
    double centre_moved = 0.0; ///< total displacement of the wedge's centroid, m
    double last_step = 0.0;    ///< largest displacement of the last step, m
    double largest_step = 0.0; ///< of any step, m
    double max_penetration = 0.0;
    int last_iterations = 0;
  };

  Result run() const {
    const double tan_dip = std::tan(20.0 * pi / 180.0);
    std::vector<NamedCurve> curves{line("base", {0.0, 0.0}, {20.0, 0.0}),
                                   line("bedding", {4.0, 10.0}, {22.0, 10.0 - 18.0 * tan_dip})};
    std::vector<int> joints{1};
    if (cross) {
      const double c = 1.0 / std::tan(70.0 * pi / 180.0);
      curves.push_back(line("cross", {11.0, 11.0}, {11.0 + 7.0 * c, 4.0}));
      joints.push_back(2);
    }
    const ElasticMaterial rock = elastic(10.0e9, 0.25, 2600.0, PlaneCondition::strain);
    testing::Setup s = testing::make_setup({testing::rectangle("rock", 0.0, 0.0, 20.0, 10.0)},
                                           curves, joints, nullptr, 1.0, rock, 0);
    Scene scene;
    scene.supports = curve_support_points(s.model, 0, true, true, SupportMethod::exact, "base");
    scene.body_loads.push_back({{0.0, -9.81}, {}});
    const Point2 centre(14.6667, 8.0587); // the wedge's centroid (left of the cross joint)
    scene.monitors.push_back({s.model.find_element(centre, 1e-9), centre});
    StepperOptions options;
    options.integration = TimeIntegration::static_reset; // Shi's static analysis, auto step
    TimeStepper stepper(s.model, scene, options,
                        contact_for(s.model, 40.0 * rock.young, {25.0 * pi / 180.0, 0.0, 0.0}));
    Result r;
    for (int step = 0; step < steps; ++step) {
      const StepReport report = stepper.step(1e9);
      r.cuts += report.step_cuts;
      r.largest_step = std::max(r.largest_step, report.max_displacement);
      r.last_step = report.max_displacement;
      r.max_penetration = std::max(r.max_penetration, report.max_penetration);
      r.last_iterations = report.open_close_iterations;
    }
    r.centre_moved = (stepper.scene().monitors[0].position - centre).norm();
    return r;
  }
};

/// The settlement of the top of a free column of rock of height H under its own weight in
/// plane strain: rho g H^2 / (2 E'), E' = E / (1 - nu^2).
double column_settlement(double height) {
  return 2600.0 * 9.81 * height * height / (2.0 * 10.0e9 / (1.0 - 0.25 * 0.25));
}

TEST(StaticContact, WedgeOnAJointMeetingTheSurfaceAt20DegreesStandsWithoutAStepCut) {
  // phi = 25 > 20 degrees: the wedge stands (its tip, where the joint carries almost no
  // normal force, slips while the rock beneath settles under its weight). Before the fix
  // (2026-11-26) the 10 steps took 13 cuts: contacts at the limit of friction at rest flipped
  // between lock and slide on the rounding of the coordinates, and the first step's slip
  // spreading along the joint needed 7 refactorisations where a step was cut after 6.
  StandingWedge wedge;
  const StandingWedge::Result r = wedge.run();
  const double bound = column_settlement(10.0);
  std::printf("standing wedge: %ld cuts, centroid moved %.3e m (free column settles %.3e m), "
              "largest step %.3e m, last step %.3e m in %d solves, max penetration %.3e m\n",
              r.cuts, r.centre_moved, bound, r.largest_step, r.last_step, r.last_iterations,
              r.max_penetration);
  EXPECT_EQ(r.cuts, 0);
  // It stands: it moves with the rock beneath it, less than the top of a free 10 m column
  // settles (measured: 0.92 of it), and at the end it is at rest, to the rounding of its
  // coordinates (measured: 1e-14 m in one solve a step).
  EXPECT_LT(r.centre_moved, bound);
  EXPECT_LT(r.last_step, 1e-12);
  EXPECT_LE(r.last_iterations, 2);
  EXPECT_LT(r.max_penetration, 1e-6);
}

TEST(StaticContact, WedgeCutByACrossingJointEndingInTheRockStandsWithoutAStepCut) {
  // The same wedge cut by a steep joint that crosses the bedding and ends inside the rock:
  // four corners meet where the joints cross (one angle-to-angle contact per pair of opposite
  // corners, not one angle-to-edge contact per edge leaving the point), and the crack faces
  // below the crossing slide near their tip, a little in each step, for about 30 steps
  // (measured 2026-11-26: 1e-7 m a step until step 26, then at rest to 1e-14 m in two solves
  // a step). Before the fix: 24 cuts in the first 10 steps.
  StandingWedge wedge;
  wedge.cross = true;
  wedge.steps = 40;
  const StandingWedge::Result r = wedge.run();
  std::printf("wedge cut by a crossing joint: %ld cuts, centroid moved %.3e m, largest step "
              "%.3e m, last step %.3e m, max penetration %.3e m\n",
              r.cuts, r.centre_moved, r.largest_step, r.last_step, r.max_penetration);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_LT(r.centre_moved, column_settlement(10.0));
  EXPECT_LT(r.last_step, 1e-12);
  EXPECT_LT(r.max_penetration, 1e-6);
}

} // namespace
} // namespace nmm
