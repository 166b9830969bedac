// SPDX-License-Identifier: MIT
// bench/contact_bench.cpp — contact detection against the linear solve of the same steps
// (issue 5, item 7).
//
// The scene: a wall of bricks 1 m x 0.5 m (running bond by default: half bricks at the ends
// of every other course), every bed and head joint a joint, on a base slab 0.5 m thick held
// at its bottom, under gravity; E = 10 GPa, nu = 0.25, density 2500, plane strain, friction
// angle 30 degrees, no cohesion, penalty 40 E, cover size 0.25 m, dynamic, dt = 1e-3 s,
// from the initial equilibrium (TimeStepper::equilibrate). The wall is twice as wide as it
// is high and sized so that about EDGES boundary edges carry a closed contact. Per step,
// means over the measured steps:
//   (a) ContactSystem::begin_step (boundary, sort-and-sweep broad phase, narrow phase,
//       transfer of the closed contacts), timed on a copy of the stepper's contact system
//       made just before the step: the same state, so the same work as the stepper's own
//       call, which StepperCounters does not time;
//   (b) open-close iterations of the step's last try (StepReport), step cuts, and every
//       solve split into refactorisations and friction-only solves (SolverCounters);
//   (c) numeric factorisation and triangular solves (StepperCounters), and the whole step.
// Then detect_contacts() alone on each wall's final boundary, best of several runs, at the
// run's detection distance and at the distance a case file's default gives (0.02 x model
// size): time per boundary edge against the number of edges.
//
//   bench_contact [--edges 1e2,1e3,1e4,1e5] [--steps 10] [--limit 0.01 | --g2 F]
//                 [--bond running|stack] [--wall COURSESxBRICKS,...] [--detect-only]
//                 [--run-distance-only] [--verbose]
//     --steps    measured steps (half of them from 5e3 edges, a fifth from 5e4)
//     --limit    max step displacement in m, the same for every wall (default 0.01 m: the
//                detection distance is 0.02 m, 4 % of a brick's height), or
//     --g2       max_step_displacement as a fraction of the model size (Shi's g2; the case
//                file's default is 0.01, so the distance grows with the model)
//     --wall     explicit walls instead of --edges (e.g. 3x2: three courses of two bricks)
//     --detect-only  mesh each wall and time detect_contacts() alone (no steps)
//     --run-distance-only  skip detect_contacts() at the case-file default distance (whose
//                broad-phase pairs grow as ~n^2 on these walls: the slowest part of a
//                --detect-only run at 1e5 edges)
//     --verbose  one line per step: iterations, cuts, modes, the contact that changed last
#include "contact/contact_system.hpp"
#include "contact/detection.hpp"
#include "manifold/boundary_conditions.hpp"
#include "manifold/model.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/threads.hpp"
#include "solver/time_stepper.hpp"

#include "timing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <set>
#include <string>
#include <vector>

namespace {

using nmm::bench::best_seconds;
using nmm::bench::Clock;
using nmm::bench::load_average;
using nmm::bench::since;

using std::numbers::pi;
constexpr double brick_length = 1.0;
constexpr double brick_height = 0.5;
constexpr double cover_size = 0.25;
/// Boundary edges in closed contacts per brick at this cover size (measured: 23-24).
constexpr double contact_edges_per_brick = 24.0;

struct Settings {
  int steps = 10;
  double limit = 0.01; ///< max step displacement, m (0: use g2)
  double g2 = 0.0;     ///< max step displacement / model size
  bool stack_bond = false;
  bool detect_only = false;
  bool default_distance = true; ///< also time detect_contacts() at 0.02 x model size
  bool verbose = false;
};

/// A wall of @p courses courses of @p bricks bricks on a base slab 0.5 m thick and 0.5 m
/// wider on both sides. Curve 0 is the base's bottom ("ground"), curve 1 every joint (one
/// polyline per bed or head joint).
nmm::PhysicalMesh make_wall(int courses, int bricks, bool stack_bond) {
  const double width = bricks * brick_length;
  const double height = courses * brick_height;
  nmm::PhysicalMesh physical;
  physical.source = "bench";
  auto rectangle = [](const std::string& name, double x0, double y0, double x1, double y1) {
    return nmm::MaterialRegion{name, {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}}}};
  };
  physical.regions.push_back(rectangle("base", -0.5, -0.5, width + 0.5, 0.0));
  physical.regions.push_back(rectangle("wall", 0.0, 0.0, width, height));
  physical.curves.push_back({"ground", {{{-0.5, -0.5}, {width + 0.5, -0.5}}}});
  nmm::NamedCurve joints{"joints", {}};
  for (int k = 0; k < courses; ++k) {
    const double y = k * brick_height;
    joints.polylines.push_back({{0.0, y}, {width, y}}); // bed joint (k = 0: on the base)
    const double shift = k % 2 == 0 || stack_bond ? 0.0 : 0.5 * brick_length;
    for (int i = 0; i <= bricks; ++i) {
      const double x = shift + i * brick_length;
      if (x > 1e-9 && x < width - 1e-9)
        joints.polylines.push_back({{x, y}, {x, y + brick_height}}); // head joint
    }
  }
  physical.curves.push_back(std::move(joints));
  nmm::validate_physical_mesh(physical);
  return physical;
}

