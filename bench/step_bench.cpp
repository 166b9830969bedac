// SPDX-License-Identifier: MIT
// bench/step_bench.cpp — per-step wall time of the time stepper split into its parts, next
// to the bare CHOLMOD factorisation + solve of the same matrix measured in the same run
// (issue 4: a whole step within 1.5x of factor + solve), and the time to write one output
// step's .vtu.
//
//   bench_step [ORDER=0] [DOFS...] [--steps K] [--no-output] [--json]
//       default DOFS: 1e4 1e5 1e6. A 4 m x 1 m beam clamped at x = 0 under gravity, dynamic,
//       1 ms steps, on a regular math mesh sized for about DOFS unknowns; the first step
//       (pattern, symbolic analysis) is not measured, then K steps (default 5, 3 above 5e5
//       unknowns), then the .vtu of one output step K times (not with --no-output).
//   bench_step --case FILE [--warmup N] [--steps K] [--json]
//       any case file, read and built through the library as `nmm run` builds it (the
//       initial equilibrium when the case asks for it): N steps not measured (default 1:
//       the pattern and symbolic analysis), then K measured steps (default 3; fewer when
//       the case's end_time comes first); nothing is written. The case's `steps` is ignored.
//
// After each measured step, in both modes: the bare numeric factorisation + solve of the
// matrix the step ended with, as many times as the step factorised (at least once), by a
// CHOLMOD solver of its own (its symbolic analysis and a first factorisation + solve of
// each new pattern not timed); the mean. Interleaved with the steps, so that both see the
// same load. A block model refactorises several times per step (open-close iterations), so
// the floor of its step is the bare time times the factorisations per step (printed).
// --json adds one line per run, a JSON object (the figures of bench/scaling.py).
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
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

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using nmm::bench::Clock;
using nmm::bench::since;

/// The bare floor of a step's linear solve: CHOLMOD numeric factorisation + solve of the
/// matrix a step ended with, by a CholmodSolver of its own configured as the stepper's,
/// measured right after the step so that both see the same load on the machine.
class BareFloor {
public:
  /// Factorises and solves @p matrix @p times, timed; before that, when its pattern is new
  /// to this solver, its symbolic analysis and one factorisation + solve, not timed (the
  /// stepper's factorisations reuse warm memory).
  void measure(const nmm::SparseMatrix& matrix, int times) {
    if (!has_pattern(matrix)) {
      if (solver_.analyze(matrix) != nmm::SolveStatus::ok)
        throw std::runtime_error("bench_step: the symbolic analysis of the last matrix failed");
      outer_.assign(matrix.outerIndexPtr(), matrix.outerIndexPtr() + matrix.outerSize() + 1);
      inner_.assign(matrix.innerIndexPtr(), matrix.innerIndexPtr() + matrix.nonZeros());
      factor_and_solve(matrix);
    }
    const Clock::time_point t = Clock::now();
    for (int i = 0; i < times; ++i)
      factor_and_solve(matrix);
    seconds_ += since(t);
    count_ += times;
  }
  /// Mean of one factorisation + solve, s.
  [[nodiscard]] double seconds() const { return seconds_ / std::max(count_, 1); }
  [[nodiscard]] int count() const { return count_; }
  /// CHOLMOD's count for the factorisation of the last pattern.
  [[nodiscard]] double flops() const { return solver_.factor_flops(); }

private:
  [[nodiscard]] bool has_pattern(const nmm::SparseMatrix& matrix) const {
    return matrix.isCompressed() &&
           outer_.size() == static_cast<std::size_t>(matrix.outerSize()) + 1 &&
           inner_.size() == static_cast<std::size_t>(matrix.nonZeros()) &&
           std::equal(outer_.begin(), outer_.end(), matrix.outerIndexPtr()) &&
           std::equal(inner_.begin(), inner_.end(), matrix.innerIndexPtr());
  }
  void factor_and_solve(const nmm::SparseMatrix& matrix) {
    if (rhs_.size() != matrix.rows())
      rhs_ = Eigen::VectorXd::Ones(matrix.rows());
    if (solver_.factorize(matrix) != nmm::SolveStatus::ok ||
        solver_.solve(rhs_, x_) != nmm::SolveStatus::ok)
      throw std::runtime_error("bench_step: the bare factorisation of the last matrix failed");
  }
  nmm::CholmodSolver solver_;
  std::vector<int> outer_;
  std::vector<int> inner_;
  Eigen::VectorXd rhs_;
  Eigen::VectorXd x_;
  double seconds_ = 0.0;
  int count_ = 0;
};

