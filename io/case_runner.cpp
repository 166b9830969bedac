// SPDX-License-Identifier: MIT
#include "io/case_runner.hpp"

#include "contact/joint_law.hpp"
#include "io/atomic_file.hpp"
#include "io/block_results.hpp"
#include "io/case_names.hpp"
#include "io/checkpoint.hpp"
#include "io/cover_warnings.hpp"
#include "io/gmsh_reader.hpp"
#include "io/joint_sets.hpp"
#include "io/step_output.hpp"
#include "io/text.hpp"
#include "io/vtk_writer.hpp"
#include "manifold/boundary_conditions.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/error.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <optional>
#include <regex>
#include <set>
#include <sstream>
#include <system_error>
#include <utility>

namespace nmm {

namespace {

using namespace case_names;
namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

std::size_t at(int i) { return static_cast<std::size_t>(i); }

ElasticMaterial elastic_material(const MaterialSpec& spec) {
  ElasticMaterial m;
  m.name = spec.name;
  m.young = spec.young;
  m.poisson = spec.poisson;
  m.density = spec.density;
  m.plane = spec.plane;
  m.thickness = spec.thickness;
  m.initial_stress = spec.initial_stress;
  m.initial_stress_gradient = spec.initial_stress_gradient;
  m.initial_stress_surface = spec.initial_stress_surface;
  m.exact_rotation = spec.exact_rotation;
  return m;
}

/// Peak memory (bytes) of an nmm model on a math mesh of @p triangles, covers of @p order.
/// 60 MB of program and libraries plus k n log2(n) / log2(2e4), since a nested-dissection
/// factor of a planar mesh fills like n log n; k fitted to the peak resident memory of one
/// static step of examples/01 at 2e4 and 7e4 triangles, orders 0 and 1, so that it errs on
/// the high side (docs/case-file.md, "Checks across tables and warnings").
double memory_estimate(double triangles, int order) {
  const double per_triangle = order == 0 ? 2.9e3 : 9.5e3;
  const double n = std::max(triangles, 2.0);
  return 60e6 + per_triangle * n * std::log2(n) / std::log2(2e4);
}

/// The memory an nmm run may use: NMM_MEMORY_LIMIT (bytes) when set, else the machine's.
std::pair<double, std::string> memory_available() {
  if (const char* limit = std::getenv("NMM_MEMORY_LIMIT")) {
    char* end = nullptr;
    const double bytes = std::strtod(limit, &end);
    if (end != limit && *end == '\0' && bytes > 0.0 && std::isfinite(bytes))
      return {bytes, "the NMM_MEMORY_LIMIT of"};
  }
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page <= 0)
    return {std::numeric_limits<double>::infinity(), ""};
  return {static_cast<double>(pages) * static_cast<double>(page), "the memory of this machine,"};
}

/// Refuses a math mesh whose nmm model would not fit in memory, before it is built.
void refuse_if_too_large(const CaseSpec& spec, double triangles) {
  const bool has_nmm =
      std::any_of(spec.materials.begin(), spec.materials.end(),
                  [](const MaterialSpec& m) { return m.model == MaterialModel::nmm; });
  if (!has_nmm)
    return; // dda and vem blocks do not use the math mesh beyond the cut
  const int order = spec.cover_mesh.order;
  const double need = memory_estimate(triangles, order);
  const auto [have, whose] = memory_available();
  if (need <= have)
    return;
  // The triangles that fit (the estimate grows with n), and the size that gives them: the
  // number of triangles goes as 1 / size^2.
  double fit = triangles;
  while (fit > 2.0 && memory_estimate(fit, order) > 0.8 * have)
    fit *= 0.9;
  const double size = spec.cover_mesh.size * std::sqrt(triangles / fit);
  fail(spec, spec.cover_mesh.size_line,
       "[cover_mesh] size = " + number_text(spec.cover_mesh.size) + " m makes " +
           number_text(triangles, 3) + " math triangles; an order-" + std::to_string(order) +
           " nmm model of that size needs about " + number_text(need / 1e9, 3) +
           " GB of memory, more than " + whose + " " + number_text(have / 1e9, 3) +
           " GB; use size = " + number_text(size, 3) + " m or more" +
           (order == 1 ? " (or order = 0, a third of the memory)" : ""));
}

/// Beyond this strain (a load's stress over Young's modulus, a velocity over the wave speed)
/// a case means nothing in small-strain elasticity, whose validity ends far below 1: the
/// displacements are many times the model's size, supports and contacts are torn apart and
/// the step equations lose every digit or overflow (a point force of 1e20 N on a 2 m plate
/// of 1 GPa ended, after writing its first step, in "contradictory supports").
constexpr double largest_strain = 1e3;

/// What every refusal of refuse_values_beyond_the_model() ends with.
std::string not_finite_in_model_units(std::string_view unit) {
  return ", which is not finite in the model's units: beyond a strain of " +
         number_text(largest_strain) +
         " the displacements are many times the model's size and the step equations lose "
         "every digit or overflow double precision; check the value and its unit (" +
         std::string(unit) + ", SI)";
}

/// The largest component of a material's initial stress in the model's box: an [in_situ]
/// field, linear in y, is largest at the box's top or bottom.
double largest_initial_stress(const MaterialSpec& m, const BoundingBox& box) {
  double stress = m.initial_stress.cwiseAbs().maxCoeff();
  if (!m.initial_stress_gradient.isZero() && !box.is_empty()) {
    const ElasticMaterial material = elastic_material(m);
    for (const double y : {box.min.y(), box.max.y()})
      stress = std::max(stress, material.initial_stress_at(y).cwiseAbs().maxCoeff());
  }
  return stress;
}

/// Refuses loads and initial states that the model cannot represent: each is turned into the
/// strain it gives the model of size @p size (m), against Young's modulus of the material
/// it acts on (the largest one when it acts on all), and must stay below largest_strain. The
/// case-file reader has already refused every number beyond 1e100, so these products are
/// finite.
void refuse_values_beyond_the_model(const CaseSpec& spec, const BoundingBox& box, double size) {
  double largest_young = 0.0;
  double thickness = 0.0;
  const MaterialSpec* stiffest = nullptr;
  for (const MaterialSpec& m : spec.materials) {
    if (m.young > largest_young) {
      largest_young = m.young;
      stiffest = &m;
    }
    thickness = std::max(thickness, m.thickness);
  }
  if (stiffest == nullptr)
    return;
  const auto against = [](const MaterialSpec& m) {
    return "Young's modulus " + number_text(m.young) + " Pa of material " + in_quotes(m.name);
  };
  for (const LoadSpec& load : spec.loads) {
    const double magnitude = load.vector.norm();
    switch (load.kind) {
    case LoadKind::gravity:
      for (const MaterialSpec& m : spec.materials) {
        const double stress = m.density * magnitude * size;
        if (stress / m.young > largest_strain)
          fail(spec, load.line,
               "[[load]] gravity = " + point_text(load.vector, 4) + " m/s^2 weighs on material " +
                   in_quotes(m.name) + " (density " + number_text(m.density) +
                   " kg/m^3) with about density x gravity x model size = " + number_text(stress) +
                   " Pa over the model's size " + number_text(size) + " m, a strain of " +
                   number_text(stress / m.young) + " against its Young's modulus " +
                   number_text(m.young) + " Pa" +
                   not_finite_in_model_units("m/s^2; Earth's is 9.81"));
      }
      break;
    case LoadKind::point: {
      const double stress = magnitude / (size * thickness);
      if (stress / largest_young > largest_strain)
        fail(spec, load.line,
             "[[load]] force = " + point_text(load.vector, 4) + " N at point " +
                 in_quotes(load.target) + " spread over the model's size " + number_text(size) +
                 " m is a stress of " + number_text(stress) + " Pa, a strain of " +
                 number_text(stress / largest_young) + " against the largest " +
                 against(*stiffest) + not_finite_in_model_units("N"));
      break;
    }
    case LoadKind::traction:
      if (magnitude / largest_young > largest_strain)
        fail(spec, load.line,
             "[[load]] traction = " + point_text(load.vector, 4) + " Pa on curve " +
                 in_quotes(load.target) + " is a strain of " +
                 number_text(magnitude / largest_young) + " against the largest " +
                 against(*stiffest) + not_finite_in_model_units("Pa"));
      break;
    case LoadKind::pressure: {
      double pressure = std::abs(load.pressure);
      if (load.water_level && !box.is_empty())
        pressure += load.water_unit_weight * std::max(0.0, *load.water_level - box.min.y());
      if (pressure / largest_young > largest_strain)
        fail(spec, load.line,
             "[[load]] on curve " + in_quotes(load.target) + ": its pressure" +
                 (load.water_level ? " (with the water's at the model's lowest point)"
                                   : std::string()) +
                 " of " + number_text(pressure) + " Pa is a strain of " +
                 number_text(pressure / largest_young) + " against the largest " +
                 against(*stiffest) +
                 not_finite_in_model_units(load.water_level ? "Pa, m and N/m^3" : "Pa"));
      break;
    }
    }
  }
  const bool dynamic = spec.analysis.kind == AnalysisKind::dynamic;
  for (const MaterialSpec& m : spec.materials) {
    const double stress = largest_initial_stress(m, box);
    if (stress / m.young > largest_strain)
      fail(spec, spec.in_situ ? spec.in_situ->line : m.line,
           (spec.in_situ ? "[in_situ] stress in material " + in_quotes(m.name)
                         : "[materials." + m.name + "] initial_stress") +
               " of " + number_text(stress) + " Pa is a strain of " +
               number_text(stress / m.young) + " against its Young's modulus " +
               number_text(m.young) + " Pa" + not_finite_in_model_units("Pa"));
    if (!dynamic || !(m.density > 0.0))
      continue; // a static analysis discards initial velocities
    // A body moving at v strains what it hits by v / c (c the wave speed, sqrt(E / rho)).
    const double wave_speed = std::sqrt(m.young / m.density);
    const double speed =
        std::max(m.initial_velocity.norm(), std::abs(m.initial_angular_velocity) * size);
    if (speed / wave_speed > largest_strain)
      fail(spec, m.line,
           "[materials." + m.name + "] " +
               (m.initial_velocity.norm() >= std::abs(m.initial_angular_velocity) * size
                    ? "initial_velocity = " + point_text(m.initial_velocity, 4) + " m/s"
                    : "initial_angular_velocity = " + number_text(m.initial_angular_velocity) +
                          " rad/s over the model's size " + number_text(size) + " m") +
               " is " + number_text(speed / wave_speed) +
               " times the speed of its elastic waves (sqrt(young / density) = " +
               number_text(wave_speed) + " m/s), the strain of an impact at that speed" +
               not_finite_in_model_units("m/s, rad/s"));
  }
}

/// Digits of a position spent on the model's distance from the origin from which that is
/// warned about: the displacements then keep 7 digits at most.
constexpr double lost_digits_warning = 6.0;

/// Below this fraction of the time an elastic wave takes to cross a math triangle, the
/// inertia term of the step equations (Shi's M 2 / dt^2 on the diagonal) exceeds the
/// stiffness by more than 1e16, double precision's digits: the elasticity is lost (and near
/// 1e-300 s the term overflows: "the step displacement is not finite").
constexpr double shortest_time_step_fraction = 1e-8;

/// Refuses a fixed `time_step` so short that the step equations lose the stiffness, when
/// the step equations have inertia (a dynamic analysis, or a static one with contact).
void refuse_too_short_time_step(const CaseSpec& spec, bool has_inertia) {
  if (!spec.analysis.time_step || !has_inertia)
    return;
  const double dt = *spec.analysis.time_step;
  const double size = spec.cover_mesh.size;
  const MaterialSpec* slowest = nullptr;
  double transit = 0.0;
  for (const MaterialSpec& m : spec.materials) {
    if (!(m.density > 0.0))
      continue;
    const double t = size * std::sqrt(m.density / m.young);
    if (t > transit) {
      transit = t;
      slowest = &m;
    }
  }
  if (slowest == nullptr || dt >= shortest_time_step_fraction * transit)
    return;
  fail(spec, spec.analysis.time_step_line,
       "[analysis] time_step = " + number_text(dt) +
           " s is far shorter than the model needs: an elastic wave crosses one math triangle "
           "([cover_mesh] size = " +
           number_text(size) + " m) of material " + in_quotes(slowest->name) + " in " +
           number_text(transit) + " s (size x sqrt(density / young)), and in a step shorter than " +
           number_text(shortest_time_step_fraction) +
           " of that the inertia of the step equations (mass x 2 / time_step^2) is more than "
           "1e16 times the stiffness: double precision loses the elasticity, or overflows; "
           "use time_step = \"auto\" or at least " +
           number_text(shortest_time_step_fraction * transit) + " s (a step of 0.1 to 1 times " +
           number_text(transit) + " s resolves the waves)");
}

} // namespace

