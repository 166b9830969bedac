// SPDX-License-Identifier: MIT
// The `[[bolt]]` tables of a case file (io/bolt_table.hpp, io/scene_bolts.hpp,
// docs/case-file.md "[[bolt]]"; issue 46, item 5): defaults and keys, a clear error at the
// line of every bad value, the bolts placed in the model (an end outside the material, both
// in one block, a curve that is no Physical Curve or not straight are errors), and what a run
// writes of them: history.csv's NAME.force, summary.json's bolts, the boundary .vtp's lines.
#include "io/case_file.hpp"
#include "io/case_runner.hpp"
#include "mesh/error.hpp"

#include "../../support/json_reader.hpp"
#include "../../support/process.hpp"
#include "../../support/vtk_readers.hpp"
#include <gtest/gtest.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>

#include <cmath>
#include <string>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::parse_json;
using testing::read_text;
using testing::TempDir;
using testing::write_text;

// A base 4 m x 1 m and a block 2 m x 1 m on it; the block's underside is the joint "slip";
// curves from the block into the base: "rod" straight, "pair" two straight ones, "arc" an
// arc.
constexpr const char* blocks_geo = R"(Point(1) = {0, 0, 0};
Point(2) = {4, 0, 0};
Point(3) = {4, 1, 0};
Point(4) = {3, 1, 0};
Point(5) = {1, 1, 0};
Point(6) = {0, 1, 0};
Point(7) = {3, 2, 0};
Point(8) = {1, 2, 0};
Point(9) = {2, 1.5, 0};
Point(10) = {2, 0.5, 0};
Point(11) = {1.5, 1.5, 0};
Point(12) = {1.4, 0.8, 0};
Point(13) = {2.5, 1.5, 0};
Point(14) = {2.6, 0.5, 0};
Point(15) = {2.5, 1.6, 0};
Point(16) = {2.5, 1.0, 0};
Point(17) = {3.1, 1.0, 0};
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 5};
Line(5) = {5, 6};
Line(6) = {6, 1};
Line(7) = {4, 7};
Line(8) = {7, 8};
Line(9) = {8, 5};
Curve Loop(1) = {1, 2, 3, 4, 5, 6};
Plane Surface(1) = {1};
Curve Loop(2) = {-4, 7, 8, 9};
Plane Surface(2) = {2};
Line(10) = {9, 10};
Line(11) = {11, 12};
Line(12) = {13, 14};
Circle(13) = {15, 16, 17};
Physical Surface("base") = {1};
Physical Surface("block") = {2};
Physical Curve("slip") = {4};
Physical Curve("bottom") = {1};
Physical Curve("rod") = {10};
Physical Curve("pair") = {11, 12};
Physical Curve("arc") = {13};
)";

// The bolt's table goes last (line 22 is its header).
constexpr const char* base_case = R"(geometry = "blocks.geo"
title = "bolted"
[cover_mesh]
size = 0.5
[materials.base]
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
[[boundary]]
curve = "bottom"
fix = "xy"
[analysis]
steps = 3
)";

CaseSpec parse(const std::string& bolt) { return parse_case_text(base_case + bolt, "case.toml"); }

