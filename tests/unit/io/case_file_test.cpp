// SPDX-License-Identifier: MIT
#include "io/case_file.hpp"
#include "mesh/error.hpp"

#include "../../support/temp_dir.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;

// DESIGN.md "Case file (TOML)", verbatim.
constexpr const char* design_example = R"(geometry = "slope.geo"

[cover_mesh]            # the mathematical mesh
kind = "regular"        # "regular" grid of equilateral triangles, or "gmsh"
size = 0.5              # edge length
order = 0               # cover function order for NMM regions: 0, 1 (2 later)

[materials.rock]        # a Physical Surface
model = "nmm"           # "nmm" | "dda" | "vem"
density = 2600.0
young = 5.0e9
poisson = 0.25
plane = "strain"        # or "stress"
initial_velocity = [0.0, 0.0]        # optional
initial_angular_velocity = 0.0       # optional, rad/s about each block's centroid
initial_stress = [0.0, 0.0, 0.0]     # optional: sxx, syy, sxy

[joints.bedding]        # a Physical Curve
friction_angle = 30.0   # degrees
cohesion = 0.0
tensile_strength = 0.0

[contact]               # any other boundary that touches something: same keys as a joint
friction_angle = 0.0    # a contact between two curves with different properties
                        # takes the smaller friction angle, cohesion and strength

[[boundary]]
curve = "base"          # or point = "..."
fix = "xy"              # "x", "y", "xy"

[[load]]
gravity = [0.0, -9.81]
[[load]]
point = "P"             # or curve = "..." with traction = [tx, ty] or pressure = p
force = [1.0e4, 0.0]

[analysis]
kind = "dynamic"        # "dynamic" | "static" (Shi's static: velocity reset every
                        # step; a scene with no contact is solved in one linear solve
                        # per load step)
steps = 2000
time_step = 1.0e-3      # or "auto"
max_step_displacement = 0.01   # fraction of the model size (Shi's g2)
penalty = 40.0          # contact spring stiffness as a multiple of the largest E
open_close_max = 6

[[monitor]]
name = "crest"
point = [10.0, 5.0]     # follows the material point that starts here

[output]
dir = "out"
every = 10
)";

// The smallest valid case, in pieces that the malformed cases below recombine.
const std::string head = "geometry = \"slope.geo\"\n[cover_mesh]\nsize = 0.5\n";
const std::string rock = "[materials.rock]\ndensity = 2600.0\nyoung = 5.0e9\npoisson = 0.25\n";
const std::string analysis = "[analysis]\nsteps = 100\n";
const std::string minimal = head + rock + analysis;

TEST(CaseFile, DesignExampleParsesToItsValues) {
  const CaseSpec spec = parse_case_text(design_example, "case.toml");
  EXPECT_EQ(spec.file, fs::path("case.toml"));
  EXPECT_EQ(spec.geometry, fs::path("slope.geo"));
  EXPECT_EQ(spec.geometry_line, 1);
  EXPECT_EQ(spec.title, "");

  EXPECT_EQ(spec.cover_mesh.kind, CoverMeshKind::regular);
  EXPECT_DOUBLE_EQ(spec.cover_mesh.size, 0.5);
  EXPECT_EQ(spec.cover_mesh.order, 0);

  ASSERT_EQ(spec.materials.size(), 1u);
  const MaterialSpec& rock_spec = spec.materials[0];
  EXPECT_EQ(rock_spec.name, "rock");
  EXPECT_EQ(rock_spec.line, 8);
  EXPECT_EQ(rock_spec.model, MaterialModel::nmm);
  EXPECT_DOUBLE_EQ(rock_spec.density, 2600.0);
  EXPECT_DOUBLE_EQ(rock_spec.young, 5.0e9);
  EXPECT_DOUBLE_EQ(rock_spec.poisson, 0.25);
  EXPECT_EQ(rock_spec.plane, PlaneCondition::strain);
  EXPECT_DOUBLE_EQ(rock_spec.thickness, 1.0);
  EXPECT_TRUE(rock_spec.initial_velocity.isZero());
  EXPECT_DOUBLE_EQ(rock_spec.initial_angular_velocity, 0.0);
  EXPECT_TRUE(rock_spec.initial_stress.isZero());
  EXPECT_EQ(spec.find_material("rock"), &spec.materials[0]);
  EXPECT_EQ(spec.find_material("soil"), nullptr);

  ASSERT_EQ(spec.joints.size(), 1u);
  EXPECT_EQ(spec.joints[0].name, "bedding");
  EXPECT_EQ(spec.joints[0].line, 18);
  EXPECT_DOUBLE_EQ(spec.joints[0].properties.friction_angle_degrees, 30.0);
  EXPECT_DOUBLE_EQ(spec.joints[0].properties.cohesion, 0.0);
  EXPECT_DOUBLE_EQ(spec.joints[0].properties.tensile_strength, 0.0);
  EXPECT_NE(spec.find_joint("bedding"), nullptr);
  EXPECT_DOUBLE_EQ(spec.contact.friction_angle_degrees, 0.0);

  ASSERT_EQ(spec.boundaries.size(), 1u);
  EXPECT_EQ(spec.boundaries[0].target, "base");
  EXPECT_TRUE(spec.boundaries[0].is_curve);
  EXPECT_TRUE(spec.boundaries[0].fix_x);
  EXPECT_TRUE(spec.boundaries[0].fix_y);
  EXPECT_EQ(spec.boundaries[0].method, SupportMethod::exact);
  EXPECT_EQ(spec.boundaries[0].line, 27);

  ASSERT_EQ(spec.loads.size(), 2u);
  EXPECT_EQ(spec.loads[0].kind, LoadKind::gravity);
  EXPECT_EQ(spec.loads[0].vector, Eigen::Vector2d(0.0, -9.81));
  EXPECT_EQ(spec.loads[0].line, 31);
  EXPECT_EQ(spec.loads[1].kind, LoadKind::point);
  EXPECT_EQ(spec.loads[1].target, "P");
  EXPECT_EQ(spec.loads[1].vector, Eigen::Vector2d(1.0e4, 0.0));
  EXPECT_EQ(spec.loads[1].line, 33);
  EXPECT_DOUBLE_EQ(spec.loads[1].factor_at(0.0), 1.0);

  EXPECT_EQ(spec.analysis.kind, AnalysisKind::dynamic);
  EXPECT_EQ(spec.analysis.steps, 2000);
  ASSERT_TRUE(spec.analysis.time_step.has_value());
  EXPECT_DOUBLE_EQ(*spec.analysis.time_step, 1.0e-3);
  EXPECT_DOUBLE_EQ(spec.analysis.max_step_displacement, 0.01);
  EXPECT_DOUBLE_EQ(spec.analysis.penalty, 40.0);
  EXPECT_FALSE(spec.analysis.penalty_stiffness.has_value());
  EXPECT_EQ(spec.analysis.open_close_max.value_or(0), 6); // given: the limit of every step

  ASSERT_EQ(spec.monitors.size(), 1u);
  EXPECT_EQ(spec.monitors[0].name, "crest");
  EXPECT_EQ(spec.monitors[0].point, Point2(10.0, 5.0));
  EXPECT_EQ(spec.monitors[0].line, 47);

  EXPECT_EQ(spec.output.dir, fs::path("out"));
  EXPECT_EQ(spec.output.every, 10);
  EXPECT_TRUE(spec.warnings.empty());
}

