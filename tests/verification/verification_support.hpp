// SPDX-License-Identifier: MIT
// tests/verification/verification_support.hpp — small builders shared by the verification
// tests: rectangles, regular meshes, materials, and a model + stepper in a few lines.
#pragma once

#include "contact/contact_system.hpp"
#include "manifold/boundary_conditions.hpp"
#include "manifold/model.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"
#include "solver/time_stepper.hpp"

#include "../support/gauss_quadrature.hpp"
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

namespace nmm::testing {

inline MaterialRegion
rectangle(const std::string& name, double x0, double y0, double x1, double y1) {
  return {name, {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}}}};
}

inline NamedCurve line(const std::string& name, Point2 a, Point2 b) { return {name, {{a, b}}}; }

inline ElasticMaterial elastic(double young, double poisson, double density, PlaneCondition plane) {
  ElasticMaterial m;
  m.name = "rock";
  m.young = young;
  m.poisson = poisson;
  m.density = density;
  m.plane = plane;
  return m;
}

/// A constant traction (Pa) on named curve @p curve.
inline CurveLoad traction_load(int curve, Point2 traction) {
  CurveLoad load;
  load.curve = curve;
  load.traction = traction;
  return load;
}

/// Integral over a convex polygon of f (independent of the simplex integration under test).
template <class F> double integrate(const Polygon& polygon, F f) {
  return gauss_fan(polygon, 0, f);
}

/// Energy norm sqrt(∫ s^T D^-1 s) over every element of a stress field s = field(element, x).
template <class Field> double stress_energy_norm(const Model& model, Field field) {
  double total = 0.0;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ModelElement& element = model.elements[static_cast<std::size_t>(e)];
    const Eigen::Matrix3d compliance = elasticity_matrix(model.material_of(e)).inverse();
    for (const Polygon& p : element.polygons) {
      total += integrate(p, [&](const Point2& x) {
        const Eigen::Vector3d s = field(element, x);
        return s.dot(compliance * s);
      });
    }
  }
  return std::sqrt(total);
}

/// Energy norm of the stress error, sqrt(∫ (s - s_h)^T D^-1 (s - s_h)), over every element
/// of a model whose elements hold their stress (one static step from zero stress).
template <class ExactStress> double stress_energy_error(const Model& model, ExactStress exact) {
  return stress_energy_norm(model, [&](const ModelElement& element, const Point2& x) {
    return Eigen::Vector3d(exact(x) - element.stress.at(x));
  });
}

/// The same energy of the exact stress alone, for relative errors.
template <class ExactStress> double stress_energy(const Model& model, ExactStress exact) {
  return stress_energy_norm(
      model, [&](const ModelElement&, const Point2& x) { return Eigen::Vector3d(exact(x)); });
}

/// A math mesh of structured triangles of @p size over [x0, x1] x [y0, y1] (one size beyond
/// on every side), its interior nodes moved off the grid by up to 0.2 size: triangles of
/// every shape and orientation, as a gmsh mesh has, that follow neither the boundary nor
/// the joints.
inline MathMesh irregular_mesh(double x0, double y0, double x1, double y1, double size) {
  const int nx = static_cast<int>(std::ceil((x1 - x0) / size)) + 2;
  const int ny = static_cast<int>(std::ceil((y1 - y0) / size)) + 2;
  MathMesh math;
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      double x = x0 - size + size * i;
      double y = y0 - size + size * j;
      if (i > 0 && i < nx && j > 0 && j < ny) {
        x += 0.2 * size * std::sin(3.1 * i + 7.3 * j);
        y += 0.2 * size * std::cos(5.7 * i - 2.9 * j);
      }
      math.nodes.emplace_back(x, y);
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = (nx + 1) * j + i;
      if ((i + j) % 2 == 0) {
        math.triangles.push_back({a, a + 1, a + nx + 2});
        math.triangles.push_back({a, a + nx + 2, a + nx + 1});
      } else {
        math.triangles.push_back({a, a + 1, a + nx + 1});
        math.triangles.push_back({a + 1, a + nx + 2, a + nx + 1});
      }
    }
  }
  return math;
}

