// SPDX-License-Identifier: MIT
// Verification of large rotations of NMM blocks (issue 45, item 4): with `exact_rotation` a
// free NMM body spinning at pi rad/s keeps its area and has no stress from the rotation, order
// 0 and 1, on a regular and an irregular math mesh, its energy balance closed; a tall NMM
// block toppling on a ramp turns as the DDA block of the same shape does.
#include "verification_support.hpp"
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {
namespace {

using std::numbers::pi;
using testing::Topple;

/// What one revolution did to a free NMM body.
struct Spin {
  double area_change = 0.0;  ///< relative, signed
  double max_stress = 0.0;   ///< largest |stress component| at any element vertex, Pa
  double spin_error = 0.0;   ///< |kinetic energy / start - 1|
  double energy_error = 0.0; ///< largest StepReport::energy_error
  int elements = 0;
};

/// An L-shaped body of 3 m² (legs 2 m, 1 m thick) turned by 0.3 rad so that the math mesh cuts
/// its edges, far from the origin, E = 1e9 Pa, nu = 0.25, rho = 2500, plane strain, covers of
/// 0.3 m (regular, or irregular_mesh()), spinning freely at pi rad/s for one revolution in
/// 2000 steps of 1 ms, no loads.
Spin spin_one_revolution(int order, bool irregular, bool exact_rotation) {
  const Point2 o(1000.0, -500.0);
  const Eigen::Matrix2d turn = Eigen::Rotation2Dd(0.3).toRotationMatrix();
  Loop outline;
  for (const Point2& p :
       {Point2(0, 0), Point2(2, 0), Point2(2, 1), Point2(1, 1), Point2(1, 2), Point2(0, 2)})
    outline.push_back(o + turn * p);
  MaterialRegion body{"body", {{outline, {}}}};
  ElasticMaterial rock = testing::elastic(1e9, 0.25, 2500.0, PlaneCondition::strain);
  rock.exact_rotation = exact_rotation;
  const double size = 0.3;
  const MathMesh math =
      testing::irregular_mesh(o.x() - 0.4, o.y() - 0.1, o.x() + 1.9, o.y() + 2.6, size);
  testing::Setup s =
      testing::make_setup({body}, {}, {}, irregular ? &math : nullptr, size, rock, order);
  StepperOptions options;
  options.time_step = 1e-3;
  TimeStepper stepper(s.model, {}, options);
  stepper.set_rigid_velocities({Point2::Zero()}, {pi});
  auto total_area = [&] {
    double a = 0.0;
    for (const ModelElement& e : s.model.elements)
      a += e.area;
    return a;
  };
  const double area0 = total_area();
  Spin r;
  r.elements = s.model.n_elements();
  double kinetic0 = 0.0;
  for (int step = 0; step < 2000; ++step) {
    const StepReport report = stepper.step(2.0);
    if (step == 0)
      kinetic0 = report.kinetic_energy;
    r.spin_error = std::abs(report.kinetic_energy / kinetic0 - 1.0);
    r.energy_error = std::max(r.energy_error, report.energy_error);
  }
  EXPECT_NEAR(stepper.time(), 2.0, 1e-12);
  r.area_change = (total_area() - area0) / area0;
  for (const ModelElement& e : s.model.elements) {
    for (const Polygon& p : e.polygons) {
      for (const Point2& x : p.outer)
        r.max_stress = std::max(r.max_stress, e.stress.at(x).cwiseAbs().maxCoeff());
    }
  }
  return r;
}

TEST(NmmRotation, FreeBodySpinsARevolutionKeepingItsAreaWithoutStress) {
  // Moved by its linear step displacement r J (x - c), r = pi 1e-3, every cover of a spinning
  // body goes along its tangent and the body grows by about 1 + r² a step, (1 + r²)^2000 - 1
  // = 2.0% in a revolution, partly pulled back by the stress the unturned velocities put in
  // (measured below without the key and printed). With exact_rotation each block's rigid part
  // turns by R(r) about its centre of mass and the velocities turn with it
  // (Model::turn_exactly): the linear step of a rigid spin then has no strain, the body
  // comes back to its shape after every step, and what is left is rounding. The bounds:
  // area 1e-6 a revolution (issue 45; measured 2e-13); stress below 1e-6 of what the run
  // without the key has (4e4 to 5e5 Pa there; rounding of strains of 1e-14 gives 1e-5 Pa,
  // measured at most 5.4e-5 Pa, 6e-10 of it); kinetic energy to 1e-9 and the energy
  // balance (energy_error) to 1e-6, where rounding over 2000 steps gives about 1e-12
  // (without the key both miss by 2%).
  for (const int order : {0, 1}) {
    for (const bool irregular : {false, true}) {
      const Spin linear = spin_one_revolution(order, irregular, false);
      const Spin exact = spin_one_revolution(order, irregular, true);
      std::printf("order %d, %s mesh (%d elements): without exact_rotation area %+.3e, stress "
                  "%.3e Pa, kinetic %.2e, energy error %.2e; with it area %+.3e, stress %.3e Pa, "
                  "kinetic %.2e, energy error %.2e\n",
                  order, irregular ? "irregular" : "regular", exact.elements, linear.area_change,
                  linear.max_stress, linear.spin_error, linear.energy_error, exact.area_change,
                  exact.max_stress, exact.spin_error, exact.energy_error);
      EXPECT_GT(std::abs(linear.area_change), 1e-3) << order << irregular;
      EXPECT_LT(std::abs(exact.area_change), 1e-6) << order << irregular;
      EXPECT_LT(exact.max_stress, 1e-6 * linear.max_stress) << order << irregular;
      EXPECT_LT(exact.spin_error, 1e-9) << order << irregular;
      EXPECT_LT(exact.energy_error, 1e-6) << order << irregular;
    }
  }
}

TEST(NmmRotation, TallBlockTopplesAsTheDdaBlockDoes) {
  // The toppling block of initial_equilibrium_test.cpp (b / h = 0.85 tan 30°, from the initial
  // equilibrium, on a ramp with friction enough to hold it from sliding, 2 ms steps) as an NMM
  // block with exact_rotation, order 0 and 1, against the same block as a DDA block: the
  // rotation at 0.8 s (about 0.55 rad) within 1% (issue 45). The blocks are ten times as stiff
  // as the Topple family's (E = 1e11 Pa, springs 40 E): what differs between an NMM block and a
  // DDA block (constant strain only) is then their kinematics, not their compliance. At
  // E = 1e10 the NMM blocks turn 0.79% (order 0) and 1.43% (order 1) more than the DDA block,
  // at 1e11 0.16% and 0.40%: the difference goes as 1/E, the elastic compliance of the NMM
  // block in its seat's springs and at its pivot (it forms in the first 0.1 s: 3% then, the
  // topple growing from the tilt it starts with as cosh(t / tau)). The key itself changes the
  // rotation at 0.8 s by 0.04% (about 4 mrad a step, whose r²/2 is 1e-5), and the DDA block
  // turns within 0.16% of the rigid block about its corner.
  Topple dda;
  dda.young = 1e11;
  dda.alpha_degrees = 30.0;
  dda.equilibrium = true;
  dda.width = 0.85 * std::tan(dda.alpha_degrees * pi / 180.0) * dda.height;
  dda.block_kind = ElementKind::dda;
  const double reference = dda.rotation(0.8);
  std::printf("DDA block: turned %.5g rad in 0.8 s (the rigid block about its corner %.5g)\n",
              reference, dda.rigid_rotation(0.8));
  for (const int order : {0, 1}) {
    Topple nmm = dda;
    nmm.block_kind = ElementKind::nmm;
    nmm.order = order;
    nmm.exact_rotation = true;
    const double turned = nmm.rotation(0.8);
    std::printf("NMM block, order %d, exact_rotation: turned %.5g rad, %+.3f%% of the DDA "
                "block's\n",
                order, turned, 100.0 * (turned / reference - 1.0));
    EXPECT_NEAR(turned, reference, 0.01 * reference) << order;
  }
}

} // namespace
} // namespace nmm