TEST(CaseFile, MinimalCaseGetsEveryDefault) {
  const CaseSpec spec = parse_case_text(minimal, "case.toml");
  EXPECT_EQ(spec.title, "");
  EXPECT_EQ(spec.cover_mesh.kind, CoverMeshKind::regular);
  EXPECT_EQ(spec.cover_mesh.order, 0);
  EXPECT_EQ(spec.cover_mesh.max_triangles, 5'000'000);
  EXPECT_DOUBLE_EQ(spec.cover_mesh.min_cover_area_ratio, 1e-3);
  EXPECT_DOUBLE_EQ(spec.cover_mesh.curve_tolerance, 0.0);

  const MaterialSpec& material = spec.materials.at(0);
  EXPECT_EQ(material.model, MaterialModel::nmm);
  EXPECT_EQ(material.plane, PlaneCondition::strain);
  EXPECT_DOUBLE_EQ(material.thickness, 1.0);
  EXPECT_TRUE(material.initial_velocity.isZero());
  EXPECT_TRUE(material.initial_stress.isZero());
  EXPECT_FALSE(material.exact_rotation);

  EXPECT_TRUE(spec.joints.empty());
  EXPECT_DOUBLE_EQ(spec.contact.friction_angle_degrees, 0.0);
  EXPECT_DOUBLE_EQ(spec.contact.cohesion, 0.0);
  EXPECT_DOUBLE_EQ(spec.contact.tensile_strength, 0.0);
  EXPECT_EQ(spec.contact.normal_stiffness, 0.0); // absent: the penalty
  EXPECT_EQ(spec.contact.shear_stiffness, 0.0);
  EXPECT_TRUE(spec.boundaries.empty());
  EXPECT_TRUE(spec.loads.empty());
  EXPECT_TRUE(spec.monitors.empty());

  EXPECT_EQ(spec.analysis.kind, AnalysisKind::dynamic);
  EXPECT_EQ(spec.analysis.steps, 100);
  EXPECT_FALSE(spec.analysis.time_step.has_value()); // "auto"
  EXPECT_DOUBLE_EQ(spec.analysis.max_step_displacement, 0.01);
  EXPECT_DOUBLE_EQ(spec.analysis.penalty, 40.0);
  EXPECT_FALSE(spec.analysis.penalty_stiffness.has_value());
  EXPECT_FALSE(spec.analysis.open_close_max.has_value()); // the scene's budget
  EXPECT_EQ(spec.analysis.solver, LinearSolverKind::cholmod);
  EXPECT_DOUBLE_EQ(spec.analysis.pcg_tolerance, 1e-10);
  EXPECT_EQ(spec.analysis.max_step_cuts, 10);
  EXPECT_DOUBLE_EQ(spec.analysis.energy_tolerance, 0.05);
  EXPECT_FALSE(spec.analysis.energy_error_limit.has_value());
  EXPECT_DOUBLE_EQ(spec.analysis.velocity_ratio, 1.0);
  EXPECT_FALSE(spec.analysis.end_time.has_value());
  EXPECT_FALSE(spec.analysis.initial_equilibrium);

  EXPECT_EQ(spec.output.dir, fs::path("out"));
  EXPECT_EQ(spec.output.every, 1);
  EXPECT_EQ(spec.output.checkpoint_every, 0);
  EXPECT_FALSE(spec.output.moved_threshold.has_value());
  EXPECT_TRUE(spec.warnings.empty());
}

TEST(CaseFile, PathsAreResolvedAgainstTheCaseFileFolder) {
  const std::string text = "geometry = \"../shared/slope.geo\"\n" +
                           minimal.substr(minimal.find('\n') + 1) +
                           "[output]\ndir = \"results/run1\"\n";
  const CaseSpec spec = parse_case_text(text, "cases/slope/case.toml");
  EXPECT_EQ(spec.geometry, fs::path("cases/shared/slope.geo"));
  EXPECT_EQ(spec.output.dir, fs::path("cases/slope/results/run1"));

  const CaseSpec defaults = parse_case_text(minimal, "cases/slope/case.toml");
  EXPECT_EQ(defaults.geometry, fs::path("cases/slope/slope.geo"));
  EXPECT_EQ(defaults.output.dir, fs::path("cases/slope/out"));

  const std::string absolute =
      "geometry = \"/data/slope.msh\"\n" + minimal.substr(minimal.find('\n') + 1);
  EXPECT_EQ(parse_case_text(absolute, "cases/case.toml").geometry, fs::path("/data/slope.msh"));
}

TEST(CaseFile, TimeStepIsAutoOrANumber) {
  const CaseSpec automatic = parse_case_text(minimal + "time_step = \"auto\"\n", "case.toml");
  EXPECT_FALSE(automatic.analysis.time_step.has_value());
  const CaseSpec fixed = parse_case_text(minimal + "time_step = 2.5e-4\n", "case.toml");
  ASSERT_TRUE(fixed.analysis.time_step.has_value());
  EXPECT_DOUBLE_EQ(*fixed.analysis.time_step, 2.5e-4);
  const CaseSpec integral = parse_case_text(minimal + "time_step = 1\n", "case.toml");
  EXPECT_DOUBLE_EQ(integral.analysis.time_step.value(), 1.0);
}

TEST(CaseFile, IntegersAreAcceptedWhereNumbersAreExpected) {
  const std::string text = head +
                           "[materials.rock]\ndensity = 2600\nyoung = 5\npoisson = 0\n"
                           "initial_velocity = [1, -2]\ninitial_stress = [0, -1000000, 0]\n" +
                           analysis;
  const CaseSpec spec = parse_case_text(text, "case.toml");
  EXPECT_DOUBLE_EQ(spec.materials[0].density, 2600.0);
  EXPECT_DOUBLE_EQ(spec.materials[0].young, 5.0);
  EXPECT_DOUBLE_EQ(spec.materials[0].poisson, 0.0);
  EXPECT_EQ(spec.materials[0].initial_velocity, Eigen::Vector2d(1.0, -2.0));
  EXPECT_EQ(spec.materials[0].initial_stress, Eigen::Vector3d(0.0, -1.0e6, 0.0));
}