/// Friction angle 30 degrees on every edge, no cohesion, no bonds, penalty @p penalty
/// (as contact_for() in tests/verification/contact_test.cpp).
std::unique_ptr<nmm::ContactSystem> make_contact(const nmm::Model& model, double penalty) {
  std::vector<std::vector<nmm::JointStrength>> strengths;
  std::vector<std::vector<bool>> bonds;
  for (const nmm::BoundaryLoop& loop : model.loops) {
    strengths.emplace_back(loop.edges.size(), nmm::JointStrength{30.0 * pi / 180.0, 0.0, 0.0});
    bonds.emplace_back(loop.edges.size(), false);
  }
  nmm::ContactOptions options;
  options.penalty = penalty;
  options.spring_length = model.scale;
  return std::make_unique<nmm::ContactSystem>(options, std::move(strengths), std::move(bonds));
}

struct Detection {
  bool measured = false;
  double distance = 0.0;
  double seconds = 0.0; ///< best of several runs
  nmm::DetectionStats stats;
  std::size_t candidates = 0;
};

struct Row {
  int courses = 0;
  int bricks = 0;
  long edges = 0;         // boundary edges of the model
  long contact_edges = 0; // edges of closed contacts (slave or master) after the last step
  int unknowns = 0;
  double model_size = 0.0;
  double setup = 0.0; // mesh, covers, model, stepper, s
  double equilibrium = 0.0;
  int equilibrium_iterations = 0;
  int steps = 0;
  // Means per measured step.
  double points = 0.0; // contact points found by begin_step
  double closed = 0.0; // closed at the end of the step
  double begin_step = 0.0;
  double iterations = 0.0; // of the step's last try
  double cuts = 0.0;
  double factorisations = 0.0;
  double friction_solves = 0.0;
  double factorisation = 0.0;
  double solve = 0.0;
  double analysis = 0.0;
  double pattern = 0.0;
  double assembly = 0.0; // constraints + assembly
  double update = 0.0;
  double step = 0.0;
  double penetration = 0.0;          // largest penetration of a closed contact over the steps, m
  long chatter_holds = 0;            // over the measured steps
  std::vector<std::string> warnings; // the stepper's
  Detection run_distance;            // detect_contacts alone at the run's distance
  Detection default_distance;        // ... at 0.02 x model size
};

Detection time_detection(const nmm::ContactBoundary& boundary,
                         const std::vector<std::uint64_t>& keep,
                         double distance,
                         int repeats) {
  Detection d;
  d.measured = true;
  d.distance = distance;
  nmm::DetectionOptions options;
  options.distance = distance;
  options.penetration = 0.1 * distance; // as ContactSystem::begin_step
  d.seconds = best_seconds(
      repeats,
      [&] {
        d.stats = {};
        d.candidates = nmm::detect_contacts(boundary, options, keep, &d.stats).size();
      },
      50); // at most 50 runs: one detection of the largest wall takes seconds
  return d;
}

