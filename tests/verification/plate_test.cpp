// SPDX-License-Identifier: MIT
// Verification of plates against closed forms (issue 4): Kirsch's hole, Griffith's crack
// (a partial joint opening under tension), and a plate cut through by a joint falling apart.
#include "verification_support.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>

namespace nmm {
namespace {

using testing::elastic;
using testing::line;
using testing::make_setup;

const double pi = std::acos(-1.0);

/// Kirsch's stresses around a hole of radius a in an infinite plate under tension s along x
/// (Kirsch 1898; Timoshenko and Goodier art. 35), in Cartesian components.
Eigen::Vector3d kirsch(const Point2& p, double a, double s) {
  const double r2 = p.squaredNorm();
  const double q = a * a / r2;
  const double theta = std::atan2(p.y(), p.x());
  const double c2 = std::cos(2.0 * theta);
  const double s2 = std::sin(2.0 * theta);
  const double rr = s / 2.0 * (1.0 - q) + s / 2.0 * (1.0 - 4.0 * q + 3.0 * q * q) * c2;
  const double tt = s / 2.0 * (1.0 + q) - s / 2.0 * (1.0 + 3.0 * q * q) * c2;
  const double rt = -s / 2.0 * (1.0 + 2.0 * q - 3.0 * q * q) * s2;
  const double c = std::cos(theta);
  const double sn = std::sin(theta);
  return {rr * c * c + tt * sn * sn - 2.0 * rt * sn * c,
          rr * sn * sn + tt * c * c + 2.0 * rt * sn * c,
          (rr - tt) * sn * c + rt * (c * c - sn * sn)};
}

/// Peak hoop stress at the top of the hole over 3 s, on a quarter plate of half-width 5a.
double kirsch_peak_ratio(double size, int order) {
  const double a = 1.0;
  const double half = 5.0;
  const double s = 1.0e6;
  Loop outline{{a, 0.0}, {half, 0.0}, {half, half}, {0.0, half}, {0.0, a}};
  const int arc = 120; // facets of the quarter hole: sagitta 2e-5 a, below what is measured
  for (int k = 1; k < arc; ++k) {
    const double angle = pi / 2.0 * (1.0 - static_cast<double>(k) / arc);
    outline.emplace_back(a * std::cos(angle), a * std::sin(angle));
  }
  testing::Setup setup =
      make_setup({{"plate", {{outline, {}}}}},
                 {line("left", {0.0, a}, {0.0, half}), line("bottom", {a, 0.0}, {half, 0.0}),
                  line("right", {half, 0.0}, {half, half}), line("top", {0.0, half}, {half, half})},
                 {}, nullptr, size, elastic(2.0e10, 0.25, 2500.0, PlaneCondition::stress), order);
  Scene scene;
  scene.supports = curve_support_points(setup.model, 0, true, false, SupportMethod::exact, "left");
  auto bottom = curve_support_points(setup.model, 1, false, true, SupportMethod::exact, "bottom");
  scene.supports.insert(scene.supports.end(), bottom.begin(), bottom.end());
  CurveLoad right;
  right.curve = 2;
  right.traction_at = [&](const Point2& x) {
    const Eigen::Vector3d t = kirsch(x, a, s);
    return Point2(t(0), t(2));
  };
  CurveLoad top;
  top.curve = 3;
  top.traction_at = [&](const Point2& x) {
    const Eigen::Vector3d t = kirsch(x, a, s);
    return Point2(t(2), t(1));
  };
  scene.curve_loads = {right, top};
  const Point2 peak(0.0, a);
  const int element = setup.model.find_element(peak, 1e-9);
  const Point2 origin = setup.model.elements[static_cast<std::size_t>(element)].stress.origin;
  StepperOptions options;
  options.integration = TimeIntegration::static_reset;
  TimeStepper stepper(setup.model, scene, options);
  (void)stepper.step(1.0);
  // Evaluated in the reference geometry (the field is attached to the moved element).
  LinearField3 stress = setup.model.elements[static_cast<std::size_t>(element)].stress;
  stress.origin = origin;
  return stress.at(peak)(0) / (3.0 * s);
}

TEST(Kirsch, PeakHoopStressConvergesToThreeTimesTheTension) {
  // Exact Kirsch tractions on the outer edges of a quarter plate, symmetry on the axes: the
  // exact solution is Kirsch's. Order-1 covers, stress read at the hole's top from the
  // element's linear stress. Issue 4: within 0.5% of 3 s on the finest mesh reported.
  std::vector<double> errors;
  for (const double size : {0.2, 0.1, 0.05}) {
    const double ratio = kirsch_peak_ratio(size, 1);
    errors.push_back(std::abs(ratio - 1.0));
    std::printf("Kirsch, order 1, size %.3f a: peak hoop stress %.5f x 3s (error %.3f%%)\n", size,
                ratio, 100.0 * errors.back());
  }
  EXPECT_LT(errors.back(), 5e-3);
  // Converging at second order (measured rates 1.9 and 2.3 for the two halvings); a rate
  // below 1.5 means an order of the linear covers was lost.
  EXPECT_GT(std::log2(errors[0] / errors[1]), 1.5);
  EXPECT_GT(std::log2(errors[1] / errors[2]), 1.5);
}

/// Westergaard's solution of Griffith's crack of half-length a under equal tension s at
/// infinity, plane strain: displacement (Irwin's form of the Westergaard function
/// Z = s z / sqrt(z² - a²)).
Point2 griffith_displacement(const Point2& p, double a, double s, const ElasticMaterial& m) {
  using C = std::complex<double>;
  const C z(p.x(), p.y());
  const C root = std::sqrt(z - a) * std::sqrt(z + a); // cut along the crack only
  const C zbar = s * root;
  const C zeta = s * z / root;
  const double mu = m.young / (2.0 * (1.0 + m.poisson));
  const double kappa = 3.0 - 4.0 * m.poisson;
  return {((kappa - 1.0) / 2.0 * zbar.real() - p.y() * zeta.imag()) / (2.0 * mu),
          ((kappa + 1.0) / 2.0 * zbar.imag() - p.y() * zeta.real()) / (2.0 * mu)};
}

/// Westergaard's stresses for the same crack: sxx = Re Z - y Im Z', syy = Re Z + y Im Z',
/// sxy = -y Re Z', with Z' = -s a² / (z² - a²)^(3/2).
Eigen::Vector3d griffith_stress(const Point2& p, double a, double s) {
  using C = std::complex<double>;
  const C z(p.x(), p.y());
  const C root = std::sqrt(z - a) * std::sqrt(z + a);
  const C zeta = s * z / root;
  const C derivative = -s * a * a / (root * root * root);
  return {zeta.real() - p.y() * derivative.imag(), zeta.real() + p.y() * derivative.imag(),
          -p.y() * derivative.real()};
}

struct CrackOpening {
  double centre = 0.0;  ///< relative error of the opening at the crack centre
  double quarter = 0.0; ///< relative error at x = a/2
};

CrackOpening griffith(double size, int order) {
  const double a = 1.0;
  const double half = 4.0;
  const double s = 1.0e6;
  const ElasticMaterial material = elastic(1.0e10, 0.25, 2500.0, PlaneCondition::strain);
  testing::Setup setup = make_setup(
      {testing::rectangle("plate", -half, -half, half, half)},
      {line("crack", {-a, 0.0}, {a, 0.0}), line("bottom", {-half, -half}, {half, -half}),
       line("right", {half, -half}, {half, half}), line("top", {half, half}, {-half, half}),
       line("left", {-half, half}, {-half, -half})},
      {0}, nullptr, size, material, order);
  // Westergaard's tractions on the four edges (outward normals), and the three rigid
  // motions held by exact values at two points of the symmetry axis x = 0.
  Scene scene;
  const std::array<Point2, 4> normals{Point2(0.0, -1.0), Point2(1.0, 0.0), Point2(0.0, 1.0),
                                      Point2(-1.0, 0.0)};
  for (int c = 1; c <= 4; ++c) {
    CurveLoad edge;
    edge.curve = c;
    const Point2 n = normals[static_cast<std::size_t>(c - 1)];
    edge.traction_at = [n, a, s](const Point2& x) {
      const Eigen::Vector3d t = griffith_stress(x, a, s);
      return Point2(t(0) * n.x() + t(2) * n.y(), t(2) * n.x() + t(1) * n.y());
    };
    scene.curve_loads.push_back(edge);
  }
  for (const double y : {-half, half}) {
    SupportPoint pin;
    pin.point = {setup.model.find_element({0.0, y}, 1e-9), Point2(0.0, y)};
    pin.start = pin.point.position;
    pin.fix_x = true;
    pin.fix_y = y < 0.0;
    pin.displacement = griffith_displacement(pin.point.position, a, s, material);
    pin.origin = "pin";
    scene.supports.push_back(pin);
  }
  // The two faces at x = 0 and x = a/2: material points just above and below the joint.
  for (const double x : {0.0, a / 2.0}) {
    for (const double side : {1.0, -1.0}) {
      const Point2 near(x, side * 1e-9);
      scene.monitors.push_back({setup.model.find_element(near, 1e-6), Point2(x, 0.0)});
    }
  }

  StepperOptions options;
  options.integration = TimeIntegration::static_reset;
  TimeStepper stepper(setup.model, scene, options);
  (void)stepper.step(1.0);
  const auto& m = stepper.scene().monitors;
  auto opening = [&](int k) {
    return (m[static_cast<std::size_t>(k)].position - m[static_cast<std::size_t>(k + 1)].position)
        .y();
  };
  // Griffith: COD(x) = 4 (1 - nu²) s / E sqrt(a² - x²).
  auto exact = [&](double x) {
    return 4.0 * (1.0 - material.poisson * material.poisson) * s / material.young *
           std::sqrt(a * a - x * x);
  };

  return {std::abs(opening(0) / exact(0.0) - 1.0), std::abs(opening(2) / exact(a / 2.0) - 1.0)};
}

TEST(Griffith, PartialJointOpeningConvergesToTheGriffithProfile) {
  // A joint of length 2a inside a plate loaded by Westergaard's exact tractions: the crack
  // faces are boundaries of one block (a slit), so the crack opens under the tension.
  // The covers of the triangle holding a crack tip are not split (Shi 1997, Figure 4.2), so the
  // crack can open only up to the last math edge it crosses: it acts up to one element
  // shorter, and the opening converges at first order in h (measured: 36%, 19%, 6.9% for
  // order 0 and 25%, 15%, 4.4% for order 1 at the centre). Checked: the error falls at
  // least like h^0.7 between refinements at both stations, and the finest mesh is within
  // 8% (order 0) and 5% (order 1). Tip enrichment would remove this (docs/formulation.md).
  for (const int order : {0, 1}) {
    std::vector<CrackOpening> errors;
    for (const double size : {0.4, 0.2, 0.1}) {
      errors.push_back(griffith(size, order));
      std::printf("Griffith, order %d, size %.2f a: opening error %.2f%% at the centre, %.2f%% "
                  "at a/2\n",
                  order, size, 100.0 * errors.back().centre, 100.0 * errors.back().quarter);
    }
    for (std::size_t i = 1; i < errors.size(); ++i) {
      EXPECT_LT(errors[i].centre, std::pow(0.5, 0.7) * errors[i - 1].centre) << "order " << order;
      EXPECT_LT(errors[i].quarter, std::pow(0.5, 0.7) * errors[i - 1].quarter) << "order " << order;
    }
    EXPECT_LT(errors[2].centre, order == 0 ? 0.08 : 0.05) << "order " << order;
  }
}

TEST(JointedPlate, APlateCutThroughFallsApartIntoTwoIndependentBodies) {
  // A joint crossing the plate completely: two blocks with no cover in common. The upper
  // block is given a velocity, the lower one none; without gravity and contact (they move
  // apart), after 0.2 s the upper block has moved 0.2 m and the lower one not at all.
  testing::Setup setup = make_setup({testing::rectangle("rock", 0.0, 0.0, 2.0, 2.0)},
                                    {line("joint", {0.0, 0.9}, {2.0, 1.1})}, {0}, nullptr, 0.3,
                                    elastic(1.0e9, 0.25, 2500.0, PlaneCondition::strain), 0);
  ASSERT_EQ(setup.covers.n_blocks(), 2);
  Scene scene;
  const Point2 upper(1.0, 1.6);
  const Point2 lower(1.0, 0.4);
  scene.monitors.push_back({setup.model.find_element(upper, 1e-9), upper});
  scene.monitors.push_back({setup.model.find_element(lower, 1e-9), lower});
  const int upper_block =
      setup.model.elements[static_cast<std::size_t>(scene.monitors[0].element)].block;
  std::vector<Point2> velocity(2, Point2::Zero());
  velocity[static_cast<std::size_t>(upper_block)] = Point2(0.0, 1.0);
  StepperOptions options;
  options.time_step = 0.01;
  TimeStepper stepper(setup.model, scene, options);
  stepper.set_rigid_velocities(velocity, {0.0, 0.0});
  for (int i = 0; i < 20; ++i)
    (void)stepper.step(1.0);
  const auto& m = stepper.scene().monitors;
  EXPECT_NEAR((m[0].position - upper - Point2(0.0, 0.2)).norm(), 0.0, 1e-12);
  EXPECT_EQ(m[1].position, lower);
}

} // namespace
} // namespace nmm