TEST(CaseFile, WholeNumbersWrittenAsFloatsAreAcceptedForCounts) {
  const CaseSpec spec = parse_case_text(
      head + "max_triangles = 2e6\n" + rock + "[analysis]\nsteps = 1e4\n", "case.toml");
  EXPECT_EQ(spec.cover_mesh.max_triangles, 2'000'000);
  EXPECT_EQ(spec.analysis.steps, 10'000);
}

TEST(CaseFile, NamedItemsKeepTheOrderAndLinesOfTheFile) {
  const std::string text = head +
                           "[materials.soil]\ndensity = 1900.0\nyoung = 5e7\npoisson = 0.3\n"
                           "[materials.\"hard rock\"]\nmodel = \"dda\"\ndensity = 2600.0\n"
                           "young = 5e9\npoisson = 0.25\n"
                           "[joints.set_b]\nfriction_angle = 35\n[joints.set_a]\ncohesion = 1e5\n" +
                           analysis;
  const CaseSpec spec = parse_case_text(text, "case.toml");
  ASSERT_EQ(spec.materials.size(), 2u);
  EXPECT_EQ(spec.materials[0].name, "soil");
  EXPECT_EQ(spec.materials[0].line, 4);
  EXPECT_EQ(spec.materials[1].name, "hard rock");
  EXPECT_EQ(spec.materials[1].line, 8);
  EXPECT_EQ(spec.materials[1].model, MaterialModel::dda);
  ASSERT_EQ(spec.joints.size(), 2u);
  EXPECT_EQ(spec.joints[0].name, "set_b");
  EXPECT_EQ(spec.joints[0].line, 13);
  EXPECT_EQ(spec.joints[1].name, "set_a");
  EXPECT_EQ(spec.joints[1].line, 15);
  EXPECT_DOUBLE_EQ(spec.joints[1].properties.cohesion, 1e5);
}

TEST(CaseFile, InlineTablesAndDottedKeysAreOrdinaryTables) {
  const std::string text = "geometry = \"slope.geo\"\n"
                           "materials.rock = { young = 5e9, poisson = 0.2 }\n"
                           "[cover_mesh]\nsize = 0.5\n"
                           "[analysis]\nkind = \"static\"\nsteps = 1\n"
                           "[[boundary]]\npoint = \"A\"\nfix = \"y\"\nmethod = \"penalty\"\n";
  const CaseSpec spec = parse_case_text(text, "case.toml");
  EXPECT_DOUBLE_EQ(spec.materials.at(0).young, 5e9);
  EXPECT_DOUBLE_EQ(spec.materials.at(0).density, 0.0); // static, no gravity: allowed
  EXPECT_EQ(spec.analysis.kind, AnalysisKind::quasi_static);
  const BoundarySpec& boundary = spec.boundaries.at(0);
  EXPECT_FALSE(boundary.is_curve);
  EXPECT_EQ(boundary.target, "A");
  EXPECT_FALSE(boundary.fix_x);
  EXPECT_TRUE(boundary.fix_y);
  EXPECT_EQ(boundary.method, SupportMethod::penalty);
}

TEST(CaseFile, CurveLoadsAndRamps) {
  const std::string text = minimal +
                           "[[load]]\ncurve = \"face\"\ntraction = [0, -1e5]\nramp = [1.0, 3.0]\n"
                           "[[load]]\ncurve = \"crest\"\npressure = 2e5\n"
                           "[[load]]\npoint = \"P\"\nforce = [1, 2]\nramp = [2.0, 2.0]\n";
  const CaseSpec spec = parse_case_text(text, "case.toml");
  ASSERT_EQ(spec.loads.size(), 3u);
  const LoadSpec& traction = spec.loads[0];
  EXPECT_EQ(traction.kind, LoadKind::traction);
  EXPECT_EQ(traction.target, "face");
  EXPECT_EQ(traction.vector, Eigen::Vector2d(0.0, -1e5));
  EXPECT_DOUBLE_EQ(traction.factor_at(0.5), 0.0);
  EXPECT_DOUBLE_EQ(traction.factor_at(1.0), 0.0);
  EXPECT_DOUBLE_EQ(traction.factor_at(2.0), 0.5);
  EXPECT_DOUBLE_EQ(traction.factor_at(3.0), 1.0);
  EXPECT_DOUBLE_EQ(traction.factor_at(10.0), 1.0);
  EXPECT_EQ(spec.loads[1].kind, LoadKind::pressure);
  EXPECT_DOUBLE_EQ(spec.loads[1].pressure, 2e5);
  EXPECT_TRUE(spec.loads[1].vector.isZero());
  EXPECT_FALSE(spec.loads[1].water_level.has_value());
  // A ramp with t0 == t1 is a step at t0.
  EXPECT_DOUBLE_EQ(spec.loads[2].factor_at(1.999), 0.0);
  EXPECT_DOUBLE_EQ(spec.loads[2].factor_at(2.0), 1.0);
}

TEST(CaseFile, WaterLevelIsAHydrostaticPressure) {
  const CaseSpec spec = parse_case_text(
      minimal + "[[load]]\ncurve = \"face\"\nwater_level = 15.0\n"
                "[[load]]\ncurve = \"face\"\nwater_level = 3\nwater_unit_weight = 1.0e4\n"
                "pressure = 5.0\n",
      "case.toml");
  ASSERT_EQ(spec.loads.size(), 2u);
  EXPECT_EQ(spec.loads[0].kind, LoadKind::pressure);
  EXPECT_DOUBLE_EQ(spec.loads[0].water_level.value(), 15.0);
  EXPECT_DOUBLE_EQ(spec.loads[0].water_unit_weight, 9810.0);
  EXPECT_DOUBLE_EQ(spec.loads[0].pressure, 0.0);
  EXPECT_DOUBLE_EQ(spec.loads[1].water_level.value(), 3.0);
  EXPECT_DOUBLE_EQ(spec.loads[1].water_unit_weight, 1.0e4);
  EXPECT_DOUBLE_EQ(spec.loads[1].pressure, 5.0);
}

TEST(CaseFile, EveryExtensionKeyIsRead) {
  const std::string text =
      "geometry = \"dam.geo\"\ntitle = \"Dam on a jointed foundation\"\n"
      "[cover_mesh]\nkind = \"gmsh\"\nsize = 2.0\norder = 1\nmax_triangles = 100000\n"
      "min_cover_area_ratio = 0.0\ncurve_tolerance = 0.05\ngeometry_sizes = true\n"
      "[materials.concrete]\nmodel = \"vem\"\ndensity = 2400\nyoung = 3e10\npoisson = 0.2\n"
      "plane = \"stress\"\nthickness = 0.3\ninitial_angular_velocity = 0.1\n"
      "exact_rotation = true\n"
      "[contact]\nfriction_angle = 25\ncohesion = 1e4\ntensile_strength = 5e3\n"
      "normal_stiffness = 2e10\nshear_stiffness = 5e9\n"
      "[analysis]\nkind = \"dynamic\"\nsteps = 50\npenalty_stiffness = 1e12\nopen_close_max = 20\n"
      "solver = \"pcg\"\npcg_tolerance = 1e-8\nmax_step_cuts = 0\nend_time = 2.5\n"
      "max_step_displacement = 0.5\n"
      "initial_equilibrium = true\npenetration_tolerance = 1e-4\n"
      "energy_tolerance = 0.02\nenergy_error_limit = 0.3\nvelocity_ratio = 0.9\n"
      "[output]\ndir = \"/tmp/dam\"\nevery = 5\ncheckpoint_every = 25\nmoved_threshold = 0.05\n";
  const CaseSpec spec = parse_case_text(text, "case.toml");
  EXPECT_EQ(spec.title, "Dam on a jointed foundation");
  EXPECT_EQ(spec.cover_mesh.kind, CoverMeshKind::gmsh);
  EXPECT_EQ(spec.cover_mesh.order, 1);
  EXPECT_EQ(spec.cover_mesh.max_triangles, 100000);
  EXPECT_DOUBLE_EQ(spec.cover_mesh.min_cover_area_ratio, 0.0);
  EXPECT_DOUBLE_EQ(spec.cover_mesh.curve_tolerance, 0.05);
  EXPECT_TRUE(spec.cover_mesh.geometry_sizes);
  const MaterialSpec& concrete = spec.materials.at(0);
  EXPECT_EQ(concrete.model, MaterialModel::vem);
  EXPECT_EQ(concrete.plane, PlaneCondition::stress);
  EXPECT_DOUBLE_EQ(concrete.thickness, 0.3);
  EXPECT_DOUBLE_EQ(concrete.initial_angular_velocity, 0.1);
  EXPECT_TRUE(concrete.exact_rotation);
  EXPECT_DOUBLE_EQ(spec.contact.friction_angle_degrees, 25.0);
  EXPECT_DOUBLE_EQ(spec.contact.cohesion, 1e4);
  EXPECT_DOUBLE_EQ(spec.contact.tensile_strength, 5e3);
  EXPECT_DOUBLE_EQ(spec.contact.normal_stiffness, 2e10);
  EXPECT_DOUBLE_EQ(spec.contact.shear_stiffness, 5e9);
  EXPECT_DOUBLE_EQ(spec.analysis.penalty_stiffness.value(), 1e12);
  EXPECT_EQ(spec.analysis.open_close_max.value_or(0), 20);
  EXPECT_EQ(spec.analysis.solver, LinearSolverKind::pcg);
  EXPECT_DOUBLE_EQ(spec.analysis.pcg_tolerance, 1e-8);
  EXPECT_EQ(spec.analysis.max_step_cuts, 0);
  EXPECT_DOUBLE_EQ(spec.analysis.end_time.value(), 2.5);
  EXPECT_DOUBLE_EQ(spec.analysis.max_step_displacement, 0.5);
  EXPECT_TRUE(spec.analysis.initial_equilibrium);
  EXPECT_DOUBLE_EQ(spec.analysis.energy_tolerance, 0.02);
  EXPECT_DOUBLE_EQ(spec.analysis.energy_error_limit.value(), 0.3);
  EXPECT_DOUBLE_EQ(spec.analysis.velocity_ratio, 0.9);
  EXPECT_DOUBLE_EQ(spec.analysis.penetration_tolerance.value(), 1e-4);
  EXPECT_EQ(spec.output.dir, fs::path("/tmp/dam"));
  EXPECT_EQ(spec.output.every, 5);
  EXPECT_EQ(spec.output.checkpoint_every, 25);
  EXPECT_DOUBLE_EQ(spec.output.moved_threshold.value(), 0.05);
  // The only material is a VEM one, so the cover function order is unused.
  ASSERT_EQ(spec.warnings.size(), 1u);
  EXPECT_NE(spec.warnings[0].find("order has no effect"), std::string::npos) << spec.warnings[0];
}

TEST(CaseFile, ExactRotationIsReadForNmmRegions) {
  // NMM blocks turn exactly with it too (Model::turn_exactly); off by default (above).
  const CaseSpec spec =
      parse_case_text(head + rock + "exact_rotation = true\n" + analysis, "case.toml");
  EXPECT_EQ(spec.materials.at(0).model, MaterialModel::nmm);
  EXPECT_TRUE(spec.materials.at(0).exact_rotation);
}

TEST(CaseFile, NonFatalRemarksBecomeWarningsWithTheirLine) {
  const std::string text = head +
                           "[materials.rock]\ndensity = 2600.0\nyoung = 5.0e9\npoisson = 0.25\n"
                           "thickness = 2.0\ninitial_velocity = [1, 0]\n"
                           "[analysis]\nkind = \"static\"\nsteps = 10\n"
                           "[[boundary]]\ncurve = \"base\"\nfix = \"x\"\n"
                           "[[boundary]]\ncurve = \"base\"\nfix = \"y\"\n";
  const CaseSpec spec = parse_case_text(text, "case.toml");
  ASSERT_EQ(spec.warnings.size(), 3u);
  EXPECT_NE(spec.warnings[0].find("case.toml:4: [materials.rock] thickness is ignored"),
            std::string::npos)
      << spec.warnings[0];
  EXPECT_NE(spec.warnings[1].find("case.toml:4: [materials.rock] has an initial velocity"),
            std::string::npos)
      << spec.warnings[1];
  EXPECT_NE(spec.warnings[2].find("case.toml:16: curve \"base\" is already fixed"),
            std::string::npos)
      << spec.warnings[2];
}

TEST(CaseFile, WarningsPointAtTheKeyConcerned) {
  const std::string text = head + "order = 1\n" +
                           "[materials.wall]\nmodel = \"dda\"\nyoung = 1e9\npoisson = 0.2\n"
                           "[analysis]\nkind = \"static\"\nsteps = 10\ntime_step = 0.1\n"
                           "end_time = 5.0\n";
  const CaseSpec spec = parse_case_text(text, "case.toml");
  ASSERT_EQ(spec.warnings.size(), 3u);
  EXPECT_EQ(spec.warnings[0].rfind("case.toml:4: [cover_mesh] order", 0), 0u) << spec.warnings[0];
  EXPECT_EQ(spec.warnings[1].rfind("case.toml:10: a static analysis with no [[boundary]]", 0), 0u)
      << spec.warnings[1];
  EXPECT_EQ(spec.warnings[2].rfind("case.toml:13: [analysis] steps * time_step = 1 s", 0), 0u)
      << spec.warnings[2];
}

TEST(CaseFile, PenaltyFarFromFortyTimesYoungIsAWarningAtItsKey) {
  // Lines: 1-3 head, 4-7 rock (young = 5e9), 8-9 analysis, 10 the penalty.
  for (const auto& [key, value, times] :
       {std::tuple{"penalty", "1.0", "1"}, std::tuple{"penalty", "2000.0", "2000"},
        std::tuple{"penalty_stiffness", "5.0e15", "1e+06"}}) {
    const CaseSpec spec = parse_case_text(minimal + key + " = " + value + "\n", "case.toml");
    ASSERT_EQ(spec.warnings.size(), 1u) << key << " = " << value;
    const std::string expected = std::string("case.toml:10: [analysis] ") + key +
                                 " makes the contact springs " + times +
                                 " times the largest Young's modulus, far from the usual 40 E";
    EXPECT_EQ(spec.warnings[0].rfind(expected, 0), 0u) << spec.warnings[0];
  }
  // Within a factor of 25 of 40 E (the paper examples' 100 E too): no warning.
  for (const char* ok : {"penalty = 2.0\n", "penalty = 100.0\n", "penalty = 1000.0\n",
                         "penalty_stiffness = 2.0e11\n"})
    EXPECT_TRUE(parse_case_text(minimal + ok, "case.toml").warnings.empty()) << ok;
}

// The reference page's examples must be valid cases: they are what users copy.
TEST(CaseFile, ExamplesOfTheReferencePageAreValid) {
  const fs::path page = fs::path(NMM_DOCS_DIR) / "case-file.md";
  std::ifstream in(page);
  ASSERT_TRUE(in) << "cannot open " << page;
  std::vector<std::string> blocks;
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside && line == "```toml") {
      inside = true;
      blocks.emplace_back();
    } else if (inside && line == "```") {
      inside = false;
    } else if (inside) {
      blocks.back() += line + "\n";
    }
  }
  ASSERT_EQ(blocks.size(), 2u);
  for (const std::string& block : blocks) {
    const CaseSpec spec = parse_case_text(block, "docs/case-file.md");
    EXPECT_TRUE(spec.warnings.empty()) << spec.warnings.front();
  }
  // The complete example sets every key at least once.
  const CaseSpec full = parse_case_text(blocks[0], "case.toml");
  EXPECT_EQ(full.materials.size(), 2u);
  EXPECT_EQ(full.boundaries.size(), 2u);
  EXPECT_EQ(full.loads.size(), 5u);
  EXPECT_EQ(full.loads[3].kind, LoadKind::pressure);
  EXPECT_DOUBLE_EQ(full.loads[3].factor_at(1.5), 0.5);
  EXPECT_DOUBLE_EQ(full.loads[4].water_level.value(), 40.0);
  EXPECT_TRUE(full.analysis.initial_equilibrium == false);
  EXPECT_EQ(full.materials[1].plane, PlaneCondition::stress);
  EXPECT_DOUBLE_EQ(full.materials[1].thickness, 0.3);
  EXPECT_DOUBLE_EQ(full.analysis.end_time.value(), 2.0);
  ASSERT_EQ(full.joint_sets.size(), 1u);
  EXPECT_DOUBLE_EQ(full.joint_sets[0].parameters.trace.value(), 8.0);
  EXPECT_EQ(full.joint_sets[0].parameters.seed, 46u);
}

