// SPDX-License-Identifier: MIT
// bench/step_bench.cpp — per-step wall time of the time stepper split into its parts, next
// to the bare CHOLMOD factorisation + solve of the same matrix measured in the same run
// (issue 4: a whole step within 1.5x of factor + solve), and the time to write one output
// step's .vtu.
//
//   bench_step [ORDER=0] [DOFS...]     default DOFS: 1e4 1e5 1e6
#include "io/step_output.hpp"
#include "io/vtk_writer.hpp"
#include "manifold/boundary_conditions.hpp"
#include "manifold/model.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/threads.hpp"
#include "solver/time_stepper.hpp"

#include "timing.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <vector>

namespace {

using nmm::bench::Clock;
using nmm::bench::since;

void run(int order, double target_dofs) {
  // A 4 m x 1 m beam clamped at x = 0 under gravity, dynamic, 1 ms steps.
  nmm::PhysicalMesh physical;
  physical.source = "bench";
  physical.regions.push_back({"rock", {{{{0, 0}, {4, 0}, {4, 1}, {0, 1}}, {}}}});
  physical.curves.push_back({"clamp", {{{0, 0}, {0, 1}}}});
  nmm::validate_physical_mesh(physical);
  const double per_node = order == 0 ? 2.0 : 6.0;
  const double size = std::sqrt(4.0 * 2.0 * per_node / (std::sqrt(3.0) * target_dofs));
  auto t = Clock::now();
  const nmm::MathMesh math =
      nmm::make_regular_math_mesh(nmm::material_bounding_box(physical), size);
  const nmm::CoverSystem covers = nmm::build_cover_system(math, physical, {});
  const double mesh_seconds = since(t);
  nmm::ElasticMaterial rock;
  rock.name = "rock";
  rock.young = 5e9;
  rock.poisson = 0.25;
  rock.density = 2600;
  nmm::ModelOptions options;
  options.order = order;
  nmm::Model model = nmm::make_model(covers, math, {rock}, options);
  nmm::Scene scene;
  scene.supports =
      nmm::curve_support_points(model, 0, true, true, nmm::SupportMethod::exact, "clamp");
  scene.body_loads.push_back({{0.0, -9.81}, {}});
  nmm::StepperOptions stepper_options;
  stepper_options.time_step = 1e-3;
  const std::vector<nmm::Point2> initial_points = nmm::step_points(model);
  nmm::TimeStepper stepper(model, scene, stepper_options);
  (void)stepper.step(1.0); // first step: pattern and symbolic analysis
  const nmm::StepperCounters first = stepper.counters();
  const int steps = target_dofs > 5e5 ? 3 : 5;
  t = Clock::now();
  for (int i = 0; i < steps; ++i)
    (void)stepper.step(1.0);
  const double per_step = since(t) / steps;
  // Output as `nmm run` writes it at an output step: the step's .vtu (the .pvd rewrite is
  // a few lines and left out).
  const std::filesystem::path vtu =
      std::filesystem::temp_directory_path() / "nmm_bench_step_output.vtu";
  t = Clock::now();
  for (int i = 0; i < steps; ++i)
    nmm::write_vtu(vtu,
                   nmm::make_step_data(model, initial_points, stepper.velocity(), stepper.time()));
  const double output = since(t) / steps;
  const auto output_bytes = static_cast<double>(std::filesystem::file_size(vtu));
  std::filesystem::remove(vtu);
  const nmm::StepperCounters& c = stepper.counters();
  auto part = [&](double nmm::StepperCounters::*field) {
    return (c.*field - first.*field) / steps;
  };
  // The bare floor: factorise and solve the same matrix (symbolic analysis excluded).
  nmm::CholmodSolver bare;
  (void)bare.analyze(stepper.last_matrix());
  const Eigen::VectorXd rhs = Eigen::VectorXd::Ones(stepper.last_matrix().rows());
  Eigen::VectorXd x;
  t = Clock::now();
  for (int i = 0; i < steps; ++i) {
    (void)bare.factorize(stepper.last_matrix());
    (void)bare.solve(rhs, x);
  }
  const double floor = since(t) / steps;
  std::printf("order %d, %8d unknowns, %7d elements (mesh %.2f s, first step %.2f s):\n", order,
              stepper.n_unknowns(), model.n_elements(), mesh_seconds,
              first.seconds_analysis + first.seconds_pattern);
  std::printf("  step %.4f s = constraints %.4f + assembly %.4f + factorisation %.4f + solve %.4f "
              "+ update %.4f (+ pattern %.4f); output %.4f s (%.1f MB) per output step\n",
              per_step, part(&nmm::StepperCounters::seconds_constraints),
              part(&nmm::StepperCounters::seconds_assembly),
              part(&nmm::StepperCounters::seconds_factorization),
              part(&nmm::StepperCounters::seconds_solve),
              part(&nmm::StepperCounters::seconds_update),
              part(&nmm::StepperCounters::seconds_pattern), output, output_bytes / 1e6);
  std::printf("  in the measured steps: %ld pattern builds (each with a symbolic analysis), %ld "
              "plan rebuilds\n",
              c.pattern_builds - first.pattern_builds, c.plan_rebuilds - first.plan_rebuilds);
  std::printf("  bare CHOLMOD factor + solve %.4f s (%.3g flops); step / bare = %.2f, "
              "(step + output) / bare = %.2f\n",
              floor, bare.factor_flops(), per_step / floor, (per_step + output) / floor);
}

} // namespace

int main(int argc, char** argv) {
  nmm::limit_threads(nmm::available_cores());
  const int order = argc > 1 ? std::atoi(argv[1]) : 0;
  std::vector<double> sizes;
  for (int i = 2; i < argc; ++i)
    sizes.push_back(std::atof(argv[i]));
  if (sizes.empty())
    sizes = {1e4, 1e5, 1e6};
  for (const double dofs : sizes)
    run(order, dofs);
  return 0;
}