/// What the measured steps did: counters before and after them, their wall time, and the
/// bare floor measured after each.
struct MeasuredSteps {
  nmm::StepperCounters before;
  nmm::StepperCounters after;
  nmm::SolverCounters solver_before;
  nmm::SolverCounters solver_after;
  int steps = 0;
  double per_step = 0.0; ///< s, wall clock around step()
  double bare = 0.0;     ///< s, mean of one bare factorisation + solve
  int bare_count = 0;
  double bare_flops = 0.0;
};

/// Takes @p steps steps (fewer if @p until is reached first) and measures them; after each,
/// as many bare factorisations + solves of its last matrix as the step factorised (at
/// least one).
MeasuredSteps measure_steps(nmm::TimeStepper& stepper, int steps, double until) {
  MeasuredSteps m;
  m.before = stepper.counters();
  m.solver_before = stepper.solver_counters();
  BareFloor floor;
  double seconds = 0.0;
  for (; m.steps < steps && stepper.time() < until * (1.0 - 1e-12); ++m.steps) {
    const long factorizations = stepper.solver_counters().factorizations;
    const Clock::time_point t = Clock::now();
    (void)stepper.step(until);
    seconds += since(t);
    floor.measure(
        stepper.last_matrix(),
        static_cast<int>(std::max(1L, stepper.solver_counters().factorizations - factorizations)));
  }
  m.per_step = seconds / std::max(m.steps, 1);
  m.after = stepper.counters();
  m.solver_after = stepper.solver_counters();
  m.bare = floor.seconds();
  m.bare_count = floor.count();
  m.bare_flops = floor.flops();
  return m;
}

/// One run's figures, printed as text and (with --json) as one JSON line.
struct Report {
  std::string kind; ///< "beam" or "case"
  std::string name; ///< order of the beam, or the case file
  int unknowns = 0;
  int elements = 0;
  int blocks = 0;
  double setup_seconds = 0.0;  ///< mesh and model (beam), or the whole CaseAnalysis (case)
  double warmup_seconds = 0.0; ///< the steps not measured
  MeasuredSteps measured;
  double output_seconds = -1.0; ///< one output step's .vtu; < 0: not measured
  double output_bytes = 0.0;
  double load_before = 0.0;
  double load_after = 0.0;
};