// ---- malformed input: each text must fail on the line marked "# <-" ----

struct BadCase {
  const char* name;
  std::string text;
  const char* expected; // a substring of the message
};

// Shown by GoogleTest (and ctest) instead of the raw bytes of the parameter.
void PrintTo(const BadCase& bad, std::ostream* out) { *out << bad.name; }

int marked_line(const std::string& text) {
  const std::size_t marker = text.find("# <-");
  if (marker == std::string::npos)
    return 1;
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(marker), '\n'));
}

std::vector<BadCase> bad_cases() {
  const std::string rock_no_density = "[materials.rock]\nyoung = 5.0e9\npoisson = 0.25\n";
  return {
      // TOML syntax
      {"SyntaxMissingValue", head + "[materials.rock]\nyoung = # <-\n", "TOML syntax error"},
      {"SyntaxDuplicateKey", head + "size = 1.0 # <-\n", "TOML syntax error"},
      {"SyntaxUnclosedHeader", head + "[materials.rock # <-\n", "TOML syntax error"},
      // unknown keys
      {"UnknownKeySuggestsYoung", head + "[materials.rock]\nyung = 5e9 # <-\n",
       "[materials.rock] has no key yung; did you mean young?"},
      {"UnknownKeyListsAllowedKeys", head + "[materials.rock]\nyung = 5e9 # <-\n",
       "allowed: model, density, young, poisson"},
      {"UnknownKeyInArrayOfTables", minimal + "[[boundary]]\ncurv = \"base\" # <-\nfix = \"xy\"\n",
       "[[boundary]] has no key curv; did you mean curve?"},
      {"UnknownKeyInInlineTableOfArray",
       "geometry = \"slope.geo\"\nload = [{ gravity = [0, -9.81] }, { point = \"P\", forse = [1, "
       "0] }] # <-\n[cover_mesh]\nsize = 0.5\n" +
           rock + analysis,
       "[[load]] has no key forse; did you mean force?"},
      {"UnknownKeyInSecondLoad",
       minimal + "[[load]]\ngravity = [0, -9.81]\n[[load]]\npoint = \"P\"\nforse = [1, 0] # <-\n",
       "did you mean force?"},
      {"UnknownTableSuggestsMaterials", head + "[material.rock] # <-\nyoung = 5e9\n",
       "unknown key material at the top level; did you mean materials?"},
      {"KeyUnderTheWrongTable", head + "steps = 100 # <-\n" + rock, "steps belongs in [analysis]"},
      {"TopLevelKeyAfterAHeader", minimal + "title = \"slope\" # <-\n",
       "title is a top-level key: move it above the first [table] header"},
      {"UnknownKeyWithNoNeighbour", minimal + "colour = \"red\" # <-\n",
       "[analysis] has no key colour; remove it"},
      // types
      {"StringForNumber", head + "[materials.rock]\nyoung = \"5e9\" # <-\n",
       "young must be a number (Pa), not a string (\"5e9\"); remove the quotes"},
      {"BooleanForNumber", head + "[materials.rock]\ndensity = true # <-\n",
       "density must be a number (kg/m^3), not a boolean"},
      {"StringForBoolean", head + rock + "model = \"vem\"\nexact_rotation = \"yes\" # <-\n",
       "exact_rotation must be true or false (without quotes)"},
      {"ExactRotationOfDdaBlocks", head + rock + "model = \"dda\"\nexact_rotation = true # <-\n",
       "[materials.rock] exact_rotation is a choice of `nmm` and `vem` regions (DDA blocks "
       "always turn by their rotation exactly); remove it"},
      {"FractionalSteps", head + rock + "[analysis]\nsteps = 1.5 # <-\n",
       "steps must be a whole number, not 1.5"},
      {"StringForSteps", head + rock + "[analysis]\nsteps = \"100\" # <-\n",
       "steps must be a whole number"},
      {"VectorTooShort", head + rock + "initial_velocity = [1.0] # <-\n",
       "initial_velocity has 1 value(s) but needs exactly 2"},
      {"StressVectorTooShort", head + rock + "initial_stress = [1.0, 2.0] # <-\n",
       "initial_stress has 2 value(s) but needs exactly 3"},
      {"NumberForVector", minimal + "[[load]]\ngravity = -9.81 # <-\n",
       "gravity must be an array of 2 numbers"},
      {"StringInsideVector", minimal + "[[load]]\ngravity = [0, \"-9.81\"] # <-\n",
       "gravity must be a number (m/s^2), not a string"},
      {"NumberForChoice", head + "kind = 3 # <-\n" + rock, "kind must be one of the strings"},
      {"NumberForName", minimal + "[[boundary]]\ncurve = 3 # <-\nfix = \"xy\"\n",
       "curve must be a string in double quotes"},
      // non-finite numbers
      {"NanYoung", head + "[materials.rock]\nyoung = nan # <-\n",
       "young is nan; it must be a finite"},
      {"InfDensity", head + "[materials.rock]\ndensity = inf # <-\n", "density is inf"},
      {"NegativeInfGravity", minimal + "[[load]]\ngravity = [0, -inf] # <-\n", "gravity is -inf"},
      // ranges
      {"NegativeYoung", head + "[materials.rock]\nyoung = -5e9 # <-\n",
       "young = -5e+09 is out of range; Young's modulus must be > 0"},
      {"PoissonHalfPlaneStrain", head + "[materials.rock]\nyoung = 5e9\npoisson = 0.5 # <-\n",
       "< 0.5 in plane strain"},
      {"PoissonHalfPlaneStress",
       head + "[materials.rock]\nyoung = 5e9\nplane = \"stress\"\npoisson = 0.5 # <-\n",
       "plane stress would allow 0.5 in theory"},
      {"PoissonMinusOne", head + "[materials.rock]\nyoung = 5e9\npoisson = -1 # <-\n",
       "must be > -1"},
      {"ZeroThickness", head + rock + "plane = \"stress\"\nthickness = 0 # <-\n",
       "thickness must be > 0"},
      {"ZeroSize", "geometry = \"slope.geo\"\n[cover_mesh]\nsize = 0 # <-\n",
       "[cover_mesh] size = 0 is out of range"},
      {"OrderTwoIsNotYetSupported", head + "order = 2 # <-\n", "order = 2 is not yet supported"},
      {"OrderThree", head + "order = 3 # <-\n",
       "order = 3 is out of range; it must be from 0 to 1"},
      {"ZeroMaxTriangles", head + "max_triangles = 0 # <-\n", "max_triangles = 0 is out of range"},
      {"CoverAreaRatioHalf", head + "min_cover_area_ratio = 0.5 # <-\n",
       "min_cover_area_ratio = 0.5 is out of range"},
      {"NegativeCurveTolerance", head + "curve_tolerance = -1 # <-\n", "curve_tolerance = -1"},
      {"FrictionAngleNinety", minimal + "[joints.bedding]\nfriction_angle = 90 # <-\n",
       "[joints.bedding] friction_angle = 90 is out of range; the friction angle must be >= 0 "
       "and < 90"},
      {"NegativeContactCohesion", minimal + "[contact]\ncohesion = -1 # <-\n",
       "[contact] cohesion = -1 is out of range"},
      {"ZeroContactNormalStiffness", minimal + "[contact]\nnormal_stiffness = 0 # <-\n",
       "[contact] normal_stiffness = 0 is out of range; a joint's stiffness must be > 0 (Pa/m)"},
      {"NegativeTensileStrength", minimal + "[joints.j]\ntensile_strength = -1e3 # <-\n",
       "tensile strength must be >= 0"},
      {"ZeroSteps", head + rock + "[analysis]\nsteps = 0 # <-\n",
       "steps = 0 is out of range; it must be from 1 to 100000000"},
      {"TooManySteps", head + rock + "[analysis]\nsteps = 2e8 # <-\n", "steps = 200000000 is out"},
      {"ZeroTimeStep", minimal + "time_step = 0.0 # <-\n", "time_step = 0 is out of range"},
      {"ZeroPenetrationTolerance", minimal + "penetration_tolerance = 0.0 # <-\n",
       "penetration_tolerance = 0 is out of range; it must be > 0 (m)"},
      {"TimeStepWord", minimal + "time_step = \"automatic\" # <-\n",
       "time_step = \"automatic\" is not allowed; write a number of seconds"},
      {"StepDisplacementTooLarge", minimal + "max_step_displacement = 0.6 # <-\n",
       "max_step_displacement = 0.6 is out of range"},
      {"ZeroPenalty", minimal + "penalty = 0 # <-\n", "penalty = 0 is out of range"},
      {"PenaltyAndStiffness", minimal + "penalty = 40\npenalty_stiffness = 1e11 # <-\n",
       "has both penalty"},
      {"ZeroOpenClose", minimal + "open_close_max = 0 # <-\n",
       "open_close_max = 0 is out of range"},
      {"TooManyStepCuts", minimal + "max_step_cuts = 51 # <-\n", "max_step_cuts = 51"},
      {"NegativeEndTime", minimal + "end_time = -1 # <-\n", "end_time = -1 is out of range"},
      {"RampBackwards", minimal + "[[load]]\ngravity = [0, -9.81]\nramp = [2.0, 1.0] # <-\n",
       "ramp = [2, 1] is out of range"},
      {"RampBeforeZero", minimal + "[[load]]\ngravity = [0, -9.81]\nramp = [-1.0, 1.0] # <-\n",
       "0 <= t0 <= t1"},
      {"OutputEveryZero", minimal + "[output]\nevery = 0 # <-\n", "[output] every = 0 is out"},
      {"NegativeCheckpoint", minimal + "[output]\ncheckpoint_every = -1 # <-\n",
       "checkpoint_every = -1"},
      {"NegativeMovedThreshold", minimal + "[output]\nmoved_threshold = -0.1 # <-\n",
       "[output] moved_threshold = -0.1 is out of range; the displacement beyond which a block "
       "counts as moved must be >= 0 (m)"},
      {"PcgToleranceTooLoose", minimal + "solver = \"pcg\"\npcg_tolerance = 0.01 # <-\n",
       "pcg_tolerance = 0.01 is out of range"},
      {"PcgToleranceZero", minimal + "pcg_tolerance = 0 # <-\n",
       "pcg_tolerance = 0 is out of range"},
      {"ZeroEnergyTolerance", minimal + "energy_tolerance = 0 # <-\n",
       "energy_tolerance = 0 is out of range; it must be > 0 and <= 1"},
      {"EnergyToleranceAboveOne", minimal + "energy_tolerance = 1.5 # <-\n",
       "energy_tolerance = 1.5 is out of range"},
      {"EnergyLimitBelowTolerance", minimal + "energy_error_limit = 0.01 # <-\n",
       "energy_error_limit = 0.01 is out of range; it must be >= energy_tolerance (0.05)"},
      {"ZeroVelocityRatio", minimal + "velocity_ratio = 0 # <-\n",
       "velocity_ratio = 0 is out of range; it must be > 0 and <= 1"},
      {"VelocityRatioAboveOne", minimal + "velocity_ratio = 1.1 # <-\n",
       "velocity_ratio = 1.1 is out of range"},
      // choices
      {"ChoiceSuggestsCase", minimal + "solver = \"Cholmod\" # <-\n",
       "solver = \"Cholmod\" is not allowed; did you mean \"cholmod\"?"},
      {"AnalysisKindSuggestion", head + rock + "[analysis]\nkind = \"statics\" # <-\n",
       "did you mean \"static\"?"},
      {"WaterUnitWeightWithoutLevel",
       head + rock + "[[load]]\ncurve = \"face\"\npressure = 1.0\nwater_unit_weight = 1.0 # <-\n",
       "water_unit_weight goes with water_level"},
      {"WaterOnATraction",
       head + rock + "[[load]]\ncurve = \"face\"\ntraction = [1.0, 0.0]\nwater_level = 1.0 # <-\n",
       "has both traction and water_level"},
      {"WaterOnGravity", head + rock + "[[load]]\ngravity = [0.0, -9.81]\nwater_level = 1.0 # <-\n",
       "a [[load]] with gravity takes no water_level"},
      {"EquilibriumNotABoolean",
       head + rock + "[analysis]\nsteps = 1\ninitial_equilibrium = \"yes\" # <-\n",
       "[analysis] initial_equilibrium must be true or false (without quotes), not a string"},
      {"UnknownModel", head + "[materials.rock]\nmodel = \"abc\" # <-\n",
       "model = \"abc\" is not allowed; use one of \"nmm\", \"dda\", \"vem\""},
      {"FemModelIsNmmOnAConformingMesh", head + "[materials.rock]\nmodel = \"FEM\" # <-\n",
       "FEM is model = \"nmm\""},
      {"FixZ", minimal + "[[boundary]]\ncurve = \"base\"\nfix = \"z\" # <-\n",
       "use one of \"x\", \"y\", \"xy\""},
      {"GeometryNotGmsh", "geometry = \"slope.step\" # <-\n[cover_mesh]\nsize = 1\n",
       "is not a .geo or .msh file"},
      // missing keys and tables
      {"MissingGeometry", "title = \"x\" # <-\n[cover_mesh]\nsize = 1\n",
       "no geometry key; add geometry = \"slope.geo\""},
      {"MissingCoverMesh", "geometry = \"slope.geo\" # <-\n" + rock + analysis,
       "no [cover_mesh] table"},
      {"MissingSize", "geometry = \"slope.geo\"\n[cover_mesh] # <-\nkind = \"gmsh\"\n",
       "[cover_mesh] is missing size"},
      {"MissingYoung", head + "[materials.rock] # <-\npoisson = 0.25\n",
       "[materials.rock] is missing young (Young's modulus in Pa); add a line such as young = "},
      {"MissingPoisson", head + "[materials.rock] # <-\nyoung = 5e9\n",
       "[materials.rock] is missing poisson"},
      {"MissingSteps", head + rock + "[analysis] # <-\nkind = \"static\"\n",
       "[analysis] is missing steps"},
      {"MissingAnalysis", "geometry = \"slope.geo\" # <-\n[cover_mesh]\nsize = 1\n" + rock,
       "no [analysis] table"},
      {"NoMaterial", "geometry = \"slope.geo\" # <-\n[cover_mesh]\nsize = 1\n" + analysis,
       "no material"},
      {"EmptyMaterialsTable", head + "[materials] # <-\n" + analysis, "no material"},
      {"DensityNeededWhenDynamic",
       head + "[materials.rock] # <-\nyoung = 5e9\npoisson = 0.2\n" + analysis,
       "[materials.rock] is missing density (kg/m^3), which a dynamic analysis needs"},
      {"DensityNeededForGravity",
       head + "[materials.rock] # <-\nyoung = 5e9\npoisson = 0.2\n[analysis]\nkind = \"static\"\n"
              "steps = 1\n[[load]]\ngravity = [0, -9.81]\n",
       "which the gravity [[load]] at line 10 needs"},
      {"MissingFix", minimal + "[[boundary]] # <-\ncurve = \"base\"\n",
       "[[boundary]] is missing fix"},
      {"MissingForce", minimal + "[[load]] # <-\npoint = \"P\"\n", "[[load]] is missing force"},
      {"MissingMonitorPoint", minimal + "[[monitor]] # <-\nname = \"crest\"\n",
       "[[monitor]] is missing point"},
      // structure
      {"BoundaryWithCurveAndPoint",
       minimal + "[[boundary]]\ncurve = \"base\"\npoint = \"A\" # <-\nfix = \"xy\"\n",
       "a [[boundary]] has both curve and point"},
      {"BoundaryWithNeither", minimal + "[[boundary]] # <-\nfix = \"xy\"\n",
       "needs curve = \"NAME\" (a Physical Curve) or point = \"NAME\""},
      {"EmptyBoundaryName", minimal + "[[boundary]]\ncurve = \"\" # <-\nfix = \"xy\"\n",
       "curve is empty"},
      {"BoundaryAsSingleTable", minimal + "[boundary] # <-\ncurve = \"base\"\nfix = \"xy\"\n",
       "boundary must be an array of tables, not a table; write [[boundary]]"},
      {"AnalysisAsArray", head + rock + "[[analysis]] # <-\nsteps = 1\n",
       "analysis must be one table, not an array of tables; write [analysis], not [[analysis]]"},
      {"MaterialKeyOnMaterialsItself", head + "[materials]\nyoung = 5e9 # <-\n",
       "young cannot be set on [materials] itself; write [materials.NAME]"},
      {"LoadWithTwoForms", minimal + "[[load]]\ngravity = [0, -9.81]\npoint = \"P\" # <-\n",
       "a [[load]] has both gravity and point"},
      {"LoadWithNoForm", minimal + "[[load]] # <-\nforce = [1, 0]\n", "a [[load]] needs one of"},
      {"GravityWithForce", minimal + "[[load]]\ngravity = [0, -9.81]\nforce = [1, 0] # <-\n",
       "a [[load]] with gravity takes no force"},
      {"PointLoadWithPressure", minimal + "[[load]]\npoint = \"P\"\npressure = 1e5 # <-\n",
       "takes no pressure"},
      {"CurveLoadWithBoth",
       minimal + "[[load]]\ncurve = \"top\"\ntraction = [0, 1]\npressure = 1e5 # <-\n",
       "has both traction and pressure"},
      {"CurveLoadWithNeither", minimal + "[[load]] # <-\ncurve = \"top\"\n",
       "a [[load]] on curve \"top\" needs traction"},
      {"DuplicateMonitor",
       minimal +
           "[[monitor]]\nname = \"crest\"\npoint = [0, 0]\n[[monitor]]\nname = \"crest\" # <-\n"
           "point = [1, 1]\n",
       "monitor name \"crest\" is already used by the [[monitor]] at line"},
      {"MonitorNameWithSpace", minimal + "[[monitor]]\nname = \"top left\" # <-\npoint = [0, 0]\n",
       "contains ' '; use only letters, digits and _ (it prefixes the history.csv columns), e.g. "
       "name = \"top_left\""},
      {"MonitorNameWithDot", minimal + "[[monitor]]\nname = \"a.b\" # <-\npoint = [0, 0]\n",
       "contains '.'"},
      {"TopLevelWrongType", "geometry = 5 # <-\n", "geometry must be a string in double quotes"},
      {"EmptyGeometry", "geometry = \"\" # <-\n", "geometry is empty"},
      // values no model can hold (issue 43): finite in TOML, not in the step equations
      {"ForceBeyondDouble", minimal + "[[load]]\npoint = \"P\"\nforce = [1.0e308, 0.0] # <-\n",
       "[[load]] force is 1e+308, which is not finite in the model's units"},
      {"GravityBeyondDouble", minimal + "[[load]]\ngravity = [0.0, -1.0e300] # <-\n",
       "[[load]] gravity is -1e+300, which is not finite in the model's units"},
      {"VelocityBeyondDouble",
       head +
           "[materials.rock]\ndensity = 2600.0\nyoung = 5.0e9\npoisson = 0.25\n"
           "initial_velocity = [1.0e200, 0.0] # <-\n" +
           analysis,
       "[materials.rock] initial_velocity is 1e+200, which is not finite in the model's units"},
      {"TractionBeyondDouble", minimal + "[[load]]\ncurve = \"C\"\ntraction = [0, -1e150] # <-\n",
       "overflow double precision"},
      {"PressureBeyondDouble", minimal + "[[load]]\ncurve = \"C\"\npressure = 1e120 # <-\n",
       "[[load]] pressure is 1e+120"},
      {"InitialStressBeyondDouble",
       head + rock + "initial_stress = [0, -1e200, 0] # <-\n" + analysis,
       "[materials.rock] initial_stress is -1e+200"},
      {"DensityBeyondDouble", head + "[materials.rock]\ndensity = 1e101 # <-\n",
       "density is 1e+101"},
      {"PenaltyMakesTheSystemSingular", minimal + "penalty = 1e30 # <-\n",
       "[analysis] penalty = 1e+30 is out of range; springs more than 1e12 times the largest "
       "Young's modulus make the step system singular"},
      {"PenaltyStiffnessMakesTheSystemSingular", minimal + "penalty_stiffness = 1e25 # <-\n",
       "[analysis] penalty_stiffness = 1e+25 N/m is 2e+15 times the largest Young's modulus "
       "(5e+09 Pa); springs more than 1e12 times"},
      {"HugeWholeNumber", head + rock + "[analysis]\nsteps = 1e300 # <-\n",
       "steps = 1e+300 is out of range; it must be from 1 to 100000000"},
      {"DateForNumber", head + "[materials.rock]\nyoung = 1979-05-27 # <-\n",
       "young must be a number (Pa), not a date or time"},
      {"SubTableInMaterial", head + rock + "[materials.rock.elastic] # <-\nyoung = 1\n",
       "[materials.rock] has no key elastic"},
      {"MaterialIsNotATable", head + "[materials]\nrock = 5 # <-\n",
       "materials.rock must be a table, not an integer; write [materials.rock]"},
      {"EmptyOutputDir", minimal + "[output]\ndir = \"\" # <-\n", "[output] dir is empty"},
  };
}

