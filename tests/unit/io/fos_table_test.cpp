// SPDX-License-Identifier: MIT
// The `[fos]` table of a case file (io/fos_table.hpp, docs/case-file.md "[fos]"): its
// defaults, its values, and a clear error at the line of every value out of range or key
// it does not know; `nmm run` cases without it read as before.
#include "io/case_file.hpp"
#include "mesh/error.hpp"

#include <gtest/gtest.h>

#include <string>

namespace nmm {
namespace {

// [fos] is line 12 when appended, its first key line 13.
constexpr const char* base_case = R"(geometry = "slope.geo"
[cover_mesh]
size = 0.5
[materials.rock]
density = 2600.0
young = 1.0e9
poisson = 0.25
[joints.bedding]
friction_angle = 30.0
[analysis]
steps = 10
)";

CaseSpec parse(const std::string& fos) { return parse_case_text(base_case + fos, "case.toml"); }

/// The message of the InputError that parsing @p fos throws, or "" when it throws none.
std::string error_of(const std::string& fos) {
  try {
    (void)parse(fos);
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(FosTable, AbsentGivesTheDefaults) {
  const FosSpec fos = parse("").fos;
  EXPECT_EQ(fos.line, 0);
  EXPECT_EQ(fos.steps, 100);
  EXPECT_EQ(fos.decay, 0.1);
  EXPECT_EQ(fos.rest, 1e-10);
  EXPECT_EQ(fos.bracket_low, 1.0);
  EXPECT_EQ(fos.bracket_high, 2.0);
  EXPECT_EQ(fos.tolerance, 0.01);
  EXPECT_FALSE(fos.time_step_set); // the case's [analysis] time_step
}

TEST(FosTable, ReadsEveryKey) {
  const FosSpec fos = parse("[fos]\nsteps = 200\ndecay = 0.2\nrest = 1e-9\nbracket = [0.5, 3]\n"
                            "tolerance = 0.02\n")
                          .fos;
  EXPECT_EQ(fos.line, 12);
  EXPECT_EQ(fos.steps, 200);
  EXPECT_EQ(fos.decay, 0.2);
  EXPECT_EQ(fos.rest, 1e-9);
  EXPECT_EQ(fos.bracket_low, 0.5);
  EXPECT_EQ(fos.bracket_high, 3.0);
  EXPECT_EQ(fos.tolerance, 0.02);
  EXPECT_FALSE(fos.time_step_set);
}

TEST(FosTable, TimeStepIsANumberOrAuto) {
  const FosSpec fixed = parse("[fos]\ntime_step = 0.05\n").fos;
  EXPECT_TRUE(fixed.time_step_set);
  EXPECT_EQ(fixed.time_step, 0.05);
  const FosSpec automatic = parse("[fos]\ntime_step = \"auto\"\n").fos;
  EXPECT_TRUE(automatic.time_step_set);
  EXPECT_FALSE(automatic.time_step.has_value());
}

TEST(FosTable, ValuesOutOfRangeAreRefusedAtTheirLine) {
  // Both sides of every range.
  for (const auto& [fos, expected] :
       {std::pair{"steps = 9", "case.toml:13:9: [fos] steps = 9 is out of range"},
        std::pair{"steps = 1000001", "[fos] steps = 1000001 is out of range"},
        std::pair{"decay = 0.0", "case.toml:13:9: [fos] decay = 0 is out of range"},
        std::pair{"decay = 1.0", "[fos] decay = 1 is out of range"},
        std::pair{"rest = 0.0", "[fos] rest = 0 is out of range"},
        std::pair{"bracket = [0.0, 2.0]", "case.toml:13:11: [fos] bracket = [0, 2] is out of"},
        std::pair{"bracket = [2.0, 2.0]", "[fos] bracket = [2, 2] is out of range"},
        std::pair{"bracket = [1.0]", "[fos] bracket has 1 value(s) but needs exactly 2"},
        std::pair{"tolerance = 0.00009", "[fos] tolerance = 9e-05 is out of range"},
        std::pair{"tolerance = 0.6", "[fos] tolerance = 0.6 is out of range"},
        std::pair{"time_step = 0.0", "case.toml:13:13: [fos] time_step = 0 is out of range"},
        std::pair{"time_step = \"fast\"", "[fos] time_step = \"fast\" is not allowed"},
        std::pair{"step = 100", "case.toml:13:1: [fos] has no key step; did you mean steps?"}}) {
    const std::string message = error_of(std::string("[fos]\n") + fos + "\n");
    EXPECT_NE(message.find(expected), std::string::npos) << fos << ": " << message;
  }
  for (const char* fos :
       {"steps = 10", "steps = 1000000", "decay = 0.99", "rest = 1e-20", "bracket = [0.01, 0.02]",
        "tolerance = 0.0001", "tolerance = 0.5", "time_step = 1e-9"})
    EXPECT_EQ(error_of(std::string("[fos]\n") + fos + "\n"), "") << fos;
}

} // namespace
} // namespace nmm