std::string error_of(const std::string& bolt) {
  try {
    (void)parse(bolt);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

constexpr const char* rod = "[[bolt]]\nfrom = [2.0, 1.5]\nto = [2.0, 0.5]\n";

TEST(BoltTable, AbsentMeansNoBolt) { EXPECT_TRUE(parse("").bolts.empty()); }

TEST(BoltTable, DefaultsAndEveryKey) {
  const BoltSpec b = parse(std::string(rod) + "stiffness = 2e8\n").bolts.at(0);
  EXPECT_EQ(b.name, "bolt1");
  EXPECT_EQ(b.line, 22);
  EXPECT_EQ(b.kind, BoltKind::end_anchored);
  EXPECT_EQ(b.axial_rigidity(2.0), 4e8);
  EXPECT_EQ(b.pretension, 0.0);
  EXPECT_TRUE(std::isinf(b.yield_force));
  EXPECT_TRUE(std::isinf(b.rupture_force));
  EXPECT_EQ(b.hardening, 0.0);
  const CaseSpec spec =
      parse("[[bolt]]\nname = \"B_2\"\ncurve = \"rod\"\nkind = \"grouted\"\nyoung = 2e11\n"
            "area = 5e-4\npretension = 1e4\nyield_force = 1e5\nrupture_force = 1.5e5\n"
            "hardening = 0.05\n");
  const BoltSpec& g = spec.bolts.at(0);
  EXPECT_EQ(g.name, "B_2");
  EXPECT_EQ(g.curve, "rod");
  EXPECT_FALSE(g.from);
  EXPECT_EQ(g.kind, BoltKind::grouted);
  EXPECT_EQ(g.axial_rigidity(3.0), 2e11 * 5e-4);
  EXPECT_EQ(g.pretension, 1e4);
  EXPECT_EQ(g.yield_force, 1e5);
  EXPECT_EQ(g.rupture_force, 1.5e5);
  EXPECT_EQ(g.hardening, 0.05);
  EXPECT_TRUE(spec.warnings.empty());
}

TEST(BoltTable, BadValuesNameTheLineAndWhatToDo) {
  const std::string k = "stiffness = 2e8\n";
  EXPECT_NE(
      error_of("[[bolt]]\nstiffness = 2e8\n").find("case.toml:22:1: [[bolt]] is missing from"),
      std::string::npos);
  EXPECT_NE(error_of("[[bolt]]\nfrom = [2.0, 1.5]\n" + k).find("is missing to"), std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + "curve = \"rod\"\n" + k).find("cannot be given with from"),
            std::string::npos);
  EXPECT_NE(
      error_of("[[bolt]]\nfrom = [2.0, 1.5]\nto = [2.0, 1.5]\n" + k).find("two different ends"),
      std::string::npos);
  EXPECT_NE(error_of(rod).find("is missing stiffness"), std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + "young = 2e11\n").find("is missing area"),
            std::string::npos);
  EXPECT_NE(
      error_of(std::string(rod) + k + "young = 2e11\n").find("cannot be given with stiffness"),
      std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + "stiffness = 0\n")
                .find("case.toml:25:13: [[bolt]] stiffness = 0 is out of range"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + k + "yield_force = -1\n").find("must be > 0"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + k + "yield_force = 1e4\npretension = 2e4\n")
                .find("|pretension| must be below the yield and rupture forces"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + k + "hardening = 1\n").find("in [0, 1)"),
            std::string::npos);
  EXPECT_NE(
      error_of(std::string(rod) + k + "kind = \"gruoted\"\n").find("did you mean \"grouted\""),
      std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + k + "name = \"B-1\"\n")
                .find("[[bolt]] name = \"B-1\" contains '-'"),
            std::string::npos);
  const std::string named = std::string(rod) + k + "name = \"B\"\n";
  EXPECT_NE(error_of(named + named).find("is already used by the [[bolt]] at line 22"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(rod) + k + "lenght = 2\n").find("lenght"), std::string::npos);
}

TEST(BoltTable, ARuptureForceAboveTheYieldForceWithoutHardeningWarns) {
  const CaseSpec spec =
      parse(std::string(rod) + "stiffness = 2e8\nyield_force = 1e5\nrupture_force = 1.5e5\n");
  ASSERT_EQ(spec.warnings.size(), 1u);
  EXPECT_NE(spec.warnings[0].find("never breaks"), std::string::npos) << spec.warnings[0];
  EXPECT_TRUE(parse(std::string(rod) + "stiffness = 2e8\nyield_force = 1e5\nrupture_force = 1e5\n")
                  .warnings.empty());
}

class BoltScene : public ::testing::Test {
protected:
  BoltScene() : dir_("nmm_bolt_scene") { write_text(dir_.path() / "blocks.geo", blocks_geo); }
  fs::path write(const std::string& bolt) const {
    write_text(dir_.path() / "case.toml", base_case + bolt);
    return dir_.path() / "case.toml";
  }
  std::string error_of(const std::string& bolt) const {
    try {
      CaseAnalysis analysis(read_case_file(write(bolt)));
    } catch (const InputError& error) {
      return error.what();
    }
    return "";
  }
  const fs::path& dir() const { return dir_.path(); }

private:
  TempDir dir_;
};

