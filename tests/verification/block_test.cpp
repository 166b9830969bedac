// SPDX-License-Identifier: MIT
// Verification of the special covers (issue 6): a DDA block spinning freely keeps its area
// and its angular velocity; DDA and VEM blocks under a uniform load have the exact constant
// stress; a region switches model with one word and gives the same rigid motion; a loaded
// block stays in its equilibrium step after step (a VEM block's stabilisation force is
// carried), and the carried force turns with the block.
#include "mesh/error.hpp"

#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace nmm {
namespace {

using testing::elastic;

using std::numbers::pi;

/// Holds the rigid motion of a body with corners at (0, 0) and (2, 0): the first in x and y,
/// the second in y.
void hold_rigid_motion(const Model& model, Scene& scene) {
  for (const auto& [x, fix_x] : {std::pair{Point2(0, 0), true}, std::pair{Point2(2, 0), false}}) {
    SupportPoint hold;
    hold.point = {model.find_element(x, 1e-9), x};
    hold.start = x;
    hold.fix_x = fix_x;
    hold.fix_y = true;
    hold.origin = "hold";
    scene.supports.push_back(hold);
  }
}

/// An L-shaped (concave) block of 3 m² with its corner at @p o, alone in the model.
testing::Setup l_block(ElementKind kind,
                       Point2 o = Point2(1000.0, -500.0),
                       PlaneCondition plane = PlaneCondition::strain) {
  MaterialRegion block{"block",
                       {{{o, o + Point2(2, 0), o + Point2(2, 1), o + Point2(1, 1), o + Point2(1, 2),
                          o + Point2(0, 2)},
                         {}}}};
  return testing::make_setup({block}, {}, {}, nullptr, 0.5, elastic(1e9, 0.25, 2500.0, plane), 0,
                             {kind});
}

/// What one revolution of a free block did to it.
struct Revolution {
  double area_change = 0.0; ///< relative, signed
  double spin_error = 0.0;  ///< |omega1 - omega| / omega, omega1 the rotation of the velocity
  double moved = 0.0;       ///< the largest distance of a vertex from its start (m)
};

/// The L block of l_block() spinning freely at one revolution a second, no loads, for one
/// revolution in 1000 steps of 1 ms; a VEM block with @p exact_rotation as its material's.
Revolution spin_one_revolution(ElementKind kind, bool exact_rotation = false) {
  testing::Setup s = l_block(kind);
  EXPECT_EQ(s.model.n_elements(), 1);
  s.model.materials[0].exact_rotation = exact_rotation;
  const double omega = 2.0 * pi;
  StepperOptions options;
  options.time_step = 1e-3;
  TimeStepper stepper(s.model, {}, options);
  stepper.set_rigid_velocities({Point2::Zero()}, {omega});
  const double area0 = s.model.elements[0].area;
  const Polygon start = s.model.elements[0].polygons[0];
  for (int step = 0; step < 1000; ++step)
    (void)stepper.step(1.0);
  EXPECT_NEAR(stepper.time(), 1.0, 1e-12);
  Revolution r;
  r.area_change = (area(s.model.elements[0].polygons[0]) - area0) / area0;
  // The rotation of the velocity field: r0's rate for a DDA block, that of Pi_P v for VEM.
  const Eigen::VectorXd velocity = s.model.element_values(0, stepper.velocity());
  r.spin_error = std::abs(s.model.shape(0).rotation(
                              {velocity.data(), static_cast<std::size_t>(velocity.size())}) -
                          omega) /
                 omega;
  for (std::size_t k = 0; k < start.outer.size(); ++k)
    r.moved = std::max(r.moved, (s.model.elements[0].polygons[0].outer[k] - start.outer[k]).norm());
  return r;
}

TEST(DdaBlock, SpinsOneRevolutionKeepingItsAreaAndItsAngularVelocity) {
  // Issue 6: a spinning block with no loads keeps its area to 1e-10 per revolution and its
  // angular velocity to 1e-6 relative. The linear DDA function moves a point by tan(r0)
  // sideways: applied as it is, the area would grow by (1 + r0²) every step, 4% in this
  // revolution of 1000 steps; the exact rotation of the geometry update removes that. What
  // is left is rounding (of order 1e-16 per step). The block also comes back to where it
  // started (1e-9 m: rounding of coordinates of order 1e3 m over 1000 steps).
  const Revolution r = spin_one_revolution(ElementKind::dda);
  std::printf("spinning DDA block: area %.3e relative change, angular velocity %.3e, back to "
              "start within %.3e m\n",
              std::abs(r.area_change), r.spin_error, r.moved);
  EXPECT_LT(std::abs(r.area_change), 1e-10);
  EXPECT_LT(r.spin_error, 1e-6);
  EXPECT_LT(r.moved, 1e-9);
}

TEST(VemBlock, SpinsOneRevolutionKeepingItsAreaWithExactRotationAndGrowsWithout) {
  // The same revolution as a VEM block (issue 8, "a block spinning"). Moved by their linear
  // displacement r0 J (x - c), the vertices leave the block (1 + r0²) larger every step,
  // r0 = 2 pi / 1000: exp(1000 r0²) - 1 = 4.0% in the revolution, with zero linear strain
  // (nothing resists it) - the paper's update, kept by default because it keeps a contact's
  // penetration in the equations that of the moved geometry (RotatingTriangle in
  // contact_test.cpp); the test asserts more than 3%. With exact_rotation
  // (Model::turn_exactly) the block turns by R(r0) and its vertex velocities with it: what is
  // left is rounding, as for the DDA block (the same bounds).
  for (const bool exact : {false, true}) {
    const Revolution r = spin_one_revolution(ElementKind::vem, exact);
    std::printf("spinning VEM block, %s rotation: area %.3e relative change, angular velocity "
                "%.3e, back to start within %.3e m\n",
                exact ? "exact" : "linear", r.area_change, r.spin_error, r.moved);
    if (exact) {
      EXPECT_LT(std::abs(r.area_change), 1e-10);
      EXPECT_LT(r.spin_error, 1e-6);
      EXPECT_LT(r.moved, 1e-9);
    } else {
      EXPECT_GT(r.area_change, 0.03);
    }
  }
}

TEST(SpecialBlocks, UniformTensionGivesTheExactStressInDdaAndVemBlocks) {
  // A concave L block pulled by a uniform traction on its three vertical faces in a static
  // analysis, held at two points: the exact stress is uniform, sxx = t, syy = sxy = 0. The
  // DDA block's constant strain and the VEM block's projected strain represent it exactly
  // (the VEM consistency term is exact for linear fields and the stabilisation vanishes on
  // them), so the error is rounding: 1e-9 relative. The support points sit on the edges.
  for (const ElementKind kind : {ElementKind::dda, ElementKind::vem}) {
    const Point2 o(0.0, 0.0);
    MaterialRegion block{"block",
                         {{{o, o + Point2(2, 0), o + Point2(2, 1), o + Point2(1, 1),
                            o + Point2(1, 2), o + Point2(0, 2)},
                           {}}}};
    testing::Setup s = testing::make_setup(
        {block},
        {testing::line("left", {0, 0}, {0, 2}), testing::line("right", {2, 0}, {2, 1}),
         testing::line("inner", {1, 1}, {1, 2})},
        {}, nullptr, 0.5, elastic(1e9, 0.25, 2500.0, PlaneCondition::stress), 0, {kind});
    Scene scene;
    // Pull right on the two right faces and left on the left face: 1 MPa.
    scene.curve_loads.push_back(testing::traction_load(0, {-1e6, 0.0}));
    scene.curve_loads.push_back(testing::traction_load(1, {1e6, 0.0}));
    scene.curve_loads.push_back(testing::traction_load(2, {1e6, 0.0}));
    hold_rigid_motion(s.model, scene);
    StepperOptions options;
    options.integration = TimeIntegration::static_reset;
    TimeStepper stepper(s.model, scene, options);
    (void)stepper.step(1.0);
    const Eigen::Vector3d stress = s.model.elements[0].stress.at(Point2(0.5, 0.5));
    std::printf("%s block in tension: stress (%.9g, %.3g, %.3g) Pa\n",
                kind == ElementKind::dda ? "dda" : "vem", stress(0), stress(1), stress(2));
    EXPECT_NEAR(stress(0), 1e6, 1e-9 * 1e6);
    EXPECT_NEAR(stress(1), 0.0, 1e-9 * 1e6);
    EXPECT_NEAR(stress(2), 0.0, 1e-9 * 1e6);
  }
}

TEST(SpecialBlocks, BlockWithoutThreeVerticesOrAreaIsAnInputErrorNamingItsMaterial) {
  // Issue 6, bad input: a dda or vem block with fewer than 3 vertices or no area after
  // cutting gets a clear message (material, place, what to check), not an assertion or NaN
  // matrices. The exact mesher does not make such blocks from sane geometry, so the cut
  // block's loop is spoiled here: cut to 2 vertices, then made collinear (area 0).
  for (const ElementKind kind : {ElementKind::dda, ElementKind::vem}) {
    testing::Setup s = l_block(kind);
    ASSERT_EQ(s.covers.blocks.size(), 1U);
    const ElasticMaterial material = elastic(1e9, 0.25, 2500.0, PlaneCondition::strain);
    ModelOptions options;
    options.region_kinds = {kind};
    const std::string name = kind == ElementKind::dda ? "dda" : "vem";
    for (const bool collinear : {false, true}) {
      CoverSystem covers = s.covers;
      ASSERT_EQ(covers.blocks[0].loops.size(), 1U);
      std::vector<Point2>& loop =
          covers.loops[static_cast<std::size_t>(covers.blocks[0].loops[0])].vertices;
      const Point2 a = loop[0];
      const Point2 b = loop[1];
      if (collinear)
        loop = {a, 0.5 * (a + b), b};
      else
        loop = {a, b};
      try {
        (void)make_model(covers, s.math, {material}, options);
        ADD_FAILURE() << name << (collinear ? ": collinear" : ": two vertices") << " accepted";
      } catch (const InputError& error) {
        const std::string what = error.what();
        std::printf("%s\n", what.c_str());
        EXPECT_NE(what.find(name + " material \"" + material.name + "\""), std::string::npos);
        EXPECT_NE(what.find(collinear ? "has 3 vertices and an area of 0 m²"
                                      : "has 2 vertices and an area of 0 m²"),
                  std::string::npos);
        EXPECT_NE(what.find("check the joints"), std::string::npos);
      }
    }
  }
}

TEST(VemBlock, LoadedBlockReachesEquilibriumInOneStepAndStaysThere) {
  // The concave L block as one VEM block, static (velocity reset every step), held at two
  // corners (three components: statically determinate), under constant point loads at three
  // vertices that deform it with more than a linear field: hourglass deformation that only
  // the stabilisation term resists. The first step solves the equilibrium; every later step
  // starts from it, so its step displacement comes only from the geometry update (the next
  // step's equations are built on the moved block): of the order of the strain times the
  // first step's displacement. The loads give a strain of about 1e-12 (1e-3 N on 1 m of a
  // 1 GPa block), so 19 more steps may add 19 * 1e-12 (times a geometric factor of order 1)
  // of the first displacement: 1e-9 relative bounds it. A block that forgets its
  // stabilisation force between steps has its hourglass part pushed back by nothing and
  // creeps by a fraction of order 1 of the first step, every step. (A DDA block has no
  // stabilisation; its largest displacement is measured from turned vertex positions, whose
  // rounding, 4e-16 m, would dominate at this scale.)
  testing::Setup s = l_block(ElementKind::vem, Point2(0.0, 0.0), PlaneCondition::stress);
  Scene scene;
  hold_rigid_motion(s.model, scene);
  const double f = 1e-3; // N
  for (const auto& [x, force] :
       {std::pair{Point2(1, 1), Point2(-f, -f)}, std::pair{Point2(1, 2), Point2(f, 0.0)},
        std::pair{Point2(2, 1), Point2(0.0, -f)}}) {
    PointLoad load;
    load.point = {s.model.find_element(x, 1e-9), x};
    load.force = force;
    scene.point_loads.push_back(load);
  }
  StepperOptions options;
  options.integration = TimeIntegration::static_reset;
  options.time_step = 1.0;
  TimeStepper stepper(s.model, scene, options);
  const double first = stepper.step(1.0).max_displacement;
  double later = 0.0; // the later steps' largest displacements, added
  const int n_steps = 20;
  for (int step = 2; step <= n_steps; ++step)
    later += stepper.step(static_cast<double>(step)).max_displacement;
  std::printf("vem block, constant loads: first step %.6e m, the next %d steps %.3e of it\n", first,
              n_steps - 1, later / first);
  EXPECT_GT(first, 1e-12); // the loads do move it (8e-12 m)
  EXPECT_LT(later, 1e-9 * first);
}

TEST(VemBlock, CarriedStabilisationForceTurnsWithTheBlock) {
  // A VEM L block given a carried stabilisation force by a step of hourglass deformation,
  // then turned rigidly by 90 degrees in 100 steps of exact rotations. A vertex force of the
  // block is material: it must turn with the block, as the stress does. Each step turns it
  // by the step's rotation r0 of Pi_P u, which for an exact rotation by a is sin a (the
  // stress turns by the same angle), so after N steps the force is short of the full turn
  // theta by theta - N sin(theta / N) = theta³ / (6 N²) = 6.5e-5 rad: the tolerance is
  // 1.1 times that, relative to the force. The rotation adds no stabilisation force (an
  // affine step has no hourglass part), the load it gives on the turned block is the first
  // load turned, without resultant and moment (1e-9 of the force, N and N m over 3 m of
  // block: rounding). A force left unturned would be off by sqrt(2) of itself.
  const Point2 o(1000.0, -500.0);
  testing::Setup s = l_block(ElementKind::vem, o, PlaneCondition::stress);
  Model& model = s.model;
  ASSERT_EQ(model.n_elements(), 1);
  ASSERT_EQ(model.n_dofs(), 12);
  // An hourglass step: the re-entrant vertex (index 3) pulled inwards by 1 mm.
  Eigen::VectorXd hourglass = Eigen::VectorXd::Zero(12);
  hourglass(6) = -1e-3;
  hourglass(7) = -1e-3;
  model.accumulate_stress(hourglass);
  std::vector<MaterialPoint> points;
  model.move(hourglass, points);
  const Eigen::VectorXd force0 = model.elements[0].stabilisation_force;
  ASSERT_EQ(force0.size(), 12);
  ASSERT_GT(force0.norm(), 1e3); // eta_E ~ E t: of order 1e9 * 1e-3 N
  auto load_of = [&model]() {
    const ElementShape shape = model.shape(0);
    const ElementIntegrals integrals(shape, model.elements[0].polygons);
    Eigen::VectorXd load = Eigen::VectorXd::Zero(12);
    integrals.add_stabilisation_load(model.elements[0].stabilisation_force, load);
    return load;
  };
  const Eigen::VectorXd load0 = load_of();
  // Turn by 90 degrees about the mean of the vertices in 100 exact rotations.
  const double theta = pi / 2.0;
  const int n = 100;
  const double a = theta / n;
  Eigen::Matrix2d step_rotation;
  step_rotation << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  for (int k = 0; k < n; ++k) {
    Point2 c = Point2::Zero();
    for (const ModelCover& cover : model.covers)
      c += cover.position / 6.0;
    Eigen::VectorXd raw(12);
    for (int i = 0; i < 6; ++i) {
      const Point2 r = model.covers[static_cast<std::size_t>(i)].position - c;
      raw.segment<2>(2 * i) = step_rotation * r - r;
    }
    model.accumulate_stress(raw);
    model.move(raw, points);
  }
  Eigen::Matrix2d turn;
  turn << 0.0, -1.0, 1.0, 0.0;
  auto turned = [&turn](const Eigen::VectorXd& v) {
    Eigen::VectorXd out(v.size());
    for (Eigen::Index i = 0; i < v.size(); i += 2)
      out.segment<2>(i) = turn * v.segment<2>(i);
    return out;
  };
  const Eigen::VectorXd& force = model.elements[0].stabilisation_force;
  const double shortfall = std::pow(theta, 3) / (6.0 * n * n);
  const double error = (force - turned(force0)).norm() / force0.norm();
  // The load on the turned block: no resultant, no moment about any point.
  const Eigen::VectorXd load = load_of();
  Point2 resultant = Point2::Zero();
  double moment = 0.0;
  for (int i = 0; i < 6; ++i) {
    const Point2 fi = load.segment<2>(2 * i);
    const Point2 r = model.covers[static_cast<std::size_t>(i)].position - o;
    resultant += fi;
    moment += r.x() * fi.y() - r.y() * fi.x();
  }
  const double load_error = (load - turned(load0)).norm() / load0.norm();
  std::printf("carried stabilisation force turned by 90 degrees: %.3e of it off the turned "
              "force (theta³/6N² = %.3e), load %.3e off, resultant %.3e N, moment %.3e N m\n",
              error, shortfall, load_error, resultant.norm(), moment);
  EXPECT_LT(error, 1.1 * shortfall);
  EXPECT_LT(load_error, 1.1 * shortfall);
  EXPECT_LT(resultant.norm(), 1e-9 * load0.norm());
  EXPECT_LT(std::abs(moment), 1e-9 * load0.norm());
}

TEST(VemBlock, ContactCouplesOnlyTheVerticesOfTheEdgesInContact) {
  // A row of four VEM blocks cut from one rock by joints, on a VEM base whose top carries a
  // vertex at every joint's end. A contact's gap and shear move with its slave point and the
  // two ends of its master edge (and the anchor on that edge): on a VEM block those are
  // vertices or points on one edge, so a contact couples at most 4 vertices (8 unknowns),
  // whatever the blocks' sizes. Coupling every unknown of both blocks made a contact on the
  // 188-vertex foundation of the 10,004-block rock mass a 380 x 380 matrix (4.9 of its 10 s
  // of steps; docs/benchmarks.md, "Blocks: DDA, VEM, NMM and conjugate gradients"). Exact counts,
  // no tolerance.
  testing::Setup s = testing::row_of_blocks_on_a_base(ElementKind::vem);
  ASSERT_EQ(s.model.n_elements(), 5);
  std::size_t largest_block = 0;
  for (int e = 0; e < s.model.n_elements(); ++e)
    largest_block = std::max(largest_block, s.model.element_dofs(e).size());
  auto contact = testing::contact_for(s.model, 40.0 * s.model.materials[0].young,
                                      {30.0 * pi / 180.0, 0.0, 0.0});
  contact->begin_step(s.model, 1e-3);
  ASSERT_GT(contact->n_points(), 0);
  std::size_t most = 0;
  for (int i = 0; i < contact->n_points(); ++i)
    most = std::max(most, contact->point_dofs(s.model, i).size());
  std::printf("vem row on a vem base: %d contact points, each on at most %zu unknowns (the "
              "largest block has %zu)\n",
              contact->n_points(), most, largest_block);
  EXPECT_GE(largest_block, 16U); // the base: at least 8 vertices
  EXPECT_LE(most, 8U);
  EXPECT_GE(most, 6U); // a vertex and an edge at least
}

} // namespace
} // namespace nmm