// ------------------------------------------------------------------------------------------
// Geometry

CaseGeometry build_case_geometry(const CaseSpec& spec, const PhaseCallback& on_phase) {
  const auto phase = [&](const std::string& text) {
    if (on_phase)
      on_phase(text);
  };
  CaseGeometry g;
  // One gmsh session for the physical mesh and a gmsh math mesh (saves the start-up).
  std::optional<GmshSession> session;
  if (!GmshSession::is_alive())
    session.emplace();
  GeometryReadOptions read_options;
  read_options.curve_tolerance = spec.cover_mesh.curve_tolerance;
  read_options.cover_size = spec.cover_mesh.size;
  // A .geo is a program: one that loops or grows without end is stopped at these limits.
  read_options.time_limit = spec.geometry_time_limit;
  if (const double memory = memory_available().first; std::isfinite(memory))
    read_options.memory_limit = memory;

  phase("reading " + spec.geometry.string());
  Clock::time_point start = Clock::now();
  g.physical = read_physical_mesh(spec.geometry, read_options);
  add_joint_sets(spec, g.physical); // [[joint_set]] joints, then like drawn Physical Curves
  g.seconds_geometry = seconds_since(start);

  // Every [materials.X] a region, every region a material.
  g.region_material.assign(g.physical.regions.size(), -1);
  for (std::size_t m = 0; m < spec.materials.size(); ++m) {
    const MaterialSpec& material = spec.materials[m];
    const int region = g.physical.find_region(material.name);
    if (region < 0) {
      fail(spec, material.line,
           unknown_name(spec, g.physical, "material " + in_quotes(material.name), material.name,
                        "Physical Surface", g.physical.regions, g.physical.region_names(),
                        "materials are Physical Surfaces: rename [materials." + material.name +
                            "] after one of them"));
    }
    g.region_material[at(region)] = static_cast<int>(m);
  }
  for (std::size_t r = 0; r < g.physical.regions.size(); ++r) {
    if (g.region_material[r] < 0) {
      const std::string& name = g.physical.regions[r].name;
      fail(spec, 0,
           "Physical Surface " + in_quotes(name) + " of " + geometry_name(spec) +
               " has no material; add a [materials." + name +
               "] table (young, poisson, density) to the case file, or remove the surface "
               "from the Physical Surfaces of " +
               geometry_name(spec));
    }
  }
  // Every [joints.X] a curve.
  for (const JointSpec& joint : spec.joints) {
    const int curve = g.physical.find_curve(joint.name);
    if (curve < 0) {
      fail(spec, joint.line,
           unknown_name(spec, g.physical, "joint " + in_quotes(joint.name), joint.name,
                        "Physical Curve", g.physical.curves, g.physical.curve_names(),
                        "joints are Physical Curves: rename [joints." + joint.name +
                            "] after one of them"));
    }
    g.joint_curves.push_back(curve);
  }

  start = Clock::now();
  if (spec.cover_mesh.kind == CoverMeshKind::regular) {
    g.math = make_regular_math_mesh(material_bounding_box(g.physical), spec.cover_mesh.size,
                                    static_cast<double>(spec.cover_mesh.max_triangles));
  } else {
    phase("meshing " + geometry_name(spec) + " with gmsh");
    g.math = make_gmsh_math_mesh(spec.geometry, g.physical, spec.cover_mesh.size,
                                 static_cast<double>(spec.cover_mesh.max_triangles),
                                 spec.cover_mesh.geometry_sizes);
  }
  g.seconds_math_mesh = seconds_since(start);
  refuse_if_too_large(spec, static_cast<double>(g.math.n_triangles()));
  phase("math mesh: " + std::to_string(g.math.n_triangles()) + " triangles, " +
        std::to_string(g.math.n_nodes()) + " nodes");

  CoverMesherOptions mesher;
  mesher.min_cover_area_ratio = spec.cover_mesh.min_cover_area_ratio;
  for (std::size_t r = 0; r < g.physical.regions.size(); ++r) {
    if (spec.materials[at(g.region_material[r])].model != MaterialModel::nmm)
      mesher.block_regions.push_back(static_cast<int>(r));
  }
  start = Clock::now();
  g.covers = build_cover_system(g.math, g.physical, g.joint_curves, mesher);
  g.seconds_covers = seconds_since(start);
  std::ostringstream done;
  done.precision(3);
  done << "cover system: " << g.covers.n_covers() << " covers, " << g.covers.n_elements()
       << " elements, " << g.covers.n_blocks() << (g.covers.n_blocks() == 1 ? " block" : " blocks")
       << " (" << g.seconds_covers << " s)";
  phase(done.str());
  return g;
}

