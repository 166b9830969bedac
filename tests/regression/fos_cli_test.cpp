// SPDX-License-Identifier: MIT
// `nmm fos CASE -o DIR` end to end (issue 46, item 7): a DDA block on a 20 degree plane with
// a joint of 30 degrees writes DIR/fos.json (factor_of_safety, bracket, status, criterion,
// failing_blocks, trials) and prints "factor of safety: F", F = tan 30 / tan 20 = 1.5863 to
// the search's 1%; a case without strength, and a bad [fos] value, are refused with the file,
// line and table before anything is written (exit code 2).
#include "../support/json_reader.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <regex>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::parse_json;
using testing::ProcessResult;
using testing::read_text;
using testing::write_text;

const fs::path nmm_program = NMM_EXECUTABLE;

class FosCli : public testing::NmmTest {
protected:
  FosCli() : NmmTest(nmm_program, "nmm_fos_cli") {}
};

// A 1 m x 0.5 m block on a ramp of 20 degrees (cos 20 = 0.93969262, sin 20 = 0.34202014).
constexpr const char* plane_geo = R"(c = 0.93969262078590843; s = 0.34202014332566871;
Point(1) = {0, 0, 0};
Point(2) = {0.5 * s, -0.5 * c, 0};
Point(3) = {6 * c + 0.5 * s, 6 * s - 0.5 * c, 0};
Point(4) = {6 * c, 6 * s, 0};
Point(5) = {2.5 * c, 2.5 * s, 0};
Point(6) = {3.5 * c, 3.5 * s, 0};
Point(7) = {3.5 * c - 0.5 * s, 3.5 * s + 0.5 * c, 0};
Point(8) = {2.5 * c - 0.5 * s, 2.5 * s + 0.5 * c, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 6};
Line(5) = {6, 5};
Line(6) = {5, 1};
Line(7) = {6, 7};
Line(8) = {7, 8};
Line(9) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-5, 7, 8, 9};
Plane Surface(2) = {2};
Physical Surface("ramp") = {1};
Physical Surface("block") = {2};
Physical Curve("slip") = {5};
Physical Curve("base") = {2};
)";

// Line numbers matter: [joints.slip] is line 14, [fos] line 26.
constexpr const char* plane_case = R"(geometry = "plane.geo"
[cover_mesh]
size = 0.25
[materials.ramp]
model = "dda"
density = 2500.0
young = 1.0e9
poisson = 0.25
[materials.block]
model = "dda"
density = 2500.0
young = 1.0e9
poisson = 0.25
[joints.slip]
friction_angle = 30.0
[contact]
friction_angle = 30.0
[[boundary]]
curve = "base"
fix = "xy"
[[load]]
gravity = [0.0, -9.81]
[analysis]
kind = "static"
steps = 1
[fos]
steps = 100
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos)
    text.replace(at, from.size(), to);
  return text;
}

