// SPDX-License-Identifier: MIT
// io/cli.cpp — the `nmm` command: run, mesh, check, fos, demo. The only place that catches
// everything and exits (exit codes: 0 ok, 2 input error, 3 numerical failure, 4 internal
// error, 130 interrupted).
#include "io/atomic_file.hpp"
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "io/checkpoint.hpp"
#include "io/cover_mesh_output.hpp"
#include "io/cover_warnings.hpp"
#include "io/demo.hpp"
#include "io/dependency_info.hpp"
#include "io/fos.hpp"
#include "io/progress.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"
#include "solver/threads.hpp"

#include <CLI/CLI.hpp>
#include <unistd.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <atomic>
#include <chrono>
#include <csignal>
#include <exception>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

namespace fs = std::filesystem;

constexpr int exit_ok = 0;
constexpr int exit_input_error = 2;
constexpr int exit_numerical_error = 3;
constexpr int exit_internal_error = 4;
constexpr int exit_interrupted = 130; // 128 + SIGINT, as shells report a Ctrl-C

/// Large buffers (a big scene's matrix, pattern and contact arrays: megabytes each) are
/// allocated anew in every step or try. glibc serves a block above its mmap threshold (128
/// KiB, growing only as far as the largest block freed) from fresh pages and unmaps it on
/// free, and trims the heap's top, so each step paid again for faulting in the pages it
/// touched: 23% of a step of the 10,004 DDA blocks of bench/rock_mass.py went to page
/// faults (perf, 2026-11-29). Served from the heap and kept there on free, they are reused:
/// that scene's steps 0.85 of the time, the 70-block wall's unchanged; the process keeps its
/// peak memory until it exits.
void keep_freed_memory() {
#ifdef __GLIBC__
  mallopt(M_MMAP_THRESHOLD, 1 << 30);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

// Set by SIGINT/SIGTERM; run_case() stops after the current step when it is true.
std::atomic<bool> stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free, "the signal handler needs a lock-free flag");

void on_stop_signal(int signal_number) {
  if (stop_requested.exchange(true)) {
    // A second Ctrl-C: stop at once, the way the user expects from a second press.
    std::signal(signal_number, SIG_DFL);
    std::raise(signal_number);
    return;
  }
  // Only async-signal-safe calls here: write(2), not iostreams.
  static constexpr char message[] =
      "\nnmm: stopping after this step (press Ctrl-C again to stop at once)\n";
  if (::write(STDERR_FILENO, message, sizeof message - 1) < 0) {
    // Nothing to do: the flag is set, the run stops anyway.
  }
}

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

/// The bundled example `nmm` runs without arguments.
fs::path bundled_example() { return fs::path(NMM_EXAMPLES_DIR) / "01_cantilever" / "case.toml"; }

struct RunArguments {
  std::string case_file;
  std::string output;
  bool quiet = false;
  /// --steps: at most this many steps (0: the case's `[analysis] steps`).
  long steps = 0;
  /// --restart: the output folder of the run to continue from its checkpoint.
  std::string restart;
};