// ------------------------------------------------------------------------------------------
// The analysis

CaseAnalysis::CaseAnalysis(CaseSpec spec, const PhaseCallback& on_phase, double strength_factor)
    : spec_(std::move(spec)), strength_factor_(strength_factor) {
  geometry_ = build_case_geometry(spec_, on_phase);
  const PhysicalMesh& physical = geometry_.physical;
  warnings_ = spec_.warnings;
  for (std::string& w : cover_system_warnings(spec_, geometry_))
    warnings_.push_back(std::move(w));

  std::vector<ElasticMaterial> materials;
  materials.reserve(physical.regions.size());
  for (const int m : geometry_.region_material)
    materials.push_back(elastic_material(spec_.materials[at(m)]));
  ModelOptions model_options;
  model_options.order = spec_.cover_mesh.order;
  for (const int m : geometry_.region_material) {
    const MaterialModel kind = spec_.materials[at(m)].model;
    model_options.region_kinds.push_back(kind == MaterialModel::dda   ? ElementKind::dda
                                         : kind == MaterialModel::vem ? ElementKind::vem
                                                                      : ElementKind::nmm);
  }
  model_ = make_model(geometry_.covers, geometry_.math, std::move(materials), model_options);

  const BoundingBox box = material_bounding_box(physical);
  const double size = box.is_empty() ? 1.0 : std::max(box.size().x(), box.size().y());
  const double tolerance = 1e-9 * size;
  model_size_ = size;
  refuse_values_beyond_the_model(spec_, box, size);
  add_scale_warnings(box, size);
  add_unused_curve_warnings();

  refuse_bad_excavations();
  Scene scene = stage_scene(0, 0.0);
  for (const Bolt& bolt : scene.bolts)
    bolt_names_.push_back(bolt.name);
  // The later stages' supports, loads and bolts, checked now (before anything is written):
  // they are placed again when their stage starts, where the material is then.
  for (int k = 1; k < static_cast<int>(spec_.stages.size()); ++k) {
    for (const Bolt& bolt : stage_scene(k, 0.0).bolts)
      bolt_names_.push_back(bolt.name);
  }
  // Monitors.
  for (const MonitorSpec& monitor : spec_.monitors) {
    const int element = model_.find_element(monitor.point, tolerance);
    if (element < 0) {
      fail(spec_, monitor.line,
           "[[monitor]] " + in_quotes(monitor.name) + ": the point " + point_text(monitor.point) +
               " lies outside the material of " + geometry_name(spec_) +
               "; give a point inside a Physical Surface or on its boundary");
    }
    scene.monitors.push_back({element, monitor.point});
    monitor_starts_.push_back(monitor.point);
  }

  // A static analysis needs every body held (the stepper checks it too, without the line);
  // with contact, bodies may rest on each other (Shi's static keeps the inertia term).
  const bool dynamic = spec_.analysis.kind == AnalysisKind::dynamic;
  const bool touching = ContactSystem::can_touch(model_);
  // Shi's static analysis keeps the inertia term when there is contact.
  refuse_too_short_time_step(spec_, dynamic || touching);
  if (!dynamic && !touching) {
    std::set<int> held;
    for (const SupportPoint& s : scene.supports)
      held.insert(model_.elements[at(s.point.element)].block);
    for (const ModelElement& element : model_.elements) {
      if (held.count(element.block) != 0)
        continue;
      const MaterialSpec& material =
          spec_.materials[at(geometry_.region_material[at(element.material)])];
      fail(spec_, material.line,
           "the body of material " + in_quotes(material.name) + " containing " +
               point_text(element.polygons.front().outer.front()) +
               " is held by no [[boundary]] support, and a static analysis has no inertia to "
               "keep it from moving freely; add a [[boundary]] on a curve or point of this "
               "body, or use [analysis] kind = \"dynamic\"");
    }
  }

  StepperOptions options;
  options.integration = dynamic ? TimeIntegration::dynamic : TimeIntegration::static_reset;
  options.time_step = spec_.analysis.time_step;
  options.max_step_displacement = spec_.analysis.max_step_displacement;
  double largest_young = 0.0;
  for (const ElasticMaterial& m : model_.materials)
    largest_young = std::max(largest_young, m.young);
  options.spring_stiffness =
      spec_.analysis.penalty_stiffness.value_or(spec_.analysis.penalty * largest_young);
  options.max_step_cuts = spec_.analysis.max_step_cuts;
  options.energy_tolerance = spec_.analysis.energy_tolerance;
  options.energy_error_limit = spec_.analysis.energy_error_limit;
  options.velocity_ratio = spec_.analysis.velocity_ratio;
  options.open_close_max = spec_.analysis.open_close_max;
  options.static_chatter_slides = spec_.analysis.static_chatter_slides;
  if (spec_.analysis.solver == LinearSolverKind::pcg)
    options.conjugate_gradients = PcgOptions{.tolerance = spec_.analysis.pcg_tolerance,
                                             .loose_tolerance = spec_.analysis.pcg_mode_tolerance};
  std::unique_ptr<ContactSystem> contact;
  if (touching)
    contact = make_contact_system(options.spring_stiffness);
  stepper_ = std::make_unique<TimeStepper>(model_, std::move(scene), options, std::move(contact));

  // Initial velocities: each block takes those of its first material.
  if (dynamic) {
    std::vector<Point2> velocity(model_.blocks.size(), Point2::Zero());
    std::vector<double> angular(model_.blocks.size(), 0.0);
    bool moving = false;
    for (std::size_t b = 0; b < model_.blocks.size(); ++b) {
      const Block& block = model_.blocks[b];
      if (block.materials.empty())
        continue;
      const MaterialSpec& material =
          spec_.materials[at(geometry_.region_material[at(block.materials.front())])];
      velocity[b] = material.initial_velocity;
      angular[b] = material.initial_angular_velocity;
      moving = moving || !velocity[b].isZero() || angular[b] != 0.0;
    }
    if (moving)
      stepper_->set_rigid_velocities(velocity, angular);
  }
}