/// Physical mesh + math mesh + cover system + model, ready for a stepper.
struct Setup {
  PhysicalMesh physical;
  MathMesh math;
  CoverSystem covers;
  Model model;
};

/// As make_setup() below, with one material per region; @p kinds gives each region's kind
/// (empty: all NMM; DDA and VEM regions become blocks).
inline Setup make_setup(std::vector<MaterialRegion> regions,
                        std::vector<NamedCurve> curves,
                        std::vector<int> joints,
                        const MathMesh* math,
                        double size,
                        const std::vector<ElasticMaterial>& materials,
                        int order,
                        const std::vector<ElementKind>& kinds = {}) {
  Setup s;
  s.physical.source = "verification";
  s.physical.regions = std::move(regions);
  s.physical.curves = std::move(curves);
  validate_physical_mesh(s.physical);
  s.math =
      math != nullptr ? *math : make_regular_math_mesh(material_bounding_box(s.physical), size);
  CoverMesherOptions mesher;
  for (std::size_t r = 0; r < kinds.size(); ++r) {
    if (kinds[r] != ElementKind::nmm)
      mesher.block_regions.push_back(static_cast<int>(r));
  }
  s.covers = build_cover_system(s.math, s.physical, joints, mesher);
  ModelOptions options;
  options.order = order;
  options.region_kinds = kinds;
  s.model = make_model(s.covers, s.math, materials, options);
  return s;
}

/// Physical mesh + regular math mesh of @p size (or @p math) + cover system + model, one
/// material for every region.
inline Setup make_setup(std::vector<MaterialRegion> regions,
                        std::vector<NamedCurve> curves,
                        std::vector<int> joints,
                        const MathMesh* math,
                        double size,
                        const ElasticMaterial& material,
                        int order,
                        const std::vector<ElementKind>& kinds = {}) {
  const std::size_t n = regions.size();
  return make_setup(std::move(regions), std::move(curves), std::move(joints), math, size,
                    std::vector<ElasticMaterial>(n, material), order, kinds);
}

/// A row of four 1 m blocks cut from one rock (4 m x 1 m) by three joints, on a base 6 m x 1 m
/// under it, far from the origin (corner at (1000, -500)); both regions of @p kind, E =
/// 1e10 Pa, nu = 0, rho = 2500, plane strain, cover size 0.5 m. Every face touches its
/// neighbour at a zero gap.
inline Setup row_of_blocks_on_a_base(ElementKind kind) {
  const Point2 o(1000.0, -500.0);
  std::vector<MaterialRegion> regions{
      rectangle("base", o.x() - 1.0, o.y() - 1.0, o.x() + 5.0, o.y()),
      rectangle("rock", o.x(), o.y(), o.x() + 4.0, o.y() + 1.0)};
  std::vector<NamedCurve> curves;
  std::vector<int> joints;
  for (int k = 1; k < 4; ++k) {
    curves.push_back(line("v" + std::to_string(k), o + Point2(k, 0), o + Point2(k, 1)));
    joints.push_back(static_cast<int>(curves.size()) - 1);
  }
  return make_setup(regions, curves, joints, nullptr, 0.5,
                    elastic(1e10, 0.0, 2500.0, PlaneCondition::strain), 0, {kind, kind});
}

/// A contact system with one strength for every boundary edge; joint faces are bonded when
/// @p bonded (an intact joint holds until its strength is exceeded); augmented-Lagrange
/// passes hold the penetration to @p penetration_tolerance when it is > 0.
inline std::unique_ptr<ContactSystem>
contact_for(const Model& model,
            double penalty,
            const JointStrength& strength,
            bool bonded = false,
            double penetration_tolerance = 0.0,
            std::size_t parallel_min_chunk = ContactOptions{}.parallel_min_chunk) {
  std::vector<std::vector<JointStrength>> strengths;
  std::vector<std::vector<bool>> bonds;
  for (const BoundaryLoop& loop : model.loops) {
    strengths.emplace_back(loop.edges.size(), strength);
    std::vector<bool> b;
    for (const BoundaryEdge& e : loop.edges)
      b.push_back(bonded && e.joint >= 0);
    bonds.push_back(std::move(b));
  }
  ContactOptions options;
  options.penalty = penalty;
  options.spring_length = model.scale;
  options.penetration_tolerance = penetration_tolerance;
  options.parallel_min_chunk = parallel_min_chunk;
  return std::make_unique<ContactSystem>(options, std::move(strengths), std::move(bonds));
}

