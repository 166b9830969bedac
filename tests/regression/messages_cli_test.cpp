// SPDX-License-Identifier: MIT
// Messages of the `nmm` program a user can act on (issue 43, item 5): a restart of an edited
// case warns before its first step, a block too small for the cover mesh is warned about in
// the same words on the terminal and in summary.json, and an output file that cannot be
// written is nmm's message (file, reason, what to do) with none of VTK's own text.
#include "../support/case_fixtures.hpp"
#include "../support/json_reader.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::parse_json;
using testing::ProcessResult;
using testing::read_text;
using testing::replaced;

const fs::path nmm_program = NMM_EXECUTABLE;

class Messages : public testing::NmmTest {
protected:
  Messages() : NmmTest(nmm_program, "nmm_messages_cli") {}
};

void expect_all(const std::string& text, const std::vector<std::string>& parts) {
  for (const std::string& part : parts)
    EXPECT_NE(text.find(part), std::string::npos) << "\"" << part << "\" not in:\n" << text;
}

/// Fails when @p err holds any of VTK's own text: its class names, its logger's level tag,
/// the source line headers of its errors, object addresses.
void expect_no_vtk_text(const std::string& err) {
  for (const char* part :
       {"vtkXML", "vtkExecutive", "vtkCompositeDataPipeline", "ERR|", "ERROR: In ", ".cxx", "(0x"})
    EXPECT_EQ(err.find(part), std::string::npos) << "\"" << part << "\" in:\n" << err;
}

TEST_F(Messages, RestartOfAnEditedCaseWarnsBeforeItsFirstStep) {
  std::string text = replaced(testing::plate_case, "kind = \"static\"\nsteps = 3",
                              "kind = \"dynamic\"\nsteps = 8\ntime_step = 1.0e-4");
  const fs::path file = testing::write_case(dir(), text);
  const fs::path out = dir() / "out";
  ASSERT_EQ(nmm({"run", file.string(), "-o", out.string(), "--steps", "3", "--quiet"}).exit_code,
            0);
  testing::write_text(file, replaced(text, "every = 2", "every = 4"));
  const ProcessResult restart = nmm({"run", file.string(), "--restart", out.string()});
  ASSERT_EQ(restart.exit_code, 0) << restart.err;
  const std::string warning = "the case file changed since the checkpoint";
  const std::size_t warned = restart.err.find("warning: " + warning);
  ASSERT_NE(warned, std::string::npos) << restart.err;
  const std::size_t first_step = restart.err.find("step 4/8");
  ASSERT_NE(first_step, std::string::npos) << restart.err;
  EXPECT_LT(warned, first_step) << restart.err;
  // Listed once more in the closing summary and in summary.json, in the same words.
  expect_all(restart.out, {"warnings: 1", warning});
  const testing::Json summary = parse_json(read_text(out / "summary.json"));
  ASSERT_EQ(summary.at("warnings").items.size(), 1u);
  expect_all(summary.at("warnings").items[0].string, {warning});
  EXPECT_NE(restart.out.find(summary.at("warnings").items[0].string), std::string::npos);
}

TEST_F(Messages, TinyBlockIsWarnedAboutInTheSameWordsOnTheTerminalAndInTheSummary) {
  // A joint cutting a 1 cm corner off the plate (tests/unit/io/messages_test.cpp).
  testing::write_text(dir() / "corner.geo", testing::corner_geo());
  const fs::path file =
      testing::write_case(dir(), replaced(testing::plate_case, "plate.geo", "corner.geo") +
                                     "[joints.cut]\nfriction_angle = 30.0\n");
  const fs::path out = dir() / "out";
  const ProcessResult run = nmm({"run", file.string(), "-o", out.string(), "--steps", "1"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const testing::Json summary = parse_json(read_text(out / "summary.json"));
  bool found = false;
  for (const auto& item : summary.at("warnings").items) {
    if (item.string.find("is too small for the cover mesh") == std::string::npos)
      continue;
    found = true;
    expect_all(item.string, {"around (1.995, 0.005)", "trim joint \"cut\""});
    EXPECT_NE(run.err.find("warning: " + item.string + "\n"), std::string::npos) << run.err;
    EXPECT_NE(run.out.find("    " + item.string + "\n"), std::string::npos) << run.out;
  }
  EXPECT_TRUE(found) << run.out;
}

/// The plate at a cover size of 0.05 m: a first step file of far more than 4 KiB.
fs::path fine_plate(const fs::path& dir) {
  return testing::write_case(dir, replaced(testing::plate_case, "size = 0.3", "size = 0.05"));
}

TEST_F(Messages, StepFileBeyondTheFileSizeLimitIsNmmsMessageWithoutVtksText) {
  const fs::path file = fine_plate(dir());
  const fs::path out = dir() / "out";
  const ProcessResult run =
      testing::run_process({"/bin/bash", "-c", "ulimit -f 4 && exec \"$0\" run \"$1\" -o \"$2\"",
                            nmm_program.string(), file.string(), out.string()},
                           dir() / "ulimit");
  EXPECT_EQ(run.exit_code, 2) << run.err;
  expect_all(run.err, {"error: file too large: cannot write '" +
                           (out / "step_000000.vtu").string() + "' (File too large)",
                       "ulimit -f", "what it wrote so far is in"});
  expect_no_vtk_text(run.err);
}

TEST_F(Messages, StepFileOnAFullDiskIsNmmsMessageWithoutVtksText) {
  // A tmpfs of 12 KiB in a user and mount namespace of our own (unshare -rm): summary.json
  // and history.csv fit, the first step file does not.
  const fs::path file = fine_plate(dir());
  const fs::path disk = dir() / "disk";
  fs::create_directories(disk);
  const ProcessResult probe =
      testing::run_process({"/usr/bin/unshare", "-rm", "/bin/sh", "-c",
                            "mount -t tmpfs -o size=12k nmm \"$0\"", disk.string()},
                           dir() / "probe");
  if (probe.exit_code != 0)
    GTEST_SKIP() << "no tmpfs in a user namespace here (unshare -rm): " << probe.err;
  const ProcessResult run = testing::run_process(
      {"/usr/bin/unshare", "-rm", "/bin/sh", "-c",
       "mount -t tmpfs -o size=12k nmm \"$0\" || exit 99; exec \"$1\" run \"$2\" -o \"$0/out\"",
       disk.string(), nmm_program.string(), file.string()},
      dir() / "full");
  ASSERT_NE(run.exit_code, 99) << run.err;
  EXPECT_EQ(run.exit_code, 2) << run.err;
  expect_all(run.err,
             {"error: disk full: cannot write '" + (disk / "out" / "step_000000.vtu").string(),
              "No space left on device", "free space on the disk of"});
  expect_no_vtk_text(run.err);
}

} // namespace
} // namespace nmm