CaseAnalysis::~CaseAnalysis() = default;

void CaseAnalysis::add_scale_warnings(const BoundingBox& box, double model_size) {
  const auto warn = [&](int line, const std::string& message) {
    warnings_.push_back(spec_.file.string() + ":" + std::to_string(line) + ": " + message);
  };
  // Positions are doubles: a model at distance d from the origin holds them to 1e-16 d, so
  // log10(d / size) of double's 16 digits are spent on where the model is, and a step's
  // motion or an elastic displacement, 1e-3 of the size or less, keeps the rest minus 3
  // (a 2 m plate at x = 1e15 m came out 1.5% off).
  if (!box.is_empty() && model_size > 0.0) {
    const Point2 centre = 0.5 * (box.min + box.max);
    const double distance = centre.norm();
    const double lost = std::log10(distance / model_size);
    if (lost >= lost_digits_warning) {
      warnings_.push_back(
          geometry_name(spec_) + ": the model lies " + number_text(distance, 3) +
          " m from the origin, " + number_text(distance / model_size, 3) + " times its size (" +
          number_text(model_size, 3) + " m): its coordinates spend " + number_text(lost, 2) +
          " of double precision's 16 significant digits on where it is, leaving the "
          "displacements (a step's motion is 1e-3 of the size or less) about " +
          number_text(std::max(0.0, 16.0 - lost - 3.0), 2) +
          "; move the geometry near the origin (subtract " + point_text(centre) +
          " from its coordinates, and from the monitors' points)");
    }
  }
  // A fixed time step longer than Shi's step for max_step_displacement (report 8.5 with the
  // velocity 0: a free body falls g dt^2 / 2 = g2 L in it) breaks the small-step assumption
  // of contact at the first step already: the stepper would warn when a step moves too far.
  double gravity = 0.0;
  for (const LoadSpec& load : spec_.loads)
    if (load.kind == LoadKind::gravity)
      gravity = std::max(gravity, load.vector.norm());
  const AnalysisSpec& analysis = spec_.analysis;
  if (analysis.kind == AnalysisKind::dynamic && analysis.time_step && gravity > 0.0) {
    const double limit = analysis.max_step_displacement * model_size;
    const double shi = std::sqrt(2.0 * limit / gravity);
    if (*analysis.time_step > shi) {
      warn(analysis.time_step_line,
           "[analysis] time_step = " + number_text(*analysis.time_step) +
               " s is longer than the step in which a free body falls max_step_displacement "
               "x model size = " +
               number_text(limit) + " m (" + number_text(shi) +
               " s): contacts are found for smaller moves than a step makes; use a shorter "
               "time_step or time_step = \"auto\"");
    }
  }
  // An nmm block much smaller than the math triangles is carried by the few covers of the
  // triangles it lies in: its motion is right, its stress coarse.
  const CoverSystem& covers = geometry_.covers;
  int smallest = -1;
  int small_blocks = 0;
  const double small = 0.01 * spec_.cover_mesh.size * spec_.cover_mesh.size;
  for (std::size_t b = 0; b < covers.blocks.size(); ++b) {
    const Block& block = covers.blocks[b];
    if (block.elements.empty() || block.loops.empty())
      continue; // dda and vem blocks do not use the math mesh
    if (block.area < small)
      ++small_blocks;
    if (smallest < 0 || block.area < covers.blocks[at(smallest)].area)
      smallest = static_cast<int>(b);
  }
  if (small_blocks > 0) {
    const Block& block = covers.blocks[at(smallest)];
    // A global size only when the triangles it needs stay within max_triangles.
    const double wanted = std::sqrt(block.area);
    const long long triangles = triangles_at_size(geometry_.physical, wanted);
    const std::string fix =
        triangles <= spec_.cover_mesh.max_triangles
            ? "use a size below " + number_text(wanted) +
                  " m (or model = \"dda\" for rigid-like blocks)"
            : "make the cover mesh finer around it only ([cover_mesh] kind = \"gmsh\" on a .msh "
              "geometry graded there; a size below " +
                  number_text(wanted) + " m everywhere would need about " +
                  std::to_string(triangles) + " triangles, more than max_triangles = " +
                  std::to_string(spec_.cover_mesh.max_triangles) +
                  "), or model = \"dda\" for rigid-like blocks";
    warn(spec_.cover_mesh.size_line,
         std::to_string(small_blocks) + (small_blocks == 1 ? " nmm block is" : " nmm blocks are") +
             " much smaller than the math triangles ([cover_mesh] size = " +
             number_text(spec_.cover_mesh.size) + " m), the smallest " + number_text(block.area) +
             " m² near " + point_text(covers.loops[at(block.loops.front())].vertices.front(), 6) +
             ": such a block moves right but its stress is coarse; " + fix);
  }
}