class MalformedCase : public ::testing::TestWithParam<BadCase> {};

TEST_P(MalformedCase, IsRejectedAtItsLineWithARemedy) {
  const BadCase& bad = GetParam();
  const int line = marked_line(bad.text);
  try {
    static_cast<void>(parse_case_text(bad.text, "case.toml"));
    FAIL() << "accepted:\n" << bad.text;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(bad.expected), std::string::npos)
        << "message: " << message << "\nexpected to contain: " << bad.expected;
    EXPECT_EQ(error.line(), line) << message;
    EXPECT_EQ(error.file(), "case.toml");
    // "file:line:column: what is wrong; what to do"
    const std::string place = "case.toml:" + std::to_string(line) + ":";
    EXPECT_EQ(message.rfind(place, 0), 0u) << message;
    EXPECT_NE(message.find("; "), std::string::npos) << "no remedy in: " << message;
  }
}

INSTANTIATE_TEST_SUITE_P(CaseFile,
                         MalformedCase,
                         ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& parameter) {
                           return std::string(parameter.param.name);
                         });

TEST(CaseFile, ColumnPointsAtTheOffendingKeyOrValue) {
  const auto message_of = [](const std::string& text) {
    try {
      static_cast<void>(parse_case_text(text, "case.toml"));
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("accepted");
  };
  // Unknown key: its own column.
  EXPECT_EQ(message_of(head + "[materials.rock]\n  yung = 5e9\n").rfind("case.toml:5:3:", 0), 0u);
  // Wrong value: the value's column.
  EXPECT_EQ(message_of(head + "[materials.rock]\nyoung = \"5e9\"\n").rfind("case.toml:5:9:", 0),
            0u);
}

// ---- read_case_file: the file system ----

class CaseFileOnDisk : public ::testing::Test {
protected:
  void SetUp() override { fs::create_directories(folder_ / "case"); }
  void write(const fs::path& path, const std::string& text) const {
    std::ofstream(folder_ / path) << text;
  }
  testing::TempDir temp_{"nmm_case_file_test"};
  fs::path folder_ = temp_.path();
};

TEST_F(CaseFileOnDisk, ResolvesTheGeometryNextToTheCaseFile) {
  write("case/slope.geo", "// geometry\n");
  write("case/case.toml", minimal);
  const CaseSpec spec = read_case_file(folder_ / "case/case.toml");
  EXPECT_EQ(spec.geometry, (folder_ / "case/slope.geo").lexically_normal());
  EXPECT_TRUE(fs::exists(spec.geometry));
  EXPECT_EQ(spec.output.dir, (folder_ / "case/out").lexically_normal());
}

TEST_F(CaseFileOnDisk, MissingGeometryIsReportedAtTheGeometryLine) {
  write("case/case.toml", "# a comment first\n" + minimal);
  try {
    static_cast<void>(read_case_file(folder_ / "case/case.toml"));
    FAIL() << "missing geometry accepted";
  } catch (const InputError& error) {
    EXPECT_EQ(error.line(), 2);
    EXPECT_NE(std::string(error.what()).find("slope.geo does not exist"), std::string::npos)
        << error.what();
  }
}

TEST_F(CaseFileOnDisk, MissingCaseFileIsAnInputError) {
  EXPECT_THROW(static_cast<void>(read_case_file(folder_ / "nothing.toml")), InputError);
}

} // namespace
} // namespace nmm