/// A 1.0 m x 0.5 m block on a 45 degree ramp (a band 0.5 m thick, 8.5 m along the slope,
/// its base held), 6.4 m up the slope so that it stays on the ramp for 1 s even at
/// phi = 15 deg; the block's bottom face is a joint of friction angle phi. It starts at rest
/// in the initial equilibrium (TimeStepper::equilibrate): the analytic solution assumes the
/// full normal force from t = 0, while a block put down on unloaded springs drops into them
/// in the first steps and slides faster meanwhile (by about 0.2% at phi = 40 deg and
/// dt = 1e-3 s, the start error the VEM-DDA paper reports). Distances are measured from the
/// settled position.
struct Incline {
  double phi_degrees = 30.0;
  double dt = 1e-3;
  double penalty_factor = 40.0;
  double young = 1.0e10;
  double penetration_tolerance = 0.0; ///< augmented Lagrange when > 0
  ElementKind block_kind = ElementKind::nmm;
  int order = 0; ///< of the NMM covers (ramp, and block when block_kind is nmm)
  /// StepperOptions::coupled_friction: false cuts a step whose open-close iteration does not
  /// converge at once.
  bool coupled_friction = true;

  struct Result {
    double distance = 0.0; ///< slid along the slope after 1 s
    double exact = 0.0;
    double max_penetration = 0.0;
    double largest_motion = 0.0; ///< largest distance of the block's centre from its start
    int steps = 0;
    long cuts = 0;
    int most_iterations = 0; ///< open-close iterations of the step that took the most
    long augmentations = 0;
    long coupled_tries = 0; ///< steps tried again with friction coupled in the solve
    std::vector<std::string> warnings;
    double max_energy_error = 0.0; ///< StepReport::energy_error, largest over the run
    double dissipated = 0.0;       ///< StepReport::dissipated_energy at the end
  };

  [[nodiscard]] Result run(double duration = 1.0) const {
    const Point2 along(1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0)); // up the slope
    const Point2 up(-1.0 / std::sqrt(2.0), 1.0 / std::sqrt(2.0));   // out of it
    const Point2 a(4.5, 4.5);
    MaterialRegion block{"block", {{{a, a + along, a + along + 0.5 * up, a + 0.5 * up}, {}}}};
    const Point2 down = -0.5 * up; // the band's thickness
    MaterialRegion ramp{"ramp", {{{{0, 0}, down, Point2(6, 6) + down, {6, 6}}, {}}}};
    const ElasticMaterial rock = elastic(young, 0.25, 2500.0, PlaneCondition::strain);
    testing::Setup s = testing::make_setup(
        {ramp, block}, {line("slip", a, a + along), line("base", down, Point2(6, 6) + down)}, {0},
        nullptr, 0.125, rock, order, {ElementKind::nmm, block_kind});
    Scene scene;
    scene.supports = curve_support_points(s.model, 1, true, true, SupportMethod::exact, "base");
    scene.body_loads.push_back({{0.0, -9.81}, {}});
    const Point2 centre = a + 0.5 * along + 0.25 * up;
    scene.monitors.push_back({s.model.find_element(centre, 1e-9), centre});
    StepperOptions options;
    options.time_step = dt;
    options.coupled_friction = coupled_friction;
    const double phi = phi_degrees * std::numbers::pi / 180.0;
    TimeStepper stepper(s.model, scene, options,
                        contact_for(s.model, penalty_factor * young, {phi, 0.0, 0.0}, false,
                                    penetration_tolerance));
    stepper.equilibrate();
    const Point2 start = stepper.scene().monitors[0].position;
    Result r;
    while (stepper.time() < duration - 1e-9) {
      const StepReport report = stepper.step(duration);
      r.max_penetration = std::max(r.max_penetration, stepper.contact_penetration());
      r.largest_motion =
          std::max(r.largest_motion, (stepper.scene().monitors[0].position - start).norm());
      r.steps = static_cast<int>(report.step);
      r.cuts += report.step_cuts;
      r.most_iterations = std::max(r.most_iterations, report.open_close_iterations);
      r.max_energy_error = std::max(r.max_energy_error, report.energy_error);
      r.dissipated = report.dissipated_energy;
    }
    r.distance = -(stepper.scene().monitors[0].position - start).dot(along);
    r.augmentations = stepper.counters().augmentations;
    r.coupled_tries = stepper.counters().coupled_friction_tries;
    r.coupled_tries = stepper.counters().coupled_friction_tries;
    r.warnings = stepper.warnings();
    const double g = 9.81;
    r.exact = std::max(
        0.0, 0.5 * g * duration * duration *
                 (std::sin(std::numbers::pi / 4) - std::tan(phi) * std::cos(std::numbers::pi / 4)));
    return r;
  }
};