void CaseAnalysis::add_unused_curve_warnings() {
  const PhysicalMesh& physical = geometry_.physical;
  std::vector<char> used(physical.curves.size(), 0);
  for (const int c : geometry_.joint_curves)
    used[at(c)] = 1;
  const auto mark = [&](const std::string& name) {
    const int c = physical.find_curve(name);
    if (c >= 0)
      used[at(c)] = 1;
  };
  for (const BoundarySpec& b : spec_.boundaries)
    if (b.is_curve)
      mark(b.target);
  for (const LoadSpec& load : spec_.loads)
    if (load.kind == LoadKind::traction || load.kind == LoadKind::pressure)
      mark(load.target);
  for (const BoltSpec& bolt : spec_.bolts)
    mark(bolt.curve);
  for (std::size_t c = 0; c < physical.curves.size(); ++c) {
    if (used[c] != 0)
      continue;
    // Inside a block: the same block on both sides of a piece (a curve on a free boundary
    // or along an interface of two blocks is a name for ParaView or scripts).
    for (const CurvePiece& piece : model_.curve_pieces[c]) {
      if (piece.left_block < 0 || piece.left_block != piece.right_block)
        continue;
      const std::string& name = physical.curves[c].name;
      warnings_.push_back(geometry_name(spec_) + ": Physical Curve " + in_quotes(name) +
                          " runs through the material near " + point_text(piece.a, 6) +
                          " but is no joint, [[boundary]] or [[load]] of " +
                          spec_.file.filename().string() +
                          ", so it does not cut the rock; add [joints." + name +
                          "] if it is a joint (a curve named only for ParaView or scripts "
                          "may stay as it is)");
      break;
    }
  }
}

std::unique_ptr<ContactSystem> CaseAnalysis::make_contact_system(double penalty) const {
  // Each boundary edge takes the properties of its joint ([joints.NAME]) or [contact]; an
  // edge pair takes the weaker of its two sides (and the softer of the joints' own
  // stiffnesses). A joint with cohesion or tensile strength is intact (bonded) until its
  // strength is exceeded.
  constexpr double degrees = 3.14159265358979323846 / 180.0;
  const auto strength_of = [&](const JointProperties& p) {
    return JointStrength{p.friction_angle_degrees * degrees, p.cohesion, p.tensile_strength,
                         p.normal_stiffness, p.shear_stiffness};
  };
  std::map<int, const JointProperties*> joint_of_curve;
  for (std::size_t j = 0; j < geometry_.joint_curves.size(); ++j)
    joint_of_curve.emplace(geometry_.joint_curves[j], &spec_.joints[j].properties);
  std::vector<std::vector<JointStrength>> strengths;
  std::vector<std::vector<bool>> bonded;
  for (const BoundaryLoop& loop : model_.loops) {
    std::vector<JointStrength> s;
    std::vector<bool> b;
    for (const BoundaryEdge& edge : loop.edges) {
      const auto joint = joint_of_curve.find(edge.joint);
      const JointProperties* properties =
          joint != joint_of_curve.end() ? joint->second : &spec_.contact;
      s.push_back(reduced_strength(strength_of(*properties), strength_factor_));
      b.push_back(edge.joint >= 0 &&
                  (properties->cohesion > 0.0 || properties->tensile_strength > 0.0));
    }
    strengths.push_back(std::move(s));
    bonded.push_back(std::move(b));
  }
  ContactOptions options;
  options.penalty = penalty;
  options.spring_length = model_.scale;
  options.penetration_tolerance = spec_.analysis.penetration_tolerance.value_or(0.0);
  return std::make_unique<ContactSystem>(options, std::move(strengths), std::move(bonded));
}

void CaseAnalysis::equilibrate() {
  stepper_->equilibrate();
  // Displacements count from the settled state.
  for (std::size_t k = 0; k < monitor_starts_.size(); ++k)
    monitor_starts_[k] = stepper_->scene().monitors[k].position;
}

void CaseAnalysis::restore_monitor_starts(std::vector<Point2> starts) {
  NMM_ASSERT(starts.size() == monitor_starts_.size(), "one start per monitor");
  monitor_starts_ = std::move(starts);
}

std::vector<MonitorValues> CaseAnalysis::monitor_values() const {
  std::vector<MonitorValues> values;
  const std::vector<MaterialPoint>& monitors = stepper_->scene().monitors;
  values.reserve(monitors.size());
  for (std::size_t k = 0; k < monitors.size(); ++k) {
    const MaterialPoint& p = monitors[k];
    const Point2 u = p.position - monitor_starts_[k];
    const Point2 v = stepper_->velocity_at(p.element, p.position);
    const Eigen::Vector3d s = model_.elements[at(p.element)].stress.at(p.position);
    values.push_back(
        {p.position.x(), p.position.y(), u.x(), u.y(), v.x(), v.y(), s(0), s(1), s(2)});
  }
  return values;
}

