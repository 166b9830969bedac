// SPDX-License-Identifier: MIT
// Checkpoint and restart (issue 7, "nmm run CASE.toml --restart DIR continues from the last
// checkpoint and gives the same result as an uninterrupted run"): bundled examples of every
// kind (friction and step cuts, many blocks, DDA and VEM blocks, static analysis with the
// automatic step, load steps with bonded joints, order-1 covers) are run straight through,
// and stopped part way and restarted; history.csv and the last step's files must be the
// same to the last byte. Also a run that went on past its checkpoint and was then lost
// (killed after a periodic checkpoint): the restart drops what came after the checkpoint.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;
using testing::read_text;
using testing::fs::path;

struct RestartCase {
  std::string case_file; ///< under examples/
  long steps = 0;        ///< of the whole run
  long stop = 0;         ///< where the first part stops
};

void PrintTo(const RestartCase& c, std::ostream* out) {
  *out << c.case_file << ", " << c.steps << " steps, stopped after " << c.stop;
}

std::string name_of(const RestartCase& c) {
  std::string name = c.case_file.substr(0, c.case_file.rfind(".toml"));
  std::replace_if(
      name.begin(), name.end(), [](char ch) { return !std::isalnum(ch); }, '_');
  return name;
}

std::string step_file(long step) {
  std::ostringstream name;
  name << "step_" << std::setw(6) << std::setfill('0') << step << ".vtu";
  return name.str();
}

std::string contact_file(long step) {
  std::ostringstream name;
  name << "contacts_" << std::setw(6) << std::setfill('0') << step << ".vtp";
  return name.str();
}

/// The lines of @p file but those of step @p step (blocks.csv rows start with the step).
std::string rows_but_step(const path& file, long step) {
  std::istringstream in(read_text(file));
  std::string kept;
  const std::string prefix = std::to_string(step) + ",";
  for (std::string line; std::getline(in, line);)
    if (line.rfind(prefix, 0) != 0)
      kept += line + "\n";
  return kept;
}

class Restart : public Example {
protected:
  /// The straight run and the restarted one agree to the byte: history.csv (every step's
  /// time, dt, iterations, contacts, energies and monitors at 17 digits) and the last
  /// step's VTK files (geometry, displacements, velocities, stresses, contact forces).
  /// Exact, not within a tolerance: the checkpoint stores every real bit for bit and the
  /// restarted run rebuilds the same sparsity pattern and slaves, so it does the same
  /// arithmetic in the same order; any state not carried (a contact's anchor, the energy
  /// budget, the last step's slaves) changes digits within a few steps.
  /// blocks.csv too, but for the rows of step @p stop: the stopped run wrote its last step
  /// there as a step file, with its blocks.csv rows, and the restart keeps both.
  void expect_same_run(const path& straight, const path& restarted, long steps, long stop) {
    EXPECT_EQ(read_text(restarted / "history.csv"), read_text(straight / "history.csv"));
    EXPECT_EQ(rows_but_step(restarted / "blocks.csv", stop),
              rows_but_step(straight / "blocks.csv", stop));
    const path last = straight / step_file(steps);
    ASSERT_TRUE(testing::fs::exists(last));
    EXPECT_EQ(read_text(restarted / step_file(steps)), read_text(last));
    if (testing::fs::exists(straight / contact_file(steps))) {
      EXPECT_EQ(read_text(restarted / contact_file(steps)),
                read_text(straight / contact_file(steps)));
    }
  }
};

class RestartExample : public Restart, public ::testing::WithParamInterface<RestartCase> {};

TEST_P(RestartExample, StoppedAndRestartedRunEqualsTheStraightRunToTheLastBit) {
  const RestartCase& c = GetParam();
  const path case_file = path(NMM_EXAMPLES_DIR) / c.case_file;
  const std::string name = name_of(c);
  const ExampleRun straight =
      run_case(case_file, name + "_straight", {"--steps", std::to_string(c.steps)});
  ASSERT_EQ(straight.summary.at("steps").number, static_cast<double>(c.steps));

  const ExampleRun first = run_case(case_file, name, {"--steps", std::to_string(c.stop)});
  ASSERT_EQ(first.summary.at("steps").number, static_cast<double>(c.stop));
  ASSERT_TRUE(testing::fs::exists(dir() / name / "checkpoint.nmm"));
  const path out = dir() / name;
  const ExampleRun restarted =
      run_case(case_file, name, {"--restart", out.string(), "--steps", std::to_string(c.steps)});
  EXPECT_EQ(restarted.summary.at("steps").number, static_cast<double>(c.steps));
  EXPECT_EQ(restarted.summary.at("step_cuts").number, straight.summary.at("step_cuts").number);
  EXPECT_EQ(restarted.summary.at("counters").at("contact_searches").number,
            straight.summary.at("counters").at("contact_searches").number);
  expect_same_run(dir() / (name + "_straight"), out, c.steps, c.stop);
}

INSTANTIATE_TEST_SUITE_P(
    Examples,
    RestartExample,
    ::testing::Values(RestartCase{"03_block_on_incline/case.toml", 50, 20},
                      RestartCase{"04_dam_on_jointed_foundation/case.toml", 12, 5},
                      RestartCase{"08_multi_block_slope/case.toml", 50, 23},
                      RestartCase{"09_block_arch/case.toml", 30, 13},
                      RestartCase{"10_rotating_triangle/case.toml", 12, 5},
                      RestartCase{"10_rotating_triangle/case_vem.toml", 12, 5},
                      RestartCase{"12_tunnel_36_blocks/case_phi30.toml", 10, 4},
                      RestartCase{"13_block_wall_70/case_vem.toml", 20, 9}),
    [](const ::testing::TestParamInfo<RestartCase>& param) { return name_of(param.param); });

