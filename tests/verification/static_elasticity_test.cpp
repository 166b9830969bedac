// SPDX-License-Identifier: MIT
// Verification against closed forms: patch test, FEM equivalence, free fall (issue 4).
#include "mesh/error.hpp"

#include "verification_support.hpp"
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

namespace nmm {
namespace {

using testing::elastic;
using testing::line;
using testing::make_setup;
using testing::rectangle;

/// Displacement of every element vertex in one static step: moves a copy of the polygons.
struct VertexMotion {
  Point2 before;
  Point2 after;
};

std::vector<VertexMotion> vertices(const Model& before, const Model& after) {
  std::vector<VertexMotion> result;
  for (std::size_t e = 0; e < before.elements.size(); ++e) {
    for (std::size_t p = 0; p < before.elements[e].polygons.size(); ++p) {
      const Loop& a = before.elements[e].polygons[p].outer;
      const Loop& b = after.elements[e].polygons[p].outer;
      for (std::size_t k = 0; k < a.size(); ++k)
        result.push_back({a[k], b[k]});
    }
  }
  return result;
}

class PatchTest : public ::testing::TestWithParam<int> {};

/// A 2 m x @p height plate, plane stress, pulled by sigma on x = 2, held in x on x = 0 and in
/// y on y = 0, in one static step on a regular math mesh of size 0.23 that ignores its
/// edges. Exact: sxx = sigma, u = sigma x / E, v = -nu sigma y / E. The field is linear, so
/// order 0 (and order 1) covers represent it exactly: the discrete solution must be the exact
/// one. Tolerance 1e-9 relative: a linear solve of condition ~1e6 at double precision.
/// @return the number of tiny covers of the model.
int expect_uniform_stress_is_exact(int order, double height) {
  const double sigma = 2.0e6;
  const ElasticMaterial material = elastic(5.0e9, 0.25, 2600.0, PlaneCondition::stress);
  testing::Setup s =
      make_setup({rectangle("rock", 0.0, 0.0, 2.0, height)},
                 {line("left", {0.0, 0.0}, {0.0, height}), line("right", {2.0, 0.0}, {2.0, height}),
                  line("bottom", {0.0, 0.0}, {2.0, 0.0})},
                 {}, nullptr, 0.23, material, order);
  Scene scene;
  auto left = curve_support_points(s.model, 0, true, false, SupportMethod::exact, "left");
  auto bottom = curve_support_points(s.model, 2, false, true, SupportMethod::exact, "bottom");
  scene.supports.insert(scene.supports.end(), left.begin(), left.end());
  scene.supports.insert(scene.supports.end(), bottom.begin(), bottom.end());
  scene.curve_loads.push_back(testing::traction_load(1, {sigma, 0.0}));
  StepperOptions options;
  options.integration = TimeIntegration::static_reset;
  const Model before = s.model;
  TimeStepper stepper(s.model, scene, options);
  (void)stepper.step(1.0);
  for (int e = 0; e < s.model.n_elements(); ++e) {
    const LinearField3& stress = s.model.elements[static_cast<std::size_t>(e)].stress;
    const Eigen::Vector3d at_centre = stress.at(stress.origin);
    EXPECT_NEAR(at_centre(0), sigma, 1e-9 * sigma) << "element " << e;
    EXPECT_NEAR(at_centre(1), 0.0, 1e-9 * sigma) << "element " << e;
    EXPECT_NEAR(at_centre(2), 0.0, 1e-9 * sigma) << "element " << e;
  }
  const double scale = sigma * 2.0 / material.young;
  for (const VertexMotion& v : vertices(before, s.model)) {
    const Point2 exact(sigma * v.before.x() / material.young,
                       -material.poisson * sigma * v.before.y() / material.young);
    EXPECT_NEAR((v.after - v.before - exact).norm(), 0.0, 1e-9 * scale);
  }
  return static_cast<int>(
      std::count_if(s.model.covers.begin(), s.model.covers.end(),
                    [](const ModelCover& c) { return c.extension_element >= 0; }));
}

TEST_P(PatchTest, UniformStressIsExactOnANonConformingMesh) {
  static_cast<void>(expect_uniform_stress_is_exact(GetParam(), 1.0));
}

TEST_P(PatchTest, UniformStressIsExactWithTinyCoversAlongAnEdge) {
  // The plate's top edge a little above the fifth row of math nodes: the sixth row's covers
  // hold slivers below min_cover_area_ratio (1e-3) of their stars and take the extension of
  // a nearby element's field. For order 1 the extension's gradient is the affine
  // extrapolation of the root's covers' gradients, so a flex of the cover framework moves a
  // tiny cover as it moves a free one and stays a combination of no displacement, fixed like
  // any other. Before 2026-11-26 the extension took the root field's gradient, which no flex
  // moves: the tiny covers held the flexes through their slivers alone, with a stiffness
  // that vanishes with the sliver. At 1e-9 of a row the matrix was singular ("not positive
  // definite"; examples/05 failed so at cover sizes 0.02 and 0.025 m).
  const double row = 0.23 * std::sqrt(3.0) / 2.0;
  for (const double sliver : {2e-5, 1e-9}) {
    SCOPED_TRACE("sliver " + std::to_string(sliver) + " of a row");
    EXPECT_GT(expect_uniform_stress_is_exact(GetParam(), 5.0 * row * (1.0 + sliver)), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Orders, PatchTest, ::testing::Values(0, 1));

/// Independent P1 FEM: stiffness of a triangle from its B matrix (Zienkiewicz), plane strain.
Eigen::Matrix<double, 6, 6> p1_stiffness(const std::array<Point2, 3>& x, const Eigen::Matrix3d& d) {
  const double twice =
      (x[1] - x[0]).x() * (x[2] - x[0]).y() - (x[1] - x[0]).y() * (x[2] - x[0]).x();
  Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
  for (int k = 0; k < 3; ++k) {
    const Point2& p = x[static_cast<std::size_t>((k + 1) % 3)];
    const Point2& q = x[static_cast<std::size_t>((k + 2) % 3)];
    b(0, 2 * k) = (p.y() - q.y()) / twice;
    b(1, 2 * k + 1) = (q.x() - p.x()) / twice;
    b(2, 2 * k) = (q.x() - p.x()) / twice;
    b(2, 2 * k + 1) = (p.y() - q.y()) / twice;
  }
  return 0.5 * twice * b.transpose() * d * b;
}

TEST(FemEquivalence, ConformingOrderZeroReproducesIndependentP1Fem) {
  // A conforming math mesh (perturbed structured triangles), no joints, order 0: NMM is P1
  // FEM (DESIGN.md "special covers"). Left edge fixed, self-weight and a traction on the
  // right edge. Tolerance 1e-12 relative: the same linear system up to assembly order.
  const int nx = 8;
  const int ny = 4;
  MathMesh math;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = 2.0 * i / nx;
      double y = 1.0 * j / ny;
      if (i > 0 && i < nx && j > 0 && j < ny) { // interior nodes moved off the grid
        x += 0.04 * std::sin(3.0 * i + 7.0 * j);
        y += 0.03 * std::cos(5.0 * i - 2.0 * j);
      }
      math.nodes.emplace_back(x, y);
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = (nx + 1) * j + i;
      math.triangles.push_back({a, a + 1, a + nx + 2});
      math.triangles.push_back({a, a + nx + 2, a + nx + 1});
    }
  }
  const ElasticMaterial material = elastic(2.0e10, 0.3, 2500.0, PlaneCondition::strain);
  testing::Setup s =
      make_setup({rectangle("rock", 0.0, 0.0, 2.0, 1.0)},
                 {line("left", {0.0, 0.0}, {0.0, 1.0}), line("right", {2.0, 0.0}, {2.0, 1.0})}, {},
                 &math, 0.0, material, 0);
  ASSERT_EQ(s.model.n_covers(), math.n_nodes());
  Scene scene;
  scene.supports = curve_support_points(s.model, 0, true, true, SupportMethod::exact, "left");
  scene.body_loads.push_back({{0.0, -9.81}, {}});
  scene.curve_loads.push_back(testing::traction_load(1, {1.0e5, -3.0e5}));
  StepperOptions options;
  options.integration = TimeIntegration::static_reset;
  std::vector<Point2> before;
  for (const ModelCover& c : s.model.covers)
    before.push_back(c.position);
  TimeStepper stepper(s.model, scene, options);
  (void)stepper.step(1.0);

  // The reference: textbook P1 assembly, consistent loads, elimination of x = 0 nodes.
  const Eigen::Matrix3d d = elasticity_matrix(material);
  const int n = 2 * math.n_nodes();
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(n);
  for (const auto& t : math.triangles) {
    const std::array<Point2, 3> x{math.nodes[static_cast<std::size_t>(t[0])],
                                  math.nodes[static_cast<std::size_t>(t[1])],
                                  math.nodes[static_cast<std::size_t>(t[2])]};
    const Eigen::Matrix<double, 6, 6> k = p1_stiffness(x, d);
    const double area =
        0.5 * ((x[1] - x[0]).x() * (x[2] - x[0]).y() - (x[1] - x[0]).y() * (x[2] - x[0]).x());
    for (int a = 0; a < 3; ++a) {
      f(2 * t[static_cast<std::size_t>(a)] + 1) += -9.81 * material.density * area / 3.0;
      for (int b = 0; b < 3; ++b)
        for (int i = 0; i < 2; ++i)
          for (int j = 0; j < 2; ++j)
            triplets.emplace_back(2 * t[static_cast<std::size_t>(a)] + i,
                                  2 * t[static_cast<std::size_t>(b)] + j, k(2 * a + i, 2 * b + j));
    }
  }
  for (int j = 0; j < ny; ++j) { // right edge: nodes (nx, j) and (nx, j + 1), length 1/ny
    for (const int node : {(nx + 1) * j + nx, (nx + 1) * (j + 1) + nx}) {
      f(2 * node) += 1.0e5 * 0.5 / ny;
      f(2 * node + 1) += -3.0e5 * 0.5 / ny;
    }
  }
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(triplets.begin(), triplets.end());
  for (int j = 0; j <= ny; ++j) { // fixed: unit rows and columns
    const int node = (nx + 1) * j;
    for (int i = 0; i < 2; ++i) {
      const int dof = 2 * node + i;
      k.prune([dof](int r, int c, double) { return r != dof && c != dof; });
      k.coeffRef(dof, dof) = 1.0;
      f(dof) = 0.0;
    }
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(k);
  const Eigen::VectorXd u = solver.solve(f);
  double largest = u.cwiseAbs().maxCoeff();
  for (int c = 0; c < s.model.n_covers(); ++c) {
    const int node = s.model.covers[static_cast<std::size_t>(c)].node;
    const Point2 moved =
        s.model.covers[static_cast<std::size_t>(c)].position - before[static_cast<std::size_t>(c)];
    EXPECT_NEAR(moved.x(), u(2 * node), 1e-12 * largest) << "node " << node;
    EXPECT_NEAR(moved.y(), u(2 * node + 1), 1e-12 * largest) << "node " << node;
  }
}

class FreeFall : public ::testing::TestWithParam<int> {};

TEST_P(FreeFall, IsExactAfterOneSecond) {
  // A free block of rock under gravity, dt = 1 ms (a usual DDA step): Shi's constant-
  // acceleration step (eq. 2.17) integrates a constant acceleration exactly, so after 1 s
  // the drop is g/2 and the speed g, to rounding: 1e-12 relative after 1000 steps.
  // Why this bound holds: the rounding of the stiffness (K 1 = 0 only to 1e-16 E) enters the
  // rigid motion amplified by kappa = E dt^2 / (rho h^2), here about 50; with dt = 10 ms the
  // same block has kappa = 5000 and drifts by 1e-11 (docs/formulation.md, "Rounding").
  // The step's rounding is carried by the velocity (v1 = 2 d / dt - v0) as a random walk, so
  // its sum depends on the summation order of the BLAS kernels OpenBLAS picks for the CPU.
  // Measured drop errors (2026-11-28, kernels Haswell, Zen, SkylakeX, Sandybridge): order 0
  // 1.3e-12 to 2.8e-12 m (at most 0.57e-12 of the drop), order 1 3.8e-12 to 5.1e-12 m (0.77e-12
  // to 1.04e-12): order-1 covers carry higher modes on the same mesh, a larger kappa. The
  // bound is 1e-12 of the drop for order 0 and 2e-12 for order 1 (it was 1e-12 for both,
  // calibrated on one kernel set; Haswell's and Zen's exceed it by 4% at order 1).
  const double rounding = GetParam() == 0 ? 1e-12 : 2e-12;
  const ElasticMaterial material = elastic(5.0e9, 0.25, 2600.0, PlaneCondition::strain);
  testing::Setup s = make_setup({rectangle("block", 0.0, 0.0, 1.0, 0.5)}, {}, {}, nullptr, 0.21,
                                material, GetParam());
  Scene scene;
  scene.body_loads.push_back({{0.0, -9.81}, {}});
  scene.monitors.push_back({s.model.find_element({0.5, 0.25}, 1e-9), {0.5, 0.25}});
  StepperOptions options;
  options.time_step = 1e-3;
  TimeStepper stepper(s.model, scene, options);
  StepReport last;
  while (stepper.time() < 1.0 - 1e-12)
    last = stepper.step(1.0);
  EXPECT_EQ(last.step, 1000);
  EXPECT_NEAR(stepper.time(), 1.0, 1e-12);
  const MaterialPoint& p = stepper.scene().monitors[0];
  EXPECT_NEAR(p.position.x(), 0.5, 1e-12);
  EXPECT_NEAR(p.position.y(), 0.25 - 0.5 * 9.81, rounding * 4.905);
  EXPECT_NEAR(stepper.velocity_at(p.element, p.position).y(), -9.81, rounding * 9.81);
  const double mass = material.density * 0.5;
  const double kinetic = 0.5 * mass * 9.81 * 9.81;
  EXPECT_NEAR(last.kinetic_energy, kinetic, 2.0 * rounding * kinetic);
  // No stress in free fall; rounding leaves 1e-8 of the weight's scale rho g h.
  for (const ModelElement& e : s.model.elements)
    EXPECT_LT(e.stress.coefficients.col(0).cwiseAbs().maxCoeff(), 1e-8 * 2600.0 * 9.81 * 0.5);
}

INSTANTIATE_TEST_SUITE_P(Orders, FreeFall, ::testing::Values(0, 1));

TEST(RigidVelocity, TurnsEachBlockAboutItsCentroid) {
  // initial_angular_velocity turns a block about its centroid: a 1 x 0.5 plate cut by a
  // math mesh that does not fit it (cut elements are quadrilaterals and pentagons, whose
  // vertex means are not their centroids). The velocity omega J (x - c) is linear, so every
  // cover reproduces it exactly: 1e-12 is rounding.
  const ElasticMaterial material = elastic(5.0e9, 0.25, 2600.0, PlaneCondition::strain);
  testing::Setup s =
      make_setup({rectangle("block", 0.0, 0.0, 1.0, 0.5)}, {}, {}, nullptr, 0.21, material, 1);
  StepperOptions options;
  options.time_step = 1e-3;
  TimeStepper stepper(s.model, Scene{}, options);
  const double omega = 2.0;
  stepper.set_rigid_velocities({Point2(0.0, 0.0)}, {omega});
  for (const Point2& x : {Point2(0.5, 0.25), Point2(1.0, 0.25), Point2(0.1, 0.45)}) {
    const Point2 v = stepper.velocity_at(s.model.find_element(x, 1e-9), x);
    const Point2 expected = omega * Point2(-(x.y() - 0.25), x.x() - 0.5);
    EXPECT_NEAR(v.x(), expected.x(), 1e-12) << x.transpose();
    EXPECT_NEAR(v.y(), expected.y(), 1e-12) << x.transpose();
  }
}

TEST(EnergyCheck, StopsARunWhoseKineticEnergyComesFromNowhere) {
  // A free block, no loads: its kinetic energy is what it starts with, for ever. Started at
  // 2 m/s it keeps that energy (the check must not trip on a run that conserves energy);
  // given 20 m/s behind the stepper's back after the first step (as a contact spring that
  // pushes through a penetration it never had would), the next step has 100 times the
  // energy the run started with and no load did work for it: no cut can cure that, so the
  // step is refused with the fastest cover named (10x the budget is the check's margin).
  const ElasticMaterial material = elastic(5.0e9, 0.25, 2600.0, PlaneCondition::strain);
  testing::Setup s =
      make_setup({rectangle("block", 0.0, 0.0, 1.0, 0.5)}, {}, {}, nullptr, 0.21, material, 0);
  StepperOptions options;
  options.time_step = 1e-3;
  TimeStepper stepper(s.model, Scene{}, options);
  stepper.set_rigid_velocities({Point2(2.0, 0.0)}, {0.0});
  StepReport first;
  for (int i = 0; i < 10; ++i)
    first = stepper.step(1.0);
  const double kinetic = 0.5 * material.density * 0.5 * 4.0;
  EXPECT_NEAR(first.kinetic_energy, kinetic, 1e-9 * kinetic);
  stepper.set_rigid_velocities({Point2(20.0, 0.0)}, {0.0});
  try {
    (void)stepper.step(1.0);
    ADD_FAILURE() << "a step with 100 times the energy of the run was accepted";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("kinetic energy"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("fastest cover (20 m/s)"), std::string::npos) << e.what();
  }
}

TEST(StaticSteps, AStructureInEquilibriumStaysPutStepAfterStep) {
  // A foundation held at its base and sides with a dam on top (two materials, one body),
  // under its weight: after the first static step it is in equilibrium, and every further
  // step under the same load must move it by rounding only. With order-1 covers the held
  // edges give more support rows than a straight edge needs (they cancel only to
  // rounding) and each row corrects its point's drift: the elimination must treat them as
  // dependent, or it divides rounding by rounding (it once moved 2 mm in the second step
  // and diverged). Tolerance 1e-8 m of motion per step: the geometry moved with the first
  // step re-balances by the strain times the settlement (1e-5 x 5e-5 m = 5e-10 m), then by
  // rounding; the failure was 2e-3 m.
  for (const int order : {0, 1}) {
    const ElasticMaterial rock = elastic(1e10, 0.3, 2446.5, PlaneCondition::strain);
    testing::Setup s = make_setup(
        {rectangle("foundation", 0, 0, 12, 5), {"dam", {{{{2, 5}, {6, 5}, {3, 8}, {2, 8}}, {}}}}},
        {line("bottom", {0, 0}, {12, 0}), {"sides", {{{12, 0}, {12, 5}}, {{0, 5}, {0, 0}}}}}, {},
        nullptr, 0.5, rock, order);
    Scene scene;
    scene.supports = curve_support_points(s.model, 0, true, true, SupportMethod::exact, "bottom");
    const std::vector<SupportPoint> sides =
        curve_support_points(s.model, 1, true, false, SupportMethod::exact, "sides");
    scene.supports.insert(scene.supports.end(), sides.begin(), sides.end());
    scene.body_loads.push_back({{0.0, -9.81}, {}});
    StepperOptions options;
    options.integration = TimeIntegration::static_reset;
    TimeStepper stepper(s.model, scene, options);
    const double settlement = stepper.step(1e9).max_displacement;
    EXPECT_GT(settlement, 1e-5);
    double largest = 0.0;
    for (int step = 0; step < 10; ++step)
      largest = std::max(largest, stepper.step(1e9).max_displacement);
    EXPECT_LT(largest, 1e-8) << "order " << order << ", settlement " << settlement;
  }
}

} // namespace
} // namespace nmm