// ------------------------------------------------------------------------------------------
// The run

fs::path output_dir_of(const CaseSpec& spec, const RunOptions& options) {
  return options.output_dir.empty() ? spec.output.dir : options.output_dir;
}

void create_output_dir(const fs::path& dir) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error || !fs::is_directory(dir)) {
    throw InputError("cannot create the output folder " + dir.string() + ": " +
                     (error ? error.message() : std::string("a file of that name exists")) +
                     "; choose another folder with -o DIR or [output] dir in the case file");
  }
}

namespace {

/// An exclusive lock on @p dir for the lifetime of the object: flock(2) on its lock file,
/// which stays in the folder (the lock goes with the descriptor, also when the process is
/// killed). It holds the locking process's id for the message of a refused second run.
class OutputLock {
public:
  explicit OutputLock(const fs::path& dir) {
    const fs::path file = dir / output_lock_file_name;
    descriptor_ = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (descriptor_ < 0) {
      throw InputError("cannot write " + quoted(file) + ": " +
                       std::generic_category().message(errno) +
                       "; make the output folder writable or choose another with -o DIR or "
                       "[output] dir");
    }
    if (::flock(descriptor_, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      std::string holder;
      char text[32] = {};
      if (::pread(descriptor_, text, sizeof text - 1, 0) > 0)
        holder = std::string(text).substr(0, std::string(text).find('\n'));
      ::close(descriptor_);
      descriptor_ = -1;
      if (error == EWOULDBLOCK) {
        throw InputError(
            "another nmm run" + (holder.empty() ? std::string() : " (process " + holder + ")") +
            " is writing into the output folder " + quoted(dir) + " (it holds " + quoted(file) +
            "): two runs in one folder would mix their files; wait for it to end or stop it, "
            "or give this run another folder with -o DIR");
      }
      // A file system without locks (ENOLCK, some network mounts): run unlocked.
      return;
    }
    const std::string pid = std::to_string(::getpid()) + "\n";
    if (::ftruncate(descriptor_, 0) != 0 ||
        ::pwrite(descriptor_, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
      // The lock holds without the process id; the message of a second run just lacks it.
    }
  }
  ~OutputLock() {
    if (descriptor_ >= 0)
      ::close(descriptor_);
  }
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;
  OutputLock(OutputLock&&) = delete;
  OutputLock& operator=(OutputLock&&) = delete;

private:
  int descriptor_ = -1;
};

/// Refuses a folder in @p dir under the name of a file that run_case() writes: the rename
/// of the finished file onto it would fail only at the end of the run.
void refuse_folders_named_like_outputs(const fs::path& dir) {
  for (const char* name :
       {"summary.json", "history.csv", blocks_file_name, "case.pvd", checkpoint_file_name}) {
    const fs::path file = dir / name;
    std::error_code error;
    if (fs::is_directory(file, error)) {
      throw InputError(quoted(file) + " is a folder, where nmm run writes its " + name +
                       " file; remove or rename the folder, or choose another output folder "
                       "with -o DIR or [output] dir");
    }
  }
}

/// Removes the step, contact and boundary files of an earlier run in @p dir after step @p after
/// (all with -1), and its checkpoint unless restarting (@p after >= 0).
void remove_old_output(const fs::path& dir, long after) {
  std::error_code error;
  static const std::regex old_output(
      R"((?:step|contacts|boundary)_([0-9]{6,})\.(?:vtu|vtp)(?:\.tmp)?|checkpoint\.nmm(?:\.tmp)?)");
  std::vector<fs::path> old_files;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, error)) {
    std::smatch match;
    const std::string name = entry.path().filename().string();
    if (!std::regex_match(name, match, old_output))
      continue;
    const bool checkpoint = !match[1].matched;
    if (after < 0 || (!checkpoint && std::stol(match[1].str()) > after))
      old_files.push_back(entry.path());
  }
  for (const fs::path& file : old_files) {
    std::error_code ignored;
    fs::remove(file, ignored);
  }
}

} // namespace

std::vector<std::string>
contact_warnings(const StepperCounters& c, double max_penetration, double step_limit) {
  std::vector<std::string> warnings;
  if (c.locks_beyond_friction > 0) {
    warnings.push_back(
        "contacts at the limit of friction were held locked beyond it at the end of " +
        std::to_string(c.locks_beyond_friction) +
        (c.locks_beyond_friction == 1 ? " step" : " steps") + " (up to " +
        number_text(c.max_lock_excess, 3) +
        " times the limit; the chatter rule): a body reported standing there may slide. "
        "history.csv's lock_excess names the steps and contacts_*.vtp the contacts (state 2 "
        "with |shear_force| above tan(phi) normal_force, plus cohesion x length where "
        "bonded); a smaller max_step_displacement, or a dynamic analysis, lets them slide");
  }
  // A tenth of the step limit: springs that let a contact sink that far move its entrance
  // line by as much as the step's motion is meant to be small against.
  if (step_limit > 0.0 && max_penetration > 0.1 * step_limit) {
    warnings.push_back("contacts penetrated up to " + number_text(max_penetration, 3) + " m, " +
                       number_text(100.0 * max_penetration / step_limit, 2) +
                       "% of the step displacement limit (" + number_text(step_limit, 3) +
                       " m): the contact springs are soft for these loads; raise [analysis] "
                       "penalty, or set penetration_tolerance (augmented Lagrange)");
  }
  // More than one step in ten cut: the time step is too long for the contacts' changes.
  if (c.step_cuts > 10 && 10 * c.step_cuts > c.steps) {
    warnings.push_back(std::to_string(c.step_cuts) + " of " + std::to_string(c.steps) +
                       " steps were cut (the open-close iteration did not settle, or a step "
                       "moved too far): a shorter time_step or max_step_displacement, or a "
                       "larger open_close_max, costs fewer solves");
  }
  return warnings;
}