int run_command(const RunArguments& args, bool is_bundled_example) {
  const auto start = std::chrono::steady_clock::now();
  const nmm::ProgressMode mode = args.quiet                ? nmm::ProgressMode::quiet
                                 : ::isatty(STDERR_FILENO) ? nmm::ProgressMode::terminal
                                                           : nmm::ProgressMode::lines;
  nmm::ProgressPrinter printer(std::cerr, mode);
  if (is_bundled_example)
    printer.phase("no command given: running the bundled example " + args.case_file +
                  " (nmm --help lists the commands)");
  nmm::CaseSpec spec = nmm::read_case_file(args.case_file);
  if (args.steps > 0 && args.steps < spec.analysis.steps)
    spec.analysis.steps = static_cast<int>(args.steps);
  const long steps = spec.analysis.steps;
  nmm::CaseAnalysis analysis(std::move(spec), [&](std::string_view text) { printer.phase(text); });
  for (const std::string& warning : analysis.warnings())
    printer.warning(warning);

  nmm::RunOptions options;
  options.output_dir = args.output;
  if (!args.restart.empty()) {
    // The run continues in its own folder: its history, series and step files are there.
    if (!args.output.empty() &&
        fs::weakly_canonical(args.output) != fs::weakly_canonical(args.restart))
      throw nmm::InputError("--restart " + args.restart +
                            " continues the run in that folder; "
                            "-o " +
                            args.output + " names another: leave -o out");
    options.output_dir = args.restart;
    options.restart = true;
  }
  options.stop = &stop_requested;
  options.on_warning = [&](const std::string& warning) { printer.warning(warning); };
  options.on_step = [&](const nmm::RunProgress& progress) {
    printer.step(progress, progress.report->step == progress.steps);
  };
  options.seconds_before = nmm::seconds_since(start);
  const fs::path dir = nmm::output_dir_of(analysis.spec(), options);
  std::ostringstream what;
  what << (options.restart
               ? "continuing from " + (dir / nmm::checkpoint_file_name).string() + " up to step "
               : std::string("running "))
       << steps << (steps == 1 ? " step" : " steps") << " (" << analysis.model().n_dofs()
       << " unknowns); output in " << dir.string();
  printer.phase(what.str());

  install_stop_handlers();
  nmm::RunResult result;
  try {
    result = nmm::run_case(analysis, options);
  } catch (const nmm::OutputWriteError&) {
    // A disk that filled or a file-size limit during the run: the files up to then stand.
    printer.finish();
    std::cerr << "nmm: the run stopped; what it wrote so far is in " << dir.string()
              << " (summary.json has the reason)\n";
    throw;
  } catch (const nmm::InputError&) {
    // The output folder could not be created or written: there is nothing to point to.
    printer.finish();
    throw;
  } catch (const std::exception&) {
    printer.finish();
    std::cerr << "nmm: the run stopped; what it wrote so far is in " << dir.string()
              << " (summary.json has the reason)\n";
    throw;
  }
  printer.finish();
  nmm::write_closing_summary(std::cout, result, steps);
  if (is_bundled_example) {
    std::cout << "  next:     open " << (result.output_dir / "case.pvd").string()
              << " in ParaView and colour by stress or displacement; the example and its "
                 "right answer are explained in "
              << (fs::path(NMM_EXAMPLES_DIR) / "01_cantilever" / "README.md").string() << '\n';
  }
  return result.status == nmm::RunStatus::interrupted ? exit_interrupted : exit_ok;
}

int mesh_command(const std::string& case_file, const std::string& output) {
  const nmm::CaseSpec spec = nmm::read_case_file(case_file);
  nmm::ProgressPrinter printer(std::cerr, nmm::ProgressMode::lines);
  const nmm::CaseGeometry geometry =
      nmm::build_case_geometry(spec, [&](std::string_view text) { printer.phase(text); });
  const fs::path dir = output.empty() ? spec.output.dir : fs::path(output);
  nmm::create_output_dir(dir);
  nmm::write_cover_mesh_vtu(dir / "mesh.vtu", geometry.covers);
  nmm::write_math_mesh_vtu(dir / "math_mesh.vtu", geometry.math, &geometry.covers);
  nmm::write_boundary_vtp(dir / "boundary.vtp", geometry.covers);
  for (const std::string& warning : spec.warnings)
    std::cout << "warning: " << warning << '\n';
  for (const std::string& warning : nmm::cover_system_warnings(spec, geometry))
    std::cout << "warning: " << warning << '\n';
  std::cout << "nmm: " << geometry.covers.n_elements() << " elements, "
            << geometry.covers.n_covers() << " covers, " << geometry.covers.n_blocks()
            << " blocks on " << geometry.math.n_triangles() << " math triangles\n"
            << "  outputs:  " << (dir / "mesh.vtu").string() << ", "
            << (dir / "math_mesh.vtu").string() << ", " << (dir / "boundary.vtp").string()
            << " (open them in ParaView)\n";
  return exit_ok;
}

int fos_command(const std::string& case_file, const std::string& output) {
  const nmm::CaseSpec spec = nmm::read_case_file(case_file);
  nmm::require_strength(spec); // before anything is written
  nmm::ProgressPrinter printer(std::cerr, nmm::ProgressMode::lines);
  for (const std::string& warning : spec.warnings)
    printer.warning(warning);
  const fs::path dir = output.empty() ? spec.output.dir : fs::path(output);
  printer.phase("strength reduction: " + std::to_string(spec.fos.steps) +
                " static steps a trial, bracket [" + nmm::number_text(spec.fos.bracket_low) + ", " +
                nmm::number_text(spec.fos.bracket_high) + "], tolerance " +
                nmm::number_text(spec.fos.tolerance));
  nmm::FosOptions options;
  options.on_trial = [&](const nmm::FosTrial& trial) {
    printer.phase("F = " + nmm::number_text(trial.factor, 6) + ": " +
                  (trial.failed ? "fails" : "stands") + " (last/first step displacement " +
                  nmm::number_text(trial.measure, 3) + ", last " +
                  nmm::number_text(trial.last_displacement, 3) + " m)" +
                  (trial.error.empty() ? std::string() : ": " + trial.error));
  };
  const nmm::FosResult result = nmm::find_factor_of_safety(spec, options);
  for (const std::string& warning : result.warnings)
    printer.warning(warning);
  printer.finish();
  nmm::create_output_dir(dir);
  nmm::write_fos_json(dir / "fos.json", spec, result);
  std::cout << nmm::fos_result_line(result) << '\n'
            << "  output:   " << (dir / "fos.json").string() << '\n';
  return exit_ok;
}

