// SPDX-License-Identifier: MIT
// io/cli.cpp — the `nmm` command. The only place that catches everything and exits.
#include "io/demo.hpp"
#include "io/dependency_info.hpp"
#include "mesh/error.hpp"
#include "solver/threads.hpp"

#include <CLI/CLI.hpp>

#include <exception>
#include <iostream>
#include <stdexcept>

namespace {

constexpr int exit_ok = 0;
constexpr int exit_input_error = 2;
constexpr int exit_numerical_error = 3;
constexpr int exit_internal_error = 4;

int run(int argc, char** argv) {
  CLI::App app{"nmm: 2D numerical manifold method (NMM, DDA and VEM blocks)", "nmm"};
  app.set_version_flag("--version", [] {
    return std::string("nmm ") + NMM_VERSION + "\n" + nmm::dependency_report();
  });
  int threads = nmm::available_cores();
  app.add_option("--threads", threads, "Threads for the linear solver (default: usable cores)")
      ->check(CLI::Range(1, 1024));
  app.footer("With no command, runs the bundled demonstration.\n"
             "Examples:\n"
             "  nmm                 run the bundled demonstration\n"
             "  nmm demo            print Shi's simplex-integration tables\n"
             "  nmm --version       versions of nmm and every library it uses");
  CLI::App* demo = app.add_subcommand("demo", "Print Shi's simplex-integration tables");
  app.require_subcommand(0, 1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? exit_ok : exit_input_error;
  }
  nmm::limit_threads(threads);

  if (app.get_subcommands().empty() || demo->parsed()) {
    return nmm::run_simplex_integration_demo(std::cout) ? exit_ok : exit_numerical_error;
  }
  return exit_ok;
}

} // namespace

int main(int argc, char** argv) {
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