Row run_wall(int courses, int bricks, int steps, const Settings& settings) {
  Row row;
  row.courses = courses;
  row.bricks = bricks;
  auto t = Clock::now();
  const nmm::PhysicalMesh physical = make_wall(courses, bricks, settings.stack_bond);
  const nmm::MathMesh math =
      nmm::make_regular_math_mesh(nmm::material_bounding_box(physical), cover_size);
  const nmm::CoverSystem covers = nmm::build_cover_system(math, physical, std::vector<int>{1});
  nmm::ElasticMaterial rock;
  rock.name = "rock";
  rock.young = 1e10;
  rock.poisson = 0.25;
  rock.density = 2500;
  rock.plane = nmm::PlaneCondition::strain;
  nmm::Model model = nmm::make_model(covers, math, {rock, rock}, {});
  nmm::Scene scene;
  scene.supports =
      nmm::curve_support_points(model, 0, true, true, nmm::SupportMethod::exact, "ground");
  scene.body_loads.push_back({{0.0, -9.81}, {}});
  const nmm::BoundingBox box = nmm::material_bounding_box(physical);
  row.model_size = std::max(box.size().x(), box.size().y()); // as TimeStepper's
  nmm::StepperOptions options;
  options.time_step = 1e-3;
  options.max_step_displacement =
      settings.limit > 0.0 ? settings.limit / row.model_size : settings.g2;
  nmm::TimeStepper stepper(model, scene, options, make_contact(model, 40.0 * rock.young));
  row.setup = since(t);
  for (const nmm::BoundaryLoop& loop : model.loops)
    row.edges += static_cast<long>(loop.edges.size());
  const double limit = options.max_step_displacement * stepper.model_size();

  if (!settings.detect_only) {
    t = Clock::now();
    row.equilibrium_iterations = stepper.equilibrate().open_close_iterations;
    row.equilibrium = since(t);
    row.steps = steps;
    const nmm::StepperCounters c0 = stepper.counters();
    const nmm::SolverCounters s0 = stepper.solver_counters();
    const long holds0 = stepper.contact()->counters().chatter_holds;
    for (int i = 0; i < steps; ++i) {
      nmm::ContactSystem copy = *stepper.contact();
      t = Clock::now();
      copy.begin_step(model, limit);
      row.begin_step += since(t);
      row.points += copy.n_points();
      t = Clock::now();
      const nmm::StepReport report = stepper.step(1e9);
      row.step += since(t);
      row.iterations += report.open_close_iterations;
      row.cuts += report.step_cuts;
      row.closed += report.contacts;
      row.penetration = std::max(row.penetration, stepper.contact_penetration());
      if (settings.verbose) {
        int modes[3] = {0, 0, 0};
        for (const nmm::ContactPoint& p : stepper.contact()->points())
          ++modes[static_cast<int>(p.mode)];
        std::printf("  step %ld: dt %.3g s, %d iterations, %d cuts, %ld factorisations so "
                    "far; open %d, slide %d, lock %d; kinetic energy %.3g J; max penetration "
                    "%.3g m; changed last: %s\n",
                    report.step, report.dt, report.open_close_iterations, report.step_cuts,
                    stepper.solver_counters().factorizations, modes[0], modes[1], modes[2],
                    report.kinetic_energy, stepper.contact_penetration(),
                    stepper.contact()->describe(stepper.contact()->last_changed()).c_str());
        std::fflush(stdout);
      }
    }
    const nmm::StepperCounters& c = stepper.counters();
    const nmm::SolverCounters& s = stepper.solver_counters();
    const double n = steps;
    for (double* mean :
         {&row.begin_step, &row.points, &row.step, &row.iterations, &row.cuts, &row.closed})
      *mean /= n;
    row.factorisations = static_cast<double>(s.factorizations - s0.factorizations) / n;
    row.friction_solves = static_cast<double>(s.solves - s0.solves) / n - row.factorisations;
    row.factorisation = (c.seconds_factorization - c0.seconds_factorization) / n;
    row.solve = (c.seconds_solve - c0.seconds_solve) / n;
    row.analysis = (c.seconds_analysis - c0.seconds_analysis) / n;
    row.pattern = (c.seconds_pattern - c0.seconds_pattern) / n;
    row.assembly = (c.seconds_constraints - c0.seconds_constraints + c.seconds_assembly -
                    c0.seconds_assembly + c.seconds_contact_springs - c0.seconds_contact_springs) /
                   n;
    row.update = (c.seconds_update - c0.seconds_update) / n;
    row.unknowns = stepper.n_unknowns();
    row.chatter_holds = stepper.contact()->counters().chatter_holds - holds0;
    row.warnings = stepper.warnings();
  }

  // Detection alone on the boundary reached, keeping the closed contacts as the stepper does.
  std::vector<std::uint64_t> keep;
  std::set<int> touching;
  for (const nmm::ContactPoint& p : stepper.contact()->points()) {
    if (p.mode != nmm::ContactMode::open) {
      keep.push_back(p.key);
      touching.insert(p.slave_edge);
      touching.insert(p.master);
    }
  }
  row.contact_edges = static_cast<long>(touching.size());
  const nmm::ContactBoundary boundary = nmm::contact_boundary(model);
  row.run_distance = time_detection(boundary, keep, 2.0 * limit, 3);
  // The case-file default distance grows with the model: one run once it takes seconds.
  if (settings.default_distance)
    row.default_distance = time_detection(boundary, keep, 2.0 * 0.01 * stepper.model_size(), 1);
  return row;
}