const char* plural(long n) { return n == 1 ? "" : "s"; }

int check_command(const std::string& case_file) {
  nmm::CaseSpec spec = nmm::read_case_file(case_file);
  nmm::CaseAnalysis analysis(std::move(spec));
  const nmm::CaseSpec& s = analysis.spec();
  const nmm::CaseGeometry& g = analysis.geometry();
  const nmm::Model& model = analysis.model();
  const nmm::Scene& scene = analysis.stepper().scene();
  std::cout << case_file << ": ok, ready to run\n"
            << "  geometry:   " << s.geometry.filename().string() << ": "
            << g.physical.regions.size() << " Physical Surface" << plural(g.physical.n_regions())
            << ", " << g.physical.curves.size() << " Physical Curve"
            << plural(static_cast<long>(g.physical.curves.size())) << ", "
            << g.physical.points.size() << " Physical Point"
            << plural(static_cast<long>(g.physical.points.size())) << '\n'
            << "  math mesh:  "
            << (s.cover_mesh.kind == nmm::CoverMeshKind::regular ? "regular" : "gmsh") << ", size "
            << s.cover_mesh.size << " m: " << g.math.n_triangles() << " triangles, "
            << g.math.n_nodes() << " nodes\n"
            << "  covers:     " << model.n_covers() << " covers (" << g.covers.stats.tiny_covers
            << " tiny), " << model.n_elements() << " elements (" << g.covers.stats.cut_triangles
            << " cut triangles), " << model.blocks.size() << " block"
            << plural(static_cast<long>(model.blocks.size())) << '\n'
            << "  unknowns:   " << model.n_dofs() << " (order " << model.order << ", "
            << model.dofs_per_cover() << " per cover)\n"
            << "  scene:      " << scene.supports.size() << " support points, "
            << scene.body_loads.size() << " body, " << scene.point_loads.size() << " point and "
            << scene.curve_loads.size() << " curve loads, " << scene.monitors.size() << " monitor"
            << plural(static_cast<long>(scene.monitors.size())) << '\n'
            << "  analysis:   "
            << (s.analysis.kind == nmm::AnalysisKind::dynamic ? "dynamic" : "static") << ", "
            << s.analysis.steps << " step" << plural(s.analysis.steps) << ", time step "
            << (s.analysis.time_step ? std::to_string(*s.analysis.time_step) + " s" : "auto")
            << ", output every " << s.output.every << " in " << s.output.dir.string() << '\n';
  if (analysis.warnings().empty()) {
    std::cout << "  warnings:   none\n";
  } else {
    std::cout << "  warnings:   " << analysis.warnings().size() << '\n';
    for (const std::string& warning : analysis.warnings())
      std::cout << "    " << warning << '\n';
  }
  return exit_ok;
}