void print(const Report& r, bool json) {
  const MeasuredSteps& m = r.measured;
  const double steps = std::max(m.steps, 1);
  auto part = [&](double nmm::StepperCounters::*field) {
    return (m.after.*field - m.before.*field) / steps;
  };
  using C = nmm::StepperCounters;
  const double detection = part(&C::seconds_detection);
  const double constraints = part(&C::seconds_constraints);
  const double pattern = part(&C::seconds_pattern);
  const double assembly = part(&C::seconds_assembly);
  const double contact = part(&C::seconds_contact_springs) + part(&C::seconds_contact_modes);
  const double analysis = part(&C::seconds_analysis);
  const double factorization = part(&C::seconds_factorization);
  const double solve = part(&C::seconds_solve);
  const double update = part(&C::seconds_update);
  const double control = part(&C::seconds_step_control);
  const double factorizations =
      static_cast<double>(m.solver_after.factorizations - m.solver_before.factorizations) / steps;
  const long cuts = m.after.step_cuts - m.before.step_cuts;
  const long patterns = m.after.pattern_builds - m.before.pattern_builds;
  const long plans = m.after.plan_rebuilds - m.before.plan_rebuilds;
  const double ratio = m.per_step / m.bare;
  const double solver_floor = m.bare * std::max(factorizations, 1.0);
  std::printf("%s %s, %8d unknowns, %7d elements, %d blocks (setup %.2f s, %d+%d steps, "
              "first %.2f s; load %.2f-%.2f):\n",
              r.kind.c_str(), r.name.c_str(), r.unknowns, r.elements, r.blocks, r.setup_seconds,
              static_cast<int>(m.before.steps), m.steps, r.warmup_seconds, r.load_before,
              r.load_after);
  std::printf("  step %.4f s = detection %.4f + constraints %.4f + assembly %.4f + contact %.4f + "
              "factorisation %.4f + solve %.4f + update %.4f + control %.4f (+ pattern %.4f, "
              "analysis %.4f)\n",
              m.per_step, detection, constraints, assembly, contact, factorization, solve, update,
              control, pattern, analysis);
  std::printf("  in the measured steps: %ld cuts, %.1f factorisations per step, %ld pattern "
              "builds (each with a symbolic analysis), %ld plan rebuilds\n",
              cuts, factorizations, patterns, plans);
  std::printf("  bare CHOLMOD factor + solve %.4f s (mean of %d after the steps, %.3g flops); step "
              "/ bare = %.2f, step / (bare x factorisations per step) = %.2f\n",
              m.bare, m.bare_count, m.bare_flops, ratio, m.per_step / solver_floor);
  if (r.output_seconds >= 0.0)
    std::printf("  output %.4f s (%.1f MB) per output step; (step + output) / bare = %.2f\n",
                r.output_seconds, r.output_bytes / 1e6, (m.per_step + r.output_seconds) / m.bare);
  if (json)
    std::printf(
        "{\"kind\": \"%s\", \"name\": \"%s\", \"unknowns\": %d, \"elements\": %d, \"blocks\": %d, "
        "\"setup_seconds\": %.6g, \"warmup_steps\": %ld, \"warmup_seconds\": %.6g, \"steps\": %d, "
        "\"step_cuts\": %ld, \"factorizations_per_step\": %.6g, \"pattern_builds\": %ld, "
        "\"plan_rebuilds\": %ld, \"seconds_step\": %.6g, \"parts\": {\"detection\": %.6g, "
        "\"constraints\": %.6g, \"pattern\": %.6g, \"assembly\": %.6g, \"contact\": %.6g, "
        "\"analysis\": %.6g, \"factorization\": %.6g, \"solve\": %.6g, \"update\": %.6g, "
        "\"control\": %.6g}, \"bare_seconds\": %.6g, \"bare_count\": %d, \"bare_flops\": %.6g, "
        "\"output_seconds\": "
        "%.6g, \"output_bytes\": %.6g, \"load_before\": %.3g, \"load_after\": %.3g}\n",
        r.kind.c_str(), r.name.c_str(), r.unknowns, r.elements, r.blocks, r.setup_seconds,
        m.before.steps, r.warmup_seconds, m.steps, cuts, factorizations, patterns, plans,
        m.per_step, detection, constraints, pattern, assembly, contact, analysis, factorization,
        solve, update, control, m.bare, m.bare_count, m.bare_flops, r.output_seconds,
        r.output_bytes, r.load_before, r.load_after);
  std::fflush(stdout);
}

struct Options {
  int order = 0;
  std::vector<double> sizes;
  std::string case_file;
  int warmup = 1;
  int steps = 0; ///< 0: the mode's default
  bool output = true;
  bool json = false;
};