std::vector<std::string> split(const char* text) {
  std::vector<std::string> items;
  std::string item;
  for (const char* c = text;; ++c) {
    if (*c == ',' || *c == '\0') {
      if (!item.empty())
        items.push_back(item);
      item.clear();
      if (*c == '\0')
        break;
    } else {
      item += *c;
    }
  }
  return items;
}

void print_tables(const std::vector<Row>& rows, bool detect_only) {
  if (!detect_only) {
    std::printf("\nPer step (means), (a) = begin_step, (c) = factorisation + solve:\n");
    std::printf("| wall | boundary edges | in closed contact | unknowns | contact points | steps "
                "| iterations (last try) | cuts | refactorisations | friction-only solves | "
                "(a) ms | (c) ms | one factor + solve ms | step ms | (a)/(c) | (a)/(one "
                "factor + solve) | (a)/step |\n");
    std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- "
                "| --- | --- | --- | --- |\n");
    for (const Row& r : rows) {
      const double c = r.factorisation + r.solve;
      const double one = c / std::max(1.0, r.factorisations);
      std::printf("| %dx%d | %ld | %ld | %d | %.0f | %d | %.1f | %.1f | %.1f | %.1f | %.3g | "
                  "%.4g | %.3g | %.4g | %.3f | %.2f | %.3f |\n",
                  r.courses, r.bricks, r.edges, r.contact_edges, r.unknowns, r.points, r.steps,
                  r.iterations, r.cuts, r.factorisations, r.friction_solves, 1e3 * r.begin_step,
                  1e3 * c, 1e3 * one, 1e3 * r.step, r.begin_step / c, r.begin_step / one,
                  r.begin_step / r.step);
    }
  }
  std::printf("\ndetect_contacts() alone (best of several runs; broad-phase pairs; ns per "
              "boundary edge, and that over log2 of the edges):\n");
  std::printf("| wall | boundary edges | distance m | pairs | pairs/edge | candidates | ms | "
              "ns/edge | ns/edge/log2 | default distance m | pairs | ms | ns/edge | vs run "
              "distance |\n");
  std::printf("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | "
              "--- |\n");
  for (const Row& r : rows) {
    const double n = static_cast<double>(r.edges);
    const Detection& a = r.run_distance;
    const Detection& b = r.default_distance;
    std::printf("| %dx%d | %ld | %.3g | %ld | %.2f | %zu | %.3g | %.0f | %.1f |", r.courses,
                r.bricks, r.edges, a.distance, a.stats.edge_pairs,
                static_cast<double>(a.stats.edge_pairs) / n, a.candidates, 1e3 * a.seconds,
                1e9 * a.seconds / n, 1e9 * a.seconds / n / std::log2(n));
    if (b.measured)
      std::printf(" %.3g | %ld | %.4g | %.0f | %.1f |\n", b.distance, b.stats.edge_pairs,
                  1e3 * b.seconds, 1e9 * b.seconds / n, b.seconds / a.seconds);
    else
      std::printf(" - | - | - | - | - |\n");
  }
}

} // namespace