int run(int argc, char** argv) {
  CLI::App app{"nmm: 2D numerical manifold method (NMM, DDA and VEM blocks)", "nmm"};
  app.set_version_flag("--version", [] {
    return std::string("nmm ") + NMM_VERSION + "\n" + nmm::dependency_report();
  });
  int threads = nmm::available_cores();
  app.add_option(
         "--threads", threads,
         "Threads for the linear solver and nmm's own parallel loops (default: usable cores)")
      ->check(CLI::Range(1, 1024));
  app.fallthrough(); // `nmm run case.toml --threads 2` as well as `nmm --threads 2 run ...`
  app.footer(
      "With no command, runs the bundled example (examples/01_cantilever) with output in ./out.\n"
      "\n"
      "Examples:\n"
      "  nmm                              run the bundled cantilever example into ./out\n"
      "  nmm run slope.toml               run a case; results go to its [output] dir\n"
      "  nmm run slope.toml -o results --quiet --threads 2\n"
      "  nmm run slope.toml --steps 10    only the first 10 steps\n"
      "  nmm run slope.toml --restart out continue the run in out/ from its last checkpoint\n"
      "  nmm mesh slope.toml -o mesh      write mesh.vtu, math_mesh.vtu, boundary.vtp only\n"
      "  nmm check slope.toml             read and check the case and its geometry, run nothing\n"
      "  nmm fos slope.toml -o fos        factor of safety by strength reduction: fos/fos.json\n"
      "  nmm demo                         print Shi's simplex-integration tables\n"
      "  nmm --version                    versions of nmm and every library it uses\n"
      "\n"
      "Outputs of run: case.pvd (open in ParaView), step_NNNNNN.vtu, history.csv, summary.json,\n"
      "checkpoint.nmm (for --restart).\n"
      "Ctrl-C stops after the current step and still writes them (press twice to stop at once).\n"
      "Exit codes: 0 ok, 2 input error, 3 numerical failure, 4 internal error, 130 interrupted.");

  RunArguments run_args;
  CLI::App* run_cmd = app.add_subcommand("run", "Run a case: VTK steps, history.csv, summary.json");
  run_cmd->add_option("case", run_args.case_file, "The case file (TOML)")->required();
  run_cmd->add_option("-o,--output", run_args.output,
                      "Output folder (default: [output] dir of the case, relative to it)");
  run_cmd->add_flag("-q,--quiet", run_args.quiet, "Print only the closing summary");
  run_cmd
      ->add_option("--steps", run_args.steps,
                   "Run at most N steps (fewer than [analysis] steps: a quick look)")
      ->check(CLI::Range(1L, 100'000'000L));
  run_cmd->add_option("--restart", run_args.restart,
                      "Continue the run whose output folder is DIR from its checkpoint.nmm "
                      "(written when a run stops and every [output] checkpoint_every steps)");

  std::string mesh_case;
  std::string mesh_output;
  CLI::App* mesh_cmd = app.add_subcommand(
      "mesh", "Write the cover mesh only: mesh.vtu, math_mesh.vtu and boundary.vtp");
  mesh_cmd->add_option("case", mesh_case, "The case file (TOML)")->required();
  mesh_cmd->add_option("-o,--output", mesh_output,
                       "Output folder (default: [output] dir of the case, relative to it)");

  std::string check_case;
  CLI::App* check_cmd = app.add_subcommand(
      "check", "Read the case and its geometry, resolve every name, build the covers; run nothing");
  check_cmd->add_option("case", check_case, "The case file (TOML)")->required();

  std::string fos_case;
  std::string fos_output;
  CLI::App* fos_cmd = app.add_subcommand(
      "fos", "Factor of safety by strength reduction of the joints ([fos] table): fos.json");
  fos_cmd->add_option("case", fos_case, "The case file (TOML)")->required();
  fos_cmd->add_option("-o,--output", fos_output,
                      "Output folder (default: [output] dir of the case, relative to it)");

  CLI::App* demo = app.add_subcommand("demo", "Print Shi's simplex-integration tables");
  app.require_subcommand(0, 1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? exit_ok : exit_input_error;
  }
  nmm::limit_threads(threads);

  if (demo->parsed())
    return nmm::run_simplex_integration_demo(std::cout) ? exit_ok : exit_numerical_error;
  if (run_cmd->parsed())
    return run_command(run_args, false);
  if (mesh_cmd->parsed())
    return mesh_command(mesh_case, mesh_output);
  if (check_cmd->parsed())
    return check_command(check_case);
  if (fos_cmd->parsed())
    return fos_command(fos_case, fos_output);
  RunArguments example;
  example.case_file = bundled_example().string();
  example.output = "out";
  return run_command(example, true);
}

} // namespace

int main(int argc, char** argv) {
  keep_freed_memory();
  // A file-size limit (ulimit -f) would kill the process by SIGXFSZ in the middle of a write;
  // ignored, the write fails with EFBIG and the run stops with a message and its files.
  std::signal(SIGXFSZ, SIG_IGN);
  try {
    return run(argc, argv);
  } catch (const nmm::InputError& e) {
    std::cerr << "error: " << e.what() << '\n';
    return exit_input_error;
  } catch (const nmm::NumericalError& e) {
    std::cerr << "numerical failure: " << e.what() << '\n';
    return exit_numerical_error;
  } catch (const std::exception& e) {
    std::cerr << "internal error: " << e.what() << '\n';
    return exit_internal_error;
  }
}
