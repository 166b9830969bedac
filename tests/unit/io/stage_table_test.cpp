// SPDX-License-Identifier: MIT
// The `[[stage]]` tables of a case file (docs/case-file.md "[[stage]]"; issue 46, item 3):
// their keys and the tables under them, the steps they add up to, a clear error at the line
// of every bad value, the excavations checked against the geometry, and a staged run that
// names its stage in history.csv and summary.json and leaves the excavated cells out of the
// step files.
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../../support/json_reader.hpp"
#include "../../support/process.hpp"
#include "../../support/vtk_readers.hpp"
#include <gtest/gtest.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <string>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::parse_json;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

// A 4 m x 2 m rock with a 1 m x 1 m "pit" in its top middle.
constexpr const char* pit_geo = R"(Point(1) = {0, 0, 0};
Point(2) = {4, 0, 0};
Point(3) = {4, 2, 0};
Point(4) = {2.5, 2, 0};
Point(5) = {1.5, 2, 0};
Point(6) = {0, 2, 0};
Point(7) = {1.5, 1, 0};
Point(8) = {2.5, 1, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 8};
Line(5) = {8, 7};
Line(6) = {7, 5};
Line(7) = {5, 6};
Line(8) = {6, 1};
Line(9) = {5, 4};
Curve Loop(1) = {1, 2, 3, 4, 5, 6, 7, 8};
Plane Surface(1) = {1};
Curve Loop(2) = {-6, -5, -4, -9};
Plane Surface(2) = {2};
Physical Surface("rock") = {1};
Physical Surface("pit") = {2};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
)";

// The stages go last (line 22 is the first [[stage]] header when appended).
constexpr const char* base_case = R"(geometry = "pit.geo"
[cover_mesh]
size = 0.25
[materials.rock]
density = 2500.0
young = 1.0e9
poisson = 0.25
[materials.pit]
density = 2500.0
young = 1.0e9
poisson = 0.25
[[boundary]]
curve = "bottom"
fix = "xy"
[[load]]
gravity = [0.0, -9.81]
[analysis]
kind = "static"
[[monitor]]
name = "floor"
point = [2.0, 0.999999]
)";

CaseSpec parse(const std::string& text) { return parse_case_text(text, "case.toml"); }