Report run_beam(const Options& options, double target_dofs) {
  // A 4 m x 1 m beam clamped at x = 0 under gravity, dynamic, 1 ms steps.
  Report r;
  r.kind = "beam";
  r.name = "order " + std::to_string(options.order);
  r.load_before = nmm::bench::load_average();
  nmm::PhysicalMesh physical;
  physical.source = "bench";
  physical.regions.push_back({"rock", {{{{0, 0}, {4, 0}, {4, 1}, {0, 1}}, {}}}});
  physical.curves.push_back({"clamp", {{{0, 0}, {0, 1}}}});
  nmm::validate_physical_mesh(physical);
  const double per_node = options.order == 0 ? 2.0 : 6.0;
  const double size = std::sqrt(4.0 * 2.0 * per_node / (std::sqrt(3.0) * target_dofs));
  Clock::time_point t = Clock::now();
  const nmm::MathMesh math =
      nmm::make_regular_math_mesh(nmm::material_bounding_box(physical), size);
  const nmm::CoverSystem covers = nmm::build_cover_system(math, physical, {});
  nmm::ElasticMaterial rock;
  rock.name = "rock";
  rock.young = 5e9;
  rock.poisson = 0.25;
  rock.density = 2600;
  nmm::ModelOptions model_options;
  model_options.order = options.order;
  nmm::Model model = nmm::make_model(covers, math, {rock}, model_options);
  r.setup_seconds = since(t);
  nmm::Scene scene;
  scene.supports =
      nmm::curve_support_points(model, 0, true, true, nmm::SupportMethod::exact, "clamp");
  scene.body_loads.push_back({{0.0, -9.81}, {}});
  nmm::StepperOptions stepper_options;
  stepper_options.time_step = 1e-3;
  const std::vector<nmm::Point2> initial_points = nmm::step_points(model);
  nmm::TimeStepper stepper(model, scene, stepper_options);
  t = Clock::now();
  (void)stepper.step(1.0); // first step: pattern and symbolic analysis
  r.warmup_seconds = since(t);
  const int steps = options.steps > 0 ? options.steps : target_dofs > 5e5 ? 3 : 5;
  r.measured = measure_steps(stepper, steps, 1.0);
  if (options.output) {
    // Output as `nmm run` writes it at an output step: the step's .vtu (the .pvd rewrite is
    // a few lines and left out).
    const std::filesystem::path vtu =
        std::filesystem::temp_directory_path() / "nmm_bench_step_output.vtu";
    t = Clock::now();
    for (int i = 0; i < steps; ++i)
      nmm::write_vtu(
          vtu, nmm::make_step_data(model, initial_points, stepper.velocity(), stepper.time()));
    r.output_seconds = since(t) / steps;
    r.output_bytes = static_cast<double>(std::filesystem::file_size(vtu));
    std::filesystem::remove(vtu);
  }
  r.unknowns = stepper.n_unknowns();
  r.elements = model.n_elements();
  r.blocks = covers.n_blocks();
  r.load_after = nmm::bench::load_average();
  return r;
}

Report run_case_file(const Options& options) {
  Report r;
  r.kind = "case";
  r.name = options.case_file;
  r.load_before = nmm::bench::load_average();
  Clock::time_point t = Clock::now();
  nmm::CaseAnalysis analysis(nmm::read_case_file(options.case_file));
  if (analysis.spec().analysis.initial_equilibrium)
    analysis.equilibrate();
  r.setup_seconds = since(t);
  nmm::TimeStepper& stepper = analysis.stepper();
  const double until =
      analysis.spec().analysis.end_time.value_or(std::numeric_limits<double>::infinity());
  t = Clock::now();
  for (int i = 0; i < options.warmup && stepper.time() < until * (1.0 - 1e-12); ++i)
    (void)stepper.step(until);
  r.warmup_seconds = since(t);
  r.measured = measure_steps(stepper, options.steps > 0 ? options.steps : 3, until);
  r.unknowns = stepper.n_unknowns();
  r.elements = analysis.model().n_elements();
  r.blocks = analysis.geometry().covers.n_blocks();
  r.load_after = nmm::bench::load_average();
  return r;
}

[[noreturn]] void usage(const char* what) {
  std::fprintf(stderr,
               "bench_step: %s\nusage: bench_step [ORDER] [DOFS...] [--steps K] [--no-output] "
               "[--json]\n       bench_step --case FILE [--warmup N] [--steps K] [--json]\n",
               what);
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options options;
  bool has_order = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        usage((arg + " needs a value").c_str());
      return argv[++i];
    };
    if (arg == "--case")
      options.case_file = value();
    else if (arg == "--warmup")
      options.warmup = std::atoi(value().c_str());
    else if (arg == "--steps")
      options.steps = std::atoi(value().c_str());
    else if (arg == "--no-output")
      options.output = false;
    else if (arg == "--json")
      options.json = true;
    else if (arg.rfind("--", 0) == 0)
      usage(("unknown option " + arg).c_str());
    else if (!has_order) {
      options.order = std::atoi(arg.c_str());
      has_order = true;
    } else
      options.sizes.push_back(std::atof(arg.c_str()));
  }
  if (options.warmup < 0 || options.steps < 0)
    usage("--warmup and --steps must not be negative");
  if (options.sizes.empty())
    options.sizes = {1e4, 1e5, 1e6};
  return options;
}

} // namespace

int main(int argc, char** argv) {
  nmm::limit_threads(nmm::available_cores());
  const Options options = parse(argc, argv);
  try {
    if (!options.case_file.empty()) {
      print(run_case_file(options), options.json);
      return 0;
    }
    for (const double dofs : options.sizes)
      print(run_beam(options, dofs), options.json);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_step: %s\n", e.what());
    return 1;
  }
  return 0;
}
