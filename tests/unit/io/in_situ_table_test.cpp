// SPDX-License-Identifier: MIT
// The case file's [in_situ] table (issue 46, item 2): the k0 and the components forms, the
// unit weight from the materials' density and gravity, and each bad input refused on its
// line with what to do.
#include "io/case_file.hpp"
#include "mesh/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <ostream>
#include <string>
#include <vector>

namespace nmm {
namespace {

const std::string head = "geometry = \"box.geo\"\n[cover_mesh]\nsize = 0.5\n";
const std::string rock = "[materials.rock]\ndensity = 2600.0\nyoung = 5.0e9\npoisson = 0.25\n";
const std::string soil = "[materials.soil]\ndensity = 2000.0\nyoung = 5.0e8\npoisson = 0.3\n";
const std::string analysis = "[analysis]\nsteps = 10\n";
const std::string gravity = "[[load]]\ngravity = [0.0, -9.81]\n";

TEST(InSituTable, K0TakesEachMaterialsDensityTimesGravity) {
  const CaseSpec spec = parse_case_text(
      head + rock + soil + gravity + analysis + "[in_situ]\nsurface = 20.0\nk0 = 0.5\n", "c.toml");
  ASSERT_TRUE(spec.in_situ.has_value());
  EXPECT_EQ(spec.in_situ->k0.value(), 0.5);
  EXPECT_FALSE(spec.in_situ->unit_weight.has_value());
  const double rock_gamma = 2600.0 * 9.81;
  const double soil_gamma = 2000.0 * 9.81;
  EXPECT_EQ(spec.materials[0].initial_stress_gradient,
            Eigen::Vector3d(-0.5 * rock_gamma, -rock_gamma, 0.0));
  EXPECT_EQ(spec.materials[1].initial_stress_gradient,
            Eigen::Vector3d(-0.5 * soil_gamma, -soil_gamma, 0.0));
  EXPECT_TRUE(spec.materials[0].initial_stress.isZero());
  EXPECT_EQ(spec.materials[1].initial_stress_surface, 20.0);
  // Two densities, one default unit weight each: not in equilibrium across their interface.
  ASSERT_EQ(spec.warnings.size(), 1u);
  EXPECT_NE(spec.warnings[0].find("gives each material its own density x |g|"), std::string::npos)
      << spec.warnings[0];
}

TEST(InSituTable, AGivenUnitWeightIsOneFieldForEveryMaterialWithoutGravity) {
  const CaseSpec spec = parse_case_text(
      head + rock + soil + analysis + "[in_situ]\nsurface = -5\nk0 = 1.5\nunit_weight = 20000\n",
      "c.toml");
  for (const MaterialSpec& m : spec.materials) {
    EXPECT_EQ(m.initial_stress_gradient, Eigen::Vector3d(-30000.0, -20000.0, 0.0));
    EXPECT_EQ(m.initial_stress_surface, -5.0);
  }
  EXPECT_TRUE(spec.warnings.empty());
}

TEST(InSituTable, ComponentsAtTheSurfaceWithTheirGradients) {
  const CaseSpec spec = parse_case_text(
      head + rock + gravity + analysis +
          "[in_situ]\nsurface = 100.0\nsxx = -2.0e6\nsxy = 1e5\nsxx_gradient = -30000\n"
          "syy_gradient = -25506\n",
      "c.toml");
  const MaterialSpec& m = spec.materials[0];
  EXPECT_EQ(m.initial_stress, Eigen::Vector3d(-2.0e6, 0.0, 1.0e5));
  EXPECT_EQ(m.initial_stress_gradient, Eigen::Vector3d(-30000.0, -25506.0, 0.0));
  EXPECT_EQ(m.initial_stress_surface, 100.0);
  EXPECT_FALSE(spec.in_situ->k0.has_value());
  // A uniform field needs no surface.
  const CaseSpec uniform =
      parse_case_text(head + rock + analysis + "[in_situ]\nsyy = -1e6\n", "c.toml");
  EXPECT_EQ(uniform.materials[0].initial_stress, Eigen::Vector3d(0.0, -1.0e6, 0.0));
  EXPECT_TRUE(uniform.materials[0].initial_stress_gradient.isZero());
}

TEST(InSituTable, WithoutTheTableNothingChanges) {
  const CaseSpec spec = parse_case_text(head + rock + gravity + analysis, "c.toml");
  EXPECT_FALSE(spec.in_situ.has_value());
  EXPECT_TRUE(spec.materials[0].initial_stress_gradient.isZero());
  EXPECT_EQ(spec.materials[0].initial_stress_surface, 0.0);
}

TEST(InSituTable, ARampedOrTurnedGravityIsNotInEquilibriumWithTheField) {
  const std::string table = "[in_situ]\nsurface = 20.0\nk0 = 0.5\n";
  const CaseSpec ramped = parse_case_text(
      head + rock + "[[load]]\ngravity = [0.0, -9.81]\nramp = [0.0, 1.0]\n" + analysis + table,
      "c.toml");
  ASSERT_EQ(ramped.warnings.size(), 1u);
  EXPECT_NE(ramped.warnings[0].find("this gravity [[load]] is ramped"), std::string::npos);
  const CaseSpec turned = parse_case_text(
      head + rock + "[[load]]\ngravity = [1.0, -9.81]\n" + analysis + table, "c.toml");
  ASSERT_EQ(turned.warnings.size(), 1u);
  EXPECT_NE(turned.warnings[0].find("the field is not in equilibrium with it"), std::string::npos);
}

// ---- malformed input: each text must fail on the line marked "# <-" ----

struct BadCase {
  const char* name;
  std::string text;
  const char* expected; // a substring of the message
};

void PrintTo(const BadCase& bad, std::ostream* out) { *out << bad.name; }

int marked_line(const std::string& text) {
  const std::size_t marker = text.find("# <-");
  return 1 +
         static_cast<int>(std::count(text.begin(), text.begin() + static_cast<long>(marker), '\n'));
}

std::vector<BadCase> bad_cases() {
  const std::string base = head + rock + gravity + analysis;
  return {
      {"K0WithComponents", base + "[in_situ]\nsurface = 10\nk0 = 0.5\nsxx = -1e6 # <-\n",
       "[in_situ] sxx cannot be given with k0"},
      {"K0WithAGradient", base + "[in_situ]\nsurface = 10\nsyy_gradient = -2e4 # <-\nk0 = 0.5\n",
       "[in_situ] syy_gradient cannot be given with k0"},
      {"UnitWeightWithoutK0",
       base + "[in_situ]\nsurface = 10\nunit_weight = 2.5e4 # <-\nsyy_gradient = -2.5e4\n",
       "[in_situ] unit_weight is used only with k0"},
      {"NoStress", base + "[in_situ] # <-\nsurface = 10\n", "[in_situ] gives no stress; add k0"},
      {"EmptyTable", base + "[in_situ] # <-\n", "[in_situ] gives no stress"},
      {"NoSurfaceWithK0", base + "[in_situ] # <-\nk0 = 0.5\n",
       "[in_situ] is missing surface (the y coordinate of the ground surface"},
      {"NoSurfaceWithAGradient", base + "[in_situ] # <-\nsyy_gradient = -2.5e4\n",
       "[in_situ] is missing surface"},
      {"K0WithoutGravityOrUnitWeight",
       head + rock + analysis + "[in_situ]\nsurface = 10\nk0 = 0.5 # <-\n",
       "[in_situ] k0 needs the rock's unit weight, and the case has no gravity [[load]]"},
      {"NegativeK0", base + "[in_situ]\nsurface = 10\nk0 = -0.5 # <-\n",
       "[in_situ] k0 = -0.5 is out of range"},
      {"ZeroUnitWeight", base + "[in_situ]\nsurface = 10\nk0 = 0.5\nunit_weight = 0 # <-\n",
       "[in_situ] unit_weight = 0 is out of range; it must be > 0 (N/m^3)"},
      {"StringForSurface", base + "[in_situ]\nsurface = \"top\" # <-\nk0 = 0.5\n",
       "[in_situ] surface must be a number"},
      {"UnknownKey", base + "[in_situ]\nsurface = 10\nk_0 = 0.5 # <-\n",
       "[in_situ] has no key k_0; did you mean k0?"},
      {"MaterialsOwnInitialStress",
       head + rock + "initial_stress = [0, -1e6, 0]\n" + gravity + analysis +
           "[in_situ]\nsurface = 10\nk0 = 0.5 # <-\n",
       "[materials.rock] initial_stress (line 4) and [in_situ] both give the initial stress"},
      {"NotATable",
       "geometry = \"box.geo\"\nin_situ = 0.5 # <-\n[cover_mesh]\nsize = 0.5\n" + rock + gravity +
           analysis,
       "in_situ must be a table, not"},
  };
}

class InSituBadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(InSituBadInput, IsRefusedOnItsLineWithWhatToDo) {
  const BadCase& bad = GetParam();
  try {
    (void)parse_case_text(bad.text, "case.toml");
    FAIL() << "accepted: " << bad.text;
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find(bad.expected), std::string::npos) << message;
    EXPECT_NE(message.find("case.toml:" + std::to_string(marked_line(bad.text)) + ":"),
              std::string::npos)
        << message;
  }
}

INSTANTIATE_TEST_SUITE_P(InSituTable,
                         InSituBadInput,
                         ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& param) {
                           return std::string(param.param.name);
                         });

} // namespace
} // namespace nmm