/// A b x h block standing on a ramp of angle alpha with friction enough to hold it from
/// sliding (phi = 45 > alpha): it topples when b / h < tan(alpha), its centroid then beyond
/// the downhill corner.
struct Topple {
  double alpha_degrees = 20.0;
  double width = 0.3;
  double height = 1.0;
  int order = 0;
  /// The block's kind (the ramp is NMM), and for an NMM block its material's exact_rotation.
  ElementKind block_kind = ElementKind::nmm;
  bool exact_rotation = false;
  double young = 1e10;     ///< Pa, of block and ramp (the penalty is 40 times it)
  double time_step = 2e-3; ///< s
  double cover_size = 0.1; ///< m, of the regular math mesh
  /// Start from the initial equilibrium (TimeStepper::equilibrate()) instead of unloaded
  /// springs.
  bool equilibrium = false;
  /// Of the last rotation(): the largest kinetic energy of a step over the work of the loads
  /// up to it (the energy of a block that falls over is gravity's work on it).
  mutable double energy_ratio = 0.0;

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
    const ElasticMaterial rock = testing::elastic(young, 0.25, 2500.0, PlaneCondition::strain);
    ElasticMaterial block_rock = rock;
    block_rock.exact_rotation = exact_rotation;
    testing::Setup s = testing::make_setup(
        {ramp, block}, {testing::line("seat", a, b), testing::line("base", down, end + down)}, {0},
        nullptr, cover_size, {rock, block_rock}, order, {ElementKind::nmm, block_kind});
    Scene scene;
    scene.supports = curve_support_points(s.model, 1, true, true, SupportMethod::exact, "base");
    scene.body_loads.push_back({{0.0, -9.81}, {}});
    // Two points of the block on its axis: their line turns with the block.
    const Point2 low = a + 0.5 * width * along + 0.1 * height * up;
    const Point2 high = a + 0.5 * width * along + 0.9 * height * up;
    scene.monitors.push_back({s.model.find_element(low, 1e-9), low});
    scene.monitors.push_back({s.model.find_element(high, 1e-9), high});
    StepperOptions options;
    options.time_step = time_step;
    TimeStepper stepper(
        s.model, scene, options,
        testing::contact_for(s.model, 40.0 * young, {std::numbers::pi / 4, 0.0, 0.0}));
    if (equilibrium)
      (void)stepper.equilibrate();
    const Point2 axis0 =
        stepper.scene().monitors[1].position - stepper.scene().monitors[0].position;
    energy_ratio = 0.0;
    while (stepper.time() < duration - 1e-9) {
      const StepReport report = stepper.step(duration);
      if (report.load_work > 0.0)
        energy_ratio = std::max(energy_ratio, report.kinetic_energy / report.load_work);
    }
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

} // namespace nmm::testing