TEST_F(BoltScene, EndsOutsideTheMaterialOrInOneBlockAreErrors) {
  const std::string k = "stiffness = 2e8\n";
  const std::string outside = error_of("[[bolt]]\nfrom = [2.0, 1.5]\nto = [2.0, 3.0]\n" + k);
  EXPECT_NE(outside.find("case.toml:22: [[bolt]] \"bolt1\": its end (2, 3) lies outside the "
                         "material"),
            std::string::npos)
      << outside;
  const std::string one = error_of("[[bolt]]\nfrom = [2.0, 1.5]\nto = [2.5, 1.8]\n" + k);
  EXPECT_NE(one.find("lie in one block"), std::string::npos) << one;
  const std::string unknown = error_of("[[bolt]]\ncurve = \"rdo\"\n" + k);
  EXPECT_NE(unknown.find("curve \"rdo\" is not a Physical Curve of blocks.geo"), std::string::npos)
      << unknown;
  const std::string arc = error_of("[[bolt]]\ncurve = \"arc\"\n" + k);
  EXPECT_NE(arc.find("off its chord: a bolt is straight"), std::string::npos) << arc;
  EXPECT_EQ(error_of("[[bolt]]\ncurve = \"pair\"\n" + k), "")
      << "each gmsh curve of a group is a straight bolt of its own";
}

TEST_F(BoltScene, BarsAreOneEndAnchoredOrOneAnElementGrouted) {
  {
    CaseAnalysis analysis(read_case_file(write("[[bolt]]\ncurve = \"rod\"\nstiffness = 2e8\n")));
    const std::vector<Bolt>& bolts = analysis.stepper().scene().bolts;
    ASSERT_EQ(bolts.size(), 1u);
    ASSERT_EQ(bolts[0].bars.size(), 1u);
    EXPECT_EQ(bolts[0].bars[0].stiffness, 2e8);
  }
  {
    // Two DDA blocks: the grouted bolt's chords are the block's and the base's, one bar.
    CaseAnalysis analysis(
        read_case_file(write("[[bolt]]\ncurve = \"pair\"\nkind = \"grouted\"\nstiffness = 2e8\n")));
    const std::vector<Bolt>& bolts = analysis.stepper().scene().bolts;
    ASSERT_EQ(bolts.size(), 2u);
    EXPECT_EQ(bolts[0].name, "bolt1_1");
    EXPECT_EQ(bolts[1].name, "bolt1_2");
  }
}

TEST_F(BoltScene, ARunWritesTheForceInHistorySummaryAndTheBoundaryLines) {
  CaseAnalysis analysis(read_case_file(
      write("[[bolt]]\nname = \"B1\"\nfrom = [2.0, 1.5]\nto = [2.0, 0.5]\nstiffness = 2e8\n"
            "pretension = 1e4\n")));
  RunOptions options;
  options.output_dir = dir() / "out";
  (void)run_case(analysis, options);
  const std::string history = read_text(dir() / "out" / "history.csv");
  const std::string header = history.substr(0, history.find('\n'));
  EXPECT_EQ(header.substr(header.rfind(',') + 1), "B1.force");
  const testing::Json summary = parse_json(read_text(dir() / "out" / "summary.json"));
  const testing::Json& bolt = summary.at("bolts").items.at(0);
  EXPECT_EQ(bolt.at("name").string, "B1");
  EXPECT_EQ(bolt.at("state").string, "elastic");
  EXPECT_EQ(bolt.at("bars").number, 1.0);
  // The block presses the bolt's ends together a little: its force stays near its pretension.
  EXPECT_NEAR(bolt.at("force").number, 1e4, 1e3);
  const auto lines = testing::read_vtp(dir() / "out" / "boundary_000003.vtp");
  vtkDataArray* force = lines->GetCellData()->GetArray("axial_force");
  vtkDataArray* which = lines->GetCellData()->GetArray("bolt");
  ASSERT_NE(force, nullptr);
  ASSERT_NE(which, nullptr);
  const vtkIdType last = lines->GetNumberOfCells() - 1;
  EXPECT_EQ(which->GetTuple1(last), 0.0);
  EXPECT_EQ(which->GetTuple1(0), -1.0);
  EXPECT_EQ(force->GetTuple1(last), bolt.at("force").number);
}

} // namespace
} // namespace nmm