TEST_F(FosCli, RoadCutWhoseBlocksCreepAtEveryStrengthWarnsThatItsFactorIsNoLimitState) {
  // examples/18's road cut without its [fos] table, so with the dynamic runs' time step of
  // 1 ms: a slab the reduced strength lets slide moves a dt^2 / 2 a static step, below the
  // settling of its 74 elastic blocks, which decays alike at every strength (last/first step
  // displacement about 0.1 on both sides of F = 0.96, where limit equilibrium gives
  // tan 25 / tan 35 = 0.666), so the search ends where that settling crosses decay = 0.1 and
  // must say that this is no limit state, and what to change.
  const fs::path example = fs::path(NMM_EXAMPLES_DIR) / "18_road_cut_joint_sets";
  std::string text = read_text(example / "case.toml");
  const std::size_t fos_table = text.rfind("\n[fos]");
  ASSERT_NE(fos_table, std::string::npos);
  text.resize(fos_table + 1);
  write_text(dir() / "case.toml", text);
  fs::copy_file(example / "road_cut.geo", dir() / "road_cut.geo");
  const fs::path out = dir() / "fos";
  const ProcessResult run = nmm({"fos", (dir() / "case.toml").string(), "-o", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const testing::Json fos = parse_json(read_text(out / "fos.json"));
  ASSERT_EQ(fos.at("warnings").items.size(), 1u);
  EXPECT_NE(fos.at("warnings").items[0].string.find("not a limit state"), std::string::npos)
      << fos.at("warnings").items[0].string;
  EXPECT_NE(run.err.find("warning: the trials at F = "), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("a longer [fos] time_step"), std::string::npos) << run.err;
}

TEST_F(FosCli, BlockOnAPlaneWritesFosJsonAndPrintsTheFactor) {
  write_text(dir() / "plane.geo", plane_geo);
  write_text(dir() / "case.toml", plane_case);
  const fs::path out = dir() / "fos";
  const ProcessResult run = nmm({"fos", (dir() / "case.toml").string(), "-o", out.string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const double expected =
      std::tan(30.0 * std::numbers::pi / 180.0) / std::tan(20.0 * std::numbers::pi / 180.0);
  std::smatch printed;
  ASSERT_TRUE(std::regex_search(run.out, printed, std::regex("factor of safety: ([0-9.]+)")))
      << run.out;
  EXPECT_NEAR(std::stod(printed[1].str()), expected, 0.01 * expected) << run.out;

  const testing::Json fos = parse_json(read_text(out / "fos.json"));
  std::vector<std::string> keys;
  for (const auto& [key, value] : fos.members)
    keys.push_back(key);
  for (const char* key : {"factor_of_safety", "bracket", "status", "criterion", "failing_blocks",
                          "warnings", "trials"})
    EXPECT_NE(std::find(keys.begin(), keys.end(), key), keys.end()) << key;
  EXPECT_EQ(fos.at("status").string, "found");
  const double factor = fos.at("factor_of_safety").number;
  EXPECT_NEAR(factor, expected, 0.01 * expected);
  // The printed factor is fos.json's, to its 4 digits.
  EXPECT_NEAR(std::stod(printed[1].str()), factor, 1e-3 * factor);
  const testing::Json& bracket = fos.at("bracket");
  ASSERT_EQ(bracket.items.size(), 2u);
  EXPECT_LT(bracket.items[0].number, factor);
  EXPECT_GT(bracket.items[1].number, factor);
  EXPECT_EQ(fos.at("failing_blocks").items.size(), 1u);
  EXPECT_TRUE(fos.at("warnings").items.empty());
  EXPECT_EQ(run.err.find("warning: "), std::string::npos) << run.err;
  const testing::Json& trials = fos.at("trials");
  ASSERT_GE(trials.items.size(), 3u);
  bool stood = false;
  bool failed = false;
  for (const testing::Json& trial : trials.items) {
    for (const char* key : {"factor", "failed", "steps", "measure"})
      EXPECT_NE(trial.find(key), nullptr) << key;
    (trial.at("failed").boolean ? failed : stood) = true;
    EXPECT_EQ(trial.at("steps").number, 100.0);
  }
  EXPECT_TRUE(stood);
  EXPECT_TRUE(failed);
}

TEST_F(FosCli, CaseWithoutStrengthIsRefusedNamingTheJointAndItsLine) {
  write_text(dir() / "plane.geo", plane_geo);
  std::string text = replaced(plane_case, "[joints.slip]\nfriction_angle = 30.0\n",
                              "[joints.slip]\nfriction_angle = 0.0\n");
  text = replaced(text, "[contact]\nfriction_angle = 30.0\n", "[contact]\n");
  write_text(dir() / "case.toml", text);
  const fs::path out = dir() / "fos";
  const ProcessResult run = nmm({"fos", (dir() / "case.toml").string(), "-o", out.string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("case.toml:14:"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("[joints.slip]"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("friction_angle"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(out)) << "nothing is written before the error";
}

TEST_F(FosCli, BadFosValueIsRefusedAtItsLine) {
  write_text(dir() / "plane.geo", plane_geo);
  write_text(dir() / "case.toml", replaced(plane_case, "[fos]\nsteps = 100\n",
                                           "[fos]\nsteps = 100\nbracket = [2.0, 1.0]\n"));
  const ProcessResult run = nmm({"fos", (dir() / "case.toml").string(), "-o", "unused"}, dir());
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("case.toml:28:"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("[fos] bracket"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir() / "unused"));
}

} // namespace
} // namespace nmm