int main(int argc, char** argv) {
  std::vector<double> sizes{1e2, 1e3, 1e4, 1e5};
  std::vector<std::pair<int, int>> walls;
  Settings settings;
  auto usage = [&] {
    std::fprintf(stderr,
                 "usage: %s [--edges 1e2,1e3,1e4,1e5] [--steps 10] [--limit 0.01 | --g2 F] "
                 "[--bond running|stack] [--wall COURSESxBRICKS,...] [--detect-only] "
                 "[--run-distance-only] [--verbose]\n",
                 argv[0]);
    return 2;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--edges" && i + 1 < argc) {
      sizes.clear();
      for (const std::string& s : split(argv[++i]))
        sizes.push_back(std::strtod(s.c_str(), nullptr));
    } else if (arg == "--wall" && i + 1 < argc) {
      for (const std::string& s : split(argv[++i])) {
        int courses = 0;
        int bricks = 0;
        if (std::sscanf(s.c_str(), "%dx%d", &courses, &bricks) != 2 || courses < 1 || bricks < 1)
          return usage();
        walls.emplace_back(courses, bricks);
      }
    } else if (arg == "--steps" && i + 1 < argc) {
      settings.steps = std::max(1, std::atoi(argv[++i]));
    } else if (arg == "--limit" && i + 1 < argc) {
      settings.limit = std::strtod(argv[++i], nullptr);
      settings.g2 = 0.0;
    } else if (arg == "--g2" && i + 1 < argc) {
      settings.g2 = std::strtod(argv[++i], nullptr);
      settings.limit = 0.0;
    } else if (arg == "--bond" && i + 1 < argc) {
      const std::string bond = argv[++i];
      if (bond != "running" && bond != "stack")
        return usage();
      settings.stack_bond = bond == "stack";
    } else if (arg == "--detect-only") {
      settings.detect_only = true;
    } else if (arg == "--run-distance-only") {
      settings.default_distance = false;
    } else if (arg == "--verbose") {
      settings.verbose = true;
    } else {
      return usage();
    }
  }
  if (walls.empty()) {
    // Twice as wide as high (bricks = courses), 24 edges in contact per brick.
    for (const double target : sizes) {
      const int courses =
          std::max(1, static_cast<int>(std::lround(std::sqrt(target / contact_edges_per_brick))));
      walls.emplace_back(courses, courses);
    }
  }
  nmm::limit_threads(nmm::available_cores());
  std::printf("%s; %s; usable cores %d; load average %.2f\n", nmm::cholmod_version().c_str(),
              nmm::blas_description().c_str(), nmm::available_cores(), load_average());
  if (settings.limit > 0.0)
    std::printf("max step displacement %.3g m for every wall (detection distance %.3g m)\n",
                settings.limit, 2.0 * settings.limit);
  else
    std::printf("max step displacement %.3g x model size\n", settings.g2);
  std::vector<Row> rows;
  for (const auto& [courses, bricks] : walls) {
    // Fewer steps for the big walls: their steps are cut and refactorised many times.
    const long bricks_total = static_cast<long>(courses) * bricks;
    const int steps =
        bricks_total * contact_edges_per_brick >= 5e4
            ? std::max(1, settings.steps / 5)
            : (bricks_total * contact_edges_per_brick >= 5e3 ? std::max(1, settings.steps / 2)
                                                             : settings.steps);
    std::printf("%s bond, %d courses x %d bricks:\n", settings.stack_bond ? "stack" : "running",
                courses, bricks);
    std::fflush(stdout);
    const Row r = run_wall(courses, bricks, steps, settings);
    std::printf("  %ld boundary edges, %ld in closed contacts, %d unknowns, model size %.1f m; "
                "setup %.2f s, equilibrium %.2f s (%d iterations)\n",
                r.edges, r.contact_edges, r.unknowns, r.model_size, r.setup, r.equilibrium,
                r.equilibrium_iterations);
    if (!settings.detect_only) {
      std::printf(
          "  per step (%d steps): step %.4f s = factorisation %.4f + solve %.4f + "
          "analysis %.4f + pattern %.4f + constraints/assembly %.4f + update %.4f + "
          "the rest (begin_step, mode updates, step control) %.4f; begin_step %.4f s\n",
          r.steps, r.step, r.factorisation, r.solve, r.analysis, r.pattern, r.assembly, r.update,
          r.step - r.factorisation - r.solve - r.analysis - r.pattern - r.assembly - r.update,
          r.begin_step);
      std::printf("  %.0f contact points, %.0f closed; %.2f iterations (last try), %.2f cuts, "
                  "%.2f refactorisations, %.2f friction-only solves; largest penetration %.3g "
                  "m; %ld chatter holds\n",
                  r.points, r.closed, r.iterations, r.cuts, r.factorisations, r.friction_solves,
                  r.penetration, r.chatter_holds);
      for (const std::string& w : r.warnings)
        std::printf("  warning: %s\n", w.c_str());
    }
    std::printf("  detection: %ld pairs, %ld vertex-edge, %ld vertex-vertex, %ld edge-edge, "
                "%zu candidates\n",
                r.run_distance.stats.edge_pairs, r.run_distance.stats.vertex_edge,
                r.run_distance.stats.vertex_vertex, r.run_distance.stats.edge_edge,
                r.run_distance.candidates);
    std::fflush(stdout);
    rows.push_back(r);
  }
  print_tables(rows, settings.detect_only);
  std::printf("load average at the end %.2f\n", load_average());
  return 0;
}