std::string error_of(const std::string& text) {
  try {
    (void)parse(text);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

constexpr const char* two_stages = R"([[stage]]
name = "in_situ"
steps = 2
[[stage]]
name = "dig"
steps = 3
kind = "dynamic"
excavate = ["pit"]
reset_displacement = true
[[stage.load]]
curve = "top"
pressure = 1.0e5
ramp = [0.0, 1.0]
[[stage.boundary]]
curve = "top"
fix = "x"
[[stage.bolt]]
from = [1.0, 1.5]
to = [3.0, 1.5]
stiffness = 1e8
)";

TEST(StageTable, KeysAndTheTablesUnderEachStage) {
  const CaseSpec spec = parse(std::string(base_case) + two_stages);
  ASSERT_EQ(spec.stages.size(), 2u);
  EXPECT_EQ(spec.stages[0].name, "in_situ");
  EXPECT_EQ(spec.stages[0].steps, 2);
  EXPECT_FALSE(spec.stages[0].kind);
  EXPECT_TRUE(spec.stages[0].excavate.empty());
  EXPECT_FALSE(spec.stages[0].reset_displacement);
  EXPECT_EQ(spec.stages[0].line, 22);
  EXPECT_EQ(spec.stages[1].kind, AnalysisKind::dynamic);
  EXPECT_EQ(spec.stages[1].excavate, std::vector<std::string>{"pit"});
  EXPECT_TRUE(spec.stages[1].reset_displacement);
  EXPECT_EQ(spec.analysis.steps, 5); // the stages' sum
  ASSERT_EQ(spec.loads.size(), 2u);  // gravity from the start, the pressure with "dig"
  EXPECT_EQ(spec.loads[0].stage, 0);
  EXPECT_EQ(spec.loads[1].stage, 1);
  ASSERT_EQ(spec.boundaries.size(), 2u);
  EXPECT_EQ(spec.boundaries[0].stage, 0);
  EXPECT_EQ(spec.boundaries[1].stage, 1);
  ASSERT_EQ(spec.bolts.size(), 1u);
  EXPECT_EQ(spec.bolts[0].stage, 1);
}

TEST(StageTable, BadValuesNameTheLineAndWhatToDo) {
  const std::string base = base_case;
  EXPECT_NE(
      error_of(base + "[[stage]]\nsteps = 2\n").find("case.toml:22:1: [[stage]] is missing name"),
      std::string::npos);
  EXPECT_NE(error_of(base + "[[stage]]\nname = \"a\"\n").find("is missing steps"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[[stage]]\nname = \"a b\"\nsteps = 1\n").find("contains ' '"),
            std::string::npos);
  EXPECT_NE(
      error_of(base + "[[stage]]\nname = \"a\"\nsteps = 1\n[[stage]]\nname = \"a\"\nsteps = 1\n")
          .find("is already used by the [[stage]] at line 22"),
      std::string::npos);
  EXPECT_NE(error_of(base + "[[stage]]\nname = \"a\"\nsteps = 1\nexcavate = \"pit\"\n")
                .find("must be a list of Physical Surface names"),
            std::string::npos);
  EXPECT_NE(error_of(base + "[[stage]]\nname = \"a\"\nsteps = 0\n").find("steps"),
            std::string::npos);
  std::string with_steps = base;
  with_steps.replace(with_steps.find("kind = \"static\""), 15, "kind = \"static\"\nsteps = 4");
  EXPECT_NE(error_of(with_steps + "[[stage]]\nname = \"a\"\nsteps = 1\n")
                .find("[analysis] steps cannot be given with [[stage]] tables"),
            std::string::npos);
  EXPECT_NE(error_of(base).find("[analysis] is missing steps"), std::string::npos);
  EXPECT_NE(
      error_of(base + "[[stage]]\nname = \"a\"\nsteps = 1\nexcavat = [\"pit\"]\n").find("excavat"),
      std::string::npos);
}

class StagedRun : public ::testing::Test {
protected:
  StagedRun() : dir_("nmm_stages") { write_text(dir_.path() / "pit.geo", pit_geo); }
  fs::path write(const std::string& stages) const {
    write_text(dir_.path() / "case.toml", base_case + stages);
    return dir_.path() / "case.toml";
  }
  std::string error_of(const std::string& stages) const {
    try {
      CaseAnalysis analysis(read_case_file(write(stages)));
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }
  const fs::path& dir() const { return dir_.path(); }

private:
  TempDir dir_;
};

TEST_F(StagedRun, ExcavationsAreCheckedAgainstTheGeometry) {
  const std::string unknown =
      error_of("[[stage]]\nname = \"a\"\nsteps = 1\nexcavate = [\"pitt\"]\n");
  EXPECT_NE(
      unknown.find("case.toml:22: [[stage]] \"a\" excavate \"pitt\" is not a Physical Surface"),
      std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("did you mean \"pit\""), std::string::npos) << unknown;
  EXPECT_NE(error_of("[[stage]]\nname = \"a\"\nsteps = 1\nexcavate = [\"pit\"]\n[[stage]]\nname = "
                     "\"b\"\nsteps = 1\nexcavate = [\"pit\"]\n")
                .find("excavates \"pit\", which an earlier stage (or this one) excavates already"),
            std::string::npos);
  EXPECT_NE(error_of("[[stage]]\nname = \"a\"\nsteps = 1\nexcavate = [\"pit\", \"rock\"]\n")
                .find("excavate all the material"),
            std::string::npos);
}

TEST_F(StagedRun, ALaterStagesPointOnExcavatedMaterialIsAnError) {
  // A point load in stage "b" at the pit's middle (2, 1.5), after stage "a" excavated the
  // pit: refused when the case is read, before the run writes anything.
  write_text(dir() / "pit.geo", std::string(pit_geo) + "Point(20) = {2.0, 1.5, 0};\n"
                                                       "Physical Point(\"middle\") = {20};\n");
  const std::string text =
      "[[stage]]\nname = \"a\"\nsteps = 1\nexcavate = [\"pit\"]\n[[stage]]\nname = \"b\"\n"
      "steps = 1\n[[stage.load]]\npoint = \"middle\"\nforce = [0.0, -1.0e3]\n";
  const std::string message = error_of(text);
  EXPECT_NE(message.find("[[load]] point \"middle\" at (2, 1.5) lies in \"pit\", which [[stage]] "
                         "\"a\" excavates, so it would act on nothing"),
            std::string::npos)
      << message;
  write_text(dir() / "pit.geo", pit_geo);
}

TEST_F(StagedRun, NamesItsStagesAndLeavesTheExcavatedCellsOut) {
  CaseAnalysis analysis(read_case_file(
      write("[[stage]]\nname = \"in_situ\"\nsteps = 1\n[[stage]]\nname = \"dig\"\nsteps = 2\n"
            "excavate = [\"pit\"]\nreset_displacement = true\n")));
  RunOptions options;
  options.output_dir = dir() / "out";
  (void)run_case(analysis, options);
  const std::string history = read_text(dir() / "out" / "history.csv");
  EXPECT_NE(history.find(",stage\n"), std::string::npos);
  EXPECT_NE(history.find(",in_situ\n"), std::string::npos);
  EXPECT_EQ(history.substr(history.size() - 5), ",dig\n");
  const testing::Json summary = parse_json(read_text(dir() / "out" / "summary.json"));
  EXPECT_EQ(summary.at("stage").string, "dig");
  ASSERT_EQ(summary.at("stages").items.size(), 2u);
  EXPECT_EQ(summary.at("stages").items[1].at("name").string, "dig");
  EXPECT_EQ(summary.at("stages").items[1].at("first_step").number, 2.0);
  EXPECT_EQ(summary.at("stages").items[1].at("steps").number, 2.0);
  // The floor of the pit rises: the pit's weight no longer presses on it.
  EXPECT_GT(analysis.monitor_values().front().uy, 0.0);
  const auto before = testing::read_vtu(dir() / "out" / "step_000001.vtu");
  const auto after = testing::read_vtu(dir() / "out" / "step_000003.vtu");
  EXPECT_LT(after->GetNumberOfCells(), before->GetNumberOfCells());
  // A staged run cannot be restarted from its checkpoint yet: a clear error.
  RunOptions restart;
  restart.output_dir = dir() / "out";
  restart.restart = true;
  CaseAnalysis again(read_case_file(dir() / "case.toml"));
  try {
    (void)run_case(again, restart);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("cannot be restarted yet"), std::string::npos);
  }
}

TEST_F(StagedRun, AStagesLoadActsFromItsStartOnly) {
  const auto floor_rise = [&](const std::string& extra) {
    CaseAnalysis analysis(read_case_file(
        write("[[stage]]\nname = \"in_situ\"\nsteps = 1\n[[stage]]\nname = \"dig\"\nsteps = 2\n"
              "excavate = [\"pit\"]\nreset_displacement = true\n" +
              extra)));
    RunOptions options;
    options.output_dir = dir() / "out_load";
    (void)run_case(analysis, options);
    return analysis.monitor_values().front().uy;
  };
  const double without = floor_rise("");
  // 1 MPa on the rock's top right of the pit, from the start of "dig": the floor rises less.
  const double with = floor_rise("[[stage.load]]\ncurve = \"top\"\npressure = 1.0e6\n");
  EXPECT_LT(with, without);
  // The same load from the start presses the pit too, whose stress the excavation then
  // releases with its own: the floor rises more than without any load.
  const double before = floor_rise("[[load]]\ncurve = \"top\"\npressure = 1.0e6\n");
  EXPECT_GT(before, without);
}

} // namespace
} // namespace nmm