RunResult run_case(CaseAnalysis& analysis, const RunOptions& options) {
  const Clock::time_point start = Clock::now();
  const CaseSpec& spec = analysis.spec();
  const Model& model = analysis.model();
  TimeStepper& stepper = analysis.stepper();
  NMM_ASSERT(stepper.counters().steps == 0, "run_case() runs an analysis once");

  RunResult result;
  result.output_dir = output_dir_of(spec, options);
  const fs::path& dir = result.output_dir;
  const fs::path checkpoint_file = dir / checkpoint_file_name;
  // Before the first step (and the initial equilibrium): what a checkpoint belongs to.
  const std::uint64_t fingerprint = model_fingerprint(model);
  const std::uint64_t case_hash = file_hash(spec.file);
  std::vector<std::string> monitor_names;
  for (const MonitorSpec& m : spec.monitors)
    monitor_names.push_back(m.name);
  const std::vector<std::string>& bolt_names = analysis.bolt_names();
  const auto bolt_forces = [&] {
    // (0 for the bolts of stages still to come)
    std::vector<double> forces(bolt_names.size(), 0.0);
    const std::vector<Bolt>& bolts = stepper.scene().bolts;
    for (std::size_t k = 0; k < bolts.size(); ++k)
      forces[k] = bolts[k].force();
    return forces;
  };
  // [[stage]]s: the steps completed at the start of each, and the one running (-1: none yet).
  std::vector<long> stage_start;
  for (long total = 0; const StageSpec& s : spec.stages) {
    stage_start.push_back(total);
    total += s.steps;
  }
  int stage = -1;
  const auto stage_name = [&] {
    return stage >= 0 ? std::string_view(spec.stages[at(stage)].name) : std::string_view();
  };
  std::vector<std::string> restart_warnings;
  std::optional<CheckpointRun> restored;
  std::optional<HistoryWriter> history;
  // blocks.csv (docs/output.md): each block's motion and state at every output step.
  std::optional<BlockOutput> blocks;
  std::vector<std::string> region_names;
  for (const int material : analysis.geometry().region_material)
    region_names.push_back(material >= 0 ? spec.materials[static_cast<std::size_t>(material)].name
                                         : std::string());
  const bool step_rates = spec.analysis.kind == AnalysisKind::quasi_static;
  const double speed_tolerance = block_speed_tolerance * stepper.model_size();
  std::optional<OutputLock> lock;
  if (options.restart && !spec.stages.empty())
    throw InputError(spec.file.string(), spec.stages.front().line, 0,
                     "a run in [[stage]]s cannot be restarted yet (its checkpoint does not "
                     "hold the stages' excavations, supports and loads); run the case again "
                     "from the start without --restart");
  if (options.restart) {
    // Everything is checked before anything in the folder changes (but the lock file).
    std::error_code error;
    if (fs::is_directory(dir, error))
      lock.emplace(dir);
    restored = read_checkpoint(checkpoint_file, stepper, fingerprint, case_hash, restart_warnings);
    refuse_folders_named_like_outputs(dir);
    const std::size_t n_points = step_points(model).size();
    if (restored->initial_points.size() != n_points ||
        restored->monitor_starts.size() != spec.monitors.size())
      throw InputError(
          checkpoint_file.string() + " holds " + std::to_string(restored->initial_points.size()) +
          " output points and " + std::to_string(restored->monitor_starts.size()) +
          " monitors, the case has " + std::to_string(n_points) + " and " +
          std::to_string(spec.monitors.size()) + "; run the case from the start without --restart");
    analysis.restore_monitor_starts(restored->monitor_starts);
    history.emplace(dir / "history.csv", monitor_names, restored->history_bytes, bolt_names);
    blocks.emplace(model, restored->initial_points, region_names, dir / blocks_file_name,
                   restored->blocks_bytes, step_rates, speed_tolerance);
    blocks->restore(restored->block_motion);
    remove_old_output(dir, restored->step);
    if (options.on_warning) {
      for (const std::string& w : restart_warnings)
        options.on_warning(w);
    }
  } else {
    create_output_dir(dir);
    lock.emplace(dir);
    refuse_folders_named_like_outputs(dir);
    remove_old_output(dir, -1);
  }

  RunSummary summary;
  summary.dofs = model.n_dofs();
  summary.covers = model.n_covers();
  summary.elements = model.n_elements();
  summary.blocks = static_cast<int>(model.blocks.size());
  summary.title = spec.title;
  summary.case_file = spec.file.string();
  summary.geometry = spec.geometry.string();
  summary.mesher = analysis.geometry().covers.stats;
  const auto all_warnings = [&] {
    std::vector<std::string> warnings = analysis.warnings();
    warnings.insert(warnings.end(), restart_warnings.begin(), restart_warnings.end());
    warnings.insert(warnings.end(), stepper.warnings().begin(), stepper.warnings().end());
    for (std::string& w :
         contact_warnings(stepper.counters(), summary.max_penetration,
                          spec.analysis.max_step_displacement * stepper.model_size()))
      warnings.push_back(std::move(w));
    return warnings;
  };
  const double wall_before = restored ? restored->wall_seconds : 0.0;
  const auto update_summary = [&](const std::string& status) {
    summary.status = status;
    summary.steps = stepper.counters().steps;
    summary.time = stepper.time();
    summary.wall_seconds = wall_before + options.seconds_before + seconds_since(start);
    summary.unknowns = stepper.n_unknowns();
    summary.step_cuts = stepper.counters().step_cuts;
    summary.counters = stepper.counters();
    summary.solver_counters = stepper.solver_counters();
    // Stresses are recovered for output (make_step_data) once per step file and nowhere else.
    summary.stress_recoveries = result.output_steps;
    summary.warnings = all_warnings();
    if (spec.output.moved_threshold)
      summary.moved_blocks =
          blocks ? blocks->moved_blocks(*spec.output.moved_threshold) : std::vector<MovedBlock>{};
    summary.monitors.clear();
    const std::vector<MonitorValues> values = analysis.monitor_values();
    for (std::size_t k = 0; k < values.size(); ++k)
      summary.monitors.emplace_back(spec.monitors[k].name, values[k]);
    summary.stage = std::string(stage_name());
    summary.stages.clear();
    for (std::size_t k = 0; k < spec.stages.size(); ++k)
      summary.stages.push_back({spec.stages[k].name, stage_start[k] + 1, spec.stages[k].steps});
    summary.bolts.clear();
    for (const Bolt& bolt : stepper.scene().bolts) {
      BoltSummary& item = summary.bolts.emplace_back();
      item.name = bolt.name;
      item.force = bolt.force();
      item.state = bolt_state_name(bolt.state());
      item.bars = static_cast<int>(bolt.bars.size());
      for (const BoltBar& bar : bolt.bars) {
        item.yielding_bars += bar.state == BoltState::yielding ? 1 : 0;
        item.ruptured_bars += bar.state == BoltState::ruptured ? 1 : 0;
      }
    }
  };
  const fs::path summary_file = dir / "summary.json";
  update_summary("running");
  write_summary_json(summary_file, summary); // also proves the folder writable
  // The status of a run stopped by an error, in summary.json.
  const auto record_failure = [&](const std::exception& error) {
    try {
      // An output that could not be written (a full disk, a file-size limit) is a failure of
      // the run, not of the case: its status says so ("failed: disk full: ...").
      const bool output_failed = dynamic_cast<const OutputWriteError*>(&error) != nullptr;
      update_summary(output_failed ? "failed: " + std::string(error.what()) : error.what());
      write_summary_json(summary_file, summary);
    } catch (const std::exception&) { // the first error is the one to report
    }
  };

  PvdSeries pvd(dir / "case.pvd", step_part_names());
  long written = -1;
  long step = 0;
  std::vector<Point2> initial_points;
  if (restored) {
    pvd.restore(restored->pvd);
    initial_points = restored->initial_points;
    written = restored->written;
    step = restored->step;
    result.output_steps = restored->output_steps;
    summary.max_penetration = restored->max_penetration;
  } else {
    history.emplace(dir / "history.csv", monitor_names, bolt_names, !spec.stages.empty());
    if (spec.analysis.initial_equilibrium) {
      try {
        analysis.equilibrate();
      } catch (const std::exception& error) { // (the summary says why, as for a step)
        record_failure(error);
        throw;
      }
    }
    initial_points = step_points(model);
    blocks.emplace(model, initial_points, region_names, dir / blocks_file_name, std::nullopt,
                   step_rates, speed_tolerance);
  }
  const auto write_checkpoint_now = [&] {
    CheckpointRun run;
    run.step = step;
    run.written = written;
    run.output_steps = result.output_steps;
    run.max_penetration = summary.max_penetration;
    run.wall_seconds = wall_before + options.seconds_before + seconds_since(start);
    run.history_bytes = history->bytes();
    run.blocks_bytes = blocks->bytes();
    run.block_motion = blocks->tracker().state();
    run.pvd = pvd.entries();
    run.initial_points = initial_points;
    run.monitor_starts = analysis.monitor_starts();
    write_checkpoint(checkpoint_file, run, stepper, fingerprint, case_hash);
  };
  const auto write_step = [&](long number) {
    const fs::path file = dir / step_file_name(number);
    write_vtu(file, make_step_data(model, initial_points, stepper.velocity(), stepper.time()));
    std::vector<fs::path> parts{file};
    if (const ContactSystem* contact = stepper.contact()) {
      parts.push_back(dir / contact_file_name(number));
      write_vtp_points(parts.back(), make_contact_data(*contact, model, stepper.time()));
      parts.push_back(dir / boundary_file_name(number));
      write_vtp_lines(parts.back(),
                      make_boundary_step_data(model, stepper.scene().bolts, stepper.time()));
    }
    pvd.add(stepper.time(), parts);
    blocks->write_step(number, stepper.time(), model, stepper);
    written = number;
    ++result.output_steps;
  };

  const long steps = spec.analysis.steps;
  const double end_time = spec.analysis.end_time.value_or(std::numeric_limits<double>::infinity());
  const long every = std::max(1, spec.output.every);
  const long checkpoint_every = spec.output.checkpoint_every;
  const double start_time = stepper.time();
  const long start_step = step;
  CutCounts cuts;
  std::size_t stepper_warnings = stepper.warnings().size(); // those restored were printed
  try {
    if (!restored)
      write_step(0);
    while (step < steps) {
      if (stepper.time() >= end_time * (1.0 - 1e-12))
        break;
      if (options.stop != nullptr && options.stop->load()) {
        result.status = RunStatus::interrupted;
        break;
      }
      if (!spec.stages.empty()) {
        const auto next =
            static_cast<int>(std::upper_bound(stage_start.begin(), stage_start.end(), step) -
                             stage_start.begin() - 1);
        if (next != stage) {
          stage = next;
          analysis.begin_stage(stage);
          if (spec.stages[at(stage)].reset_displacement) {
            analysis.reset_monitor_starts();
            initial_points = step_points(model);
            const std::uintmax_t kept = blocks->bytes();
            blocks.emplace(model, initial_points, region_names, dir / blocks_file_name, kept,
                           step_rates, speed_tolerance);
          }
        }
        // The excavation's tractions released evenly over the stage's steps.
        const long done = step - stage_start[at(stage)] + 1;
        analysis.set_release(1.0 - static_cast<double>(done) / spec.stages[at(stage)].steps);
      }
      const StepReport report = stepper.step(end_time);
      step = report.step;
      result.load_work = report.load_work;
      summary.max_penetration = std::max(summary.max_penetration, report.max_penetration);
      history->write_row(report, analysis.monitor_values(), bolt_forces(), stage_name());
      blocks->update(model, report.dt);
      // The stepper's warnings as they come (the energy balance's among them), not only in
      // the final list.
      for (; stepper_warnings < stepper.warnings().size(); ++stepper_warnings) {
        if (options.on_warning)
          options.on_warning(stepper.warnings()[stepper_warnings]);
      }
      if (step % every == 0)
        write_step(step);
      if (checkpoint_every > 0 && step % checkpoint_every == 0)
        write_checkpoint_now();
      if (options.on_step) {
        RunProgress progress;
        progress.report = &report;
        progress.steps = steps;
        progress.end_time = end_time;
        progress.wall_seconds = seconds_since(start);
        progress.step_cuts = stepper.counters().step_cuts;
        cuts.add(report);
        progress.cuts = cuts;
        progress.start_time = start_time;
        progress.start_step = start_step;
        options.on_step(progress);
      }
    }
    if (written != step)
      write_step(step);
    write_checkpoint_now();
  } catch (const std::exception& error) {
    // Leave a readable record of how far the run got, then let the caller report it.
    try {
      if (written != step)
        write_step(step);
    } catch (const std::exception&) { // the first error is the one to report
    }
    record_failure(error);
    throw;
  }

  update_summary(result.status == RunStatus::completed ? "completed" : "interrupted");
  write_summary_json(summary_file, summary);
  result.steps = summary.steps;
  result.time = summary.time;
  result.wall_seconds = summary.wall_seconds;
  result.step_cuts = summary.step_cuts;
  result.max_penetration = summary.max_penetration;
  result.locks_beyond_friction = summary.counters.locks_beyond_friction;
  result.max_lock_excess = summary.counters.max_lock_excess;
  result.slides_against_motion = summary.counters.slides_against_motion;
  result.slide_feed_work = summary.counters.slide_feed_work;
  result.solves = summary.solver_counters.solves;
  result.cg_iterations = summary.solver_counters.iterations;
  result.cg_fallbacks = summary.solver_counters.fallbacks;
  result.warnings = summary.warnings;
  return result;
}

} // namespace nmm
