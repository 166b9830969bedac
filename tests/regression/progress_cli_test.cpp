// SPDX-License-Identifier: MIT
// The progress of `nmm run` as a user sees it in a log (issue 43, item 4): a run whose steps
// are cut says why on its progress line, and the lines stay plain (no carriage returns).
#include "../support/case_fixtures.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::ProcessResult;
using testing::replaced;

const fs::path nmm_program = NMM_EXECUTABLE;

class ProgressCli : public testing::NmmTest {
protected:
  ProgressCli() : NmmTest(nmm_program, "nmm_progress_cli") {}
};

TEST_F(ProgressCli, RunWhoseStepsAreCutSaysWhy) {
  // The plate of the fixtures, dynamic with the automatic time step: Shi's step (8.5) counts
  // body and point loads, not the traction on "right", so the first steps move further than
  // the limit and are cut to it.
  const std::string text =
      replaced(replaced(testing::plate_case, "kind = \"static\"\nsteps = 3",
                        "kind = \"dynamic\"\nsteps = 4\nmax_step_displacement = 1.0e-5"),
               "traction = [1.0e5, 0.0]", "traction = [1.0e7, 0.0]");
  const fs::path file = testing::write_case(dir(), text);
  const ProcessResult run = nmm({"run", file.string(), "-o", (dir() / "out").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  // The last step's progress line, with the run's cuts by reason.
  const std::size_t last = run.err.find("step 4/4");
  ASSERT_NE(last, std::string::npos) << run.err;
  const std::string line = run.err.substr(last, run.err.find('\n', last) - last);
  EXPECT_NE(line.find(" (displacement "), std::string::npos) << line;
  EXPECT_EQ(run.err.find('\r'), std::string::npos) << "stderr is a file: plain lines";
}

} // namespace
} // namespace nmm