TEST_F(Restart, ByConjugateGradientsEqualsTheStraightRunToTheLastBit) {
  // [analysis] solver = "pcg": a solve's first guess comes from the saved velocities, and a
  // pattern given up on in one step is tried again in the next (LinearSolver::start_step()),
  // so the restarted run iterates exactly as the straight one. The 70-block DDA wall: every
  // system by conjugate gradients. The jointed double cantilever: static steps, every
  // system left to CHOLMOD, on one sparsity pattern from step 2 on: without start_step() the
  // straight run would have given up on it for good and the restarted one try again.
  for (const RestartCase& c : {RestartCase{"13_block_wall_70", 12, 5},
                               RestartCase{"16_jointed_double_cantilever", 5, 3}}) {
    const std::string& name = c.case_file;
    const path case_file = dir() / (name + "_pcg.toml");
    testing::write_text(case_file, testing::example_variant(name, "case.toml", "solver = \"pcg\""));
    const std::string steps = std::to_string(c.steps);
    const ExampleRun straight = run_case(case_file, name + "_straight", {"--steps", steps});
    ASSERT_EQ(straight.summary.at("steps").number, static_cast<double>(c.steps));
    EXPECT_GT(straight.summary.at("counters").at("cg_iterations").number, 0.0);
    const ExampleRun first = run_case(case_file, name, {"--steps", std::to_string(c.stop)});
    ASSERT_EQ(first.summary.at("steps").number, static_cast<double>(c.stop));
    const path out = dir() / name;
    const ExampleRun restarted =
        run_case(case_file, name, {"--restart", out.string(), "--steps", steps});
    EXPECT_EQ(restarted.summary.at("counters").at("cg_iterations").number,
              straight.summary.at("counters").at("cg_iterations").number)
        << name;
    EXPECT_EQ(restarted.summary.at("counters").at("cg_fallbacks").number,
              straight.summary.at("counters").at("cg_fallbacks").number)
        << name;
    expect_same_run(dir() / (name + "_straight"), out, c.steps, c.stop);
  }
}

TEST_F(Restart, WithNmmBlocksTurnedExactlyEqualsTheStraightRunToTheLastBit) {
  // examples/15's sliding mass on order-1 covers with `exact_rotation = true`: its order-1
  // dependency fixes are chosen again after every step for the turned geometry, and after
  // the checkpoint's model is loaded (TimeStepper::load_state), as after the step it ended.
  const std::string name = "15_circular_sliding";
  std::string text = testing::example_variant(name, "case.toml", "");
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"order = 0", "order = 1"},
        {"[materials.soil]\n", "[materials.soil]\nexact_rotation = true\n"}}) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const path case_file = dir() / (name + "_exact.toml");
  testing::write_text(case_file, text);
  const ExampleRun straight = run_case(case_file, name + "_straight", {"--steps", "12"});
  ASSERT_EQ(straight.summary.at("steps").number, 12.0);
  const ExampleRun first = run_case(case_file, name, {"--steps", "5"});
  ASSERT_EQ(first.summary.at("steps").number, 5.0);
  const path out = dir() / name;
  const ExampleRun restarted =
      run_case(case_file, name, {"--restart", out.string(), "--steps", "12"});
  EXPECT_EQ(restarted.summary.at("steps").number, 12.0);
  expect_same_run(dir() / (name + "_straight"), out, 12, 5);
}

// A run lost after its checkpoint (killed, machine down) has history rows and step files
// past it; the restart continues from the checkpoint and drops them. Made deterministic by
// putting back an earlier checkpoint: stop at 20, keep its checkpoint, go on to 30, put the
// step-20 checkpoint back, restart.
TEST_F(Restart, FromAnOlderCheckpointDropsTheRowsAndFilesAfterIt) {
  const path case_file = path(NMM_EXAMPLES_DIR) / "03_block_on_incline/case.toml";
  const path out = dir() / "lost";
  static_cast<void>(run_case(case_file, "straight", {"--steps", "50"}));
  static_cast<void>(run_case(case_file, "lost", {"--steps", "20"}));
  testing::fs::copy_file(out / "checkpoint.nmm", dir() / "checkpoint_20.nmm");
  static_cast<void>(run_case(case_file, "lost", {"--restart", out.string(), "--steps", "30"}));
  ASSERT_EQ(testing::read_history_columns(out / "history.csv").at("step").size(), 30U);
  ASSERT_TRUE(testing::fs::exists(out / step_file(30)));
  testing::fs::copy_file(dir() / "checkpoint_20.nmm", out / "checkpoint.nmm",
                         testing::fs::copy_options::overwrite_existing);
  const ExampleRun restarted =
      run_case(case_file, "lost", {"--restart", out.string(), "--steps", "50"});
  EXPECT_EQ(restarted.summary.at("steps").number, 50.0);
  EXPECT_FALSE(testing::fs::exists(out / step_file(30)));
  EXPECT_EQ(read_text(out / "case.pvd").find(step_file(30)), std::string::npos);
  expect_same_run(dir() / "straight", out, 50, 20);
}

} // namespace
} // namespace nmm
