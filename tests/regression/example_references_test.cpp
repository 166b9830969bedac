// SPDX-License-Identifier: MIT
// Every bundled example (issue 7, "regression tests running every example at reduced
// size"): the first few steps of each (`nmm run CASE --steps N`; 05 and 06 on a cover mesh
// four times coarser than theirs) against what they gave when
// tests/regression/data/example_references.json was written by
// scripts/update_example_references.py. The examples' right answers are checked elsewhere
// (examples_test.cpp, slow_examples_test.cpp, block_examples_test.cpp, cli_test.cpp); this
// test catches any change of result, meant or not: a change that is meant updates the file
// and says why in its commit.
#include "example_run.hpp"
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <string>
#include <vector>

namespace nmm {
namespace {

using testing::Example;
using testing::ExampleRun;
using testing::Json;

const Json& references() {
  static const Json json =
      testing::parse_json(testing::read_text(testing::fs::path(NMM_REFERENCES_FILE)));
  return json;
}

std::vector<std::size_t> reference_indices() {
  std::vector<std::size_t> indices(references().at("examples").items.size());
  for (std::size_t k = 0; k < indices.size(); ++k)
    indices[k] = k;
  return indices;
}

/// "10_rotating_triangle/case_vem.toml" -> "10_rotating_triangle_case_vem".
std::string test_name(std::size_t k) {
  std::string name = references().at("examples").items[k].at("case").string;
  name = name.substr(0, name.rfind(".toml"));
  std::replace_if(
      name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  return name;
}

// The monitor values by kind: a value is compared against the largest of its kind in the
// case (positions against the largest coordinate), so that a component that is nearly zero
// is not held to a relative precision it never had.
const std::vector<std::vector<std::string>> kinds{
    {"x", "y"}, {"ux", "uy"}, {"vx", "vy"}, {"sxx", "syy", "sxy"}};

// OpenBLAS picks its kernels by CPU (SkylakeX with AVX-512, Haswell with AVX2, Zen, ...) and
// their summation orders differ in the last bits, which some examples amplify far beyond
// rounding: the open-close iteration stops at the first iterate within its tolerances
// (friction 1e-5, lift-off 1e-4 of the contact work and force), and which iterate that is
// depends on those bits. examples/12 case_phi30 after 10 steps on one machine: top_right.uy
// -0.0091774 m with the SkylakeX kernels, -0.0092166 m with Haswell's and Zen's, -0.0092161 m
// with Sandybridge's. So the references are written (scripts/update_example_references.py)
// and checked with one set of kernels, Haswell's, which every x86-64 CPU with AVX2 runs
// (OpenBLAS reads OPENBLAS_CORETYPE when nmm starts; the child processes inherit it).
bool cpu_has_avx2() {
  const std::string cpuinfo = testing::read_text("/proc/cpuinfo");
  return cpuinfo.find(" avx2") != std::string::npos;
}

class ExampleReference : public Example, public ::testing::WithParamInterface<std::size_t> {
protected:
  static void SetUpTestSuite() {
    if (cpu_has_avx2())
      ::setenv("OPENBLAS_CORETYPE", "Haswell", 1);
  }

  /// The case to run for @p reference: the example's own, or, when the reference has
  /// `edits` (pairs of text and replacement, e.g. a coarser cover size), a copy edited as
  /// scripts/update_example_references.py edits it, beside a copy of its geometry.
  testing::fs::path case_to_run(const Json& reference, const std::string& name) {
    const testing::fs::path example =
        testing::fs::path(NMM_EXAMPLES_DIR) / reference.at("case").string;
    const Json* edits = reference.find("edits");
    if (edits == nullptr)
      return example;
    std::string text = testing::read_text(example);
    for (const Json& edit : edits->items) {
      const std::string& old_text = edit.items.at(0).string;
      const std::size_t at = text.find(old_text);
      EXPECT_TRUE(at != std::string::npos && text.find(old_text, at + 1) == std::string::npos)
          << "'" << old_text << "' is not in " << example << " exactly once";
      if (at != std::string::npos)
        text.replace(at, old_text.size(), edit.items.at(1).string);
    }
    std::smatch geometry;
    const std::regex geometry_key(R"re(^geometry\s*=\s*"([^"]+)")re",
                                  std::regex::ECMAScript | std::regex::multiline);
    EXPECT_TRUE(std::regex_search(text, geometry, geometry_key)) << example;
    const testing::fs::path folder = dir() / (name + "-case");
    testing::fs::create_directories(folder);
    testing::fs::copy_file(example.parent_path() / geometry[1].str(), folder / geometry[1].str());
    const testing::fs::path edited = folder / example.filename();
    testing::write_text(edited, text);
    return edited;
  }
};

TEST_P(ExampleReference, FirstStepsGiveTheStoredMonitorsStepsAndCuts) {
  const Json& reference = references().at("examples").items[GetParam()];
  const std::string case_file = reference.at("case").string;
  const auto steps = static_cast<long>(reference.at("steps").number);
  const std::string test = test_name(GetParam());
  const ExampleRun run =
      run_case(case_to_run(reference, test), test, {"--steps", std::to_string(steps)});
  // Steps and cuts are decisions: the same, or the run went another way.
  EXPECT_EQ(run.summary.at("steps").number, reference.at("steps").number);
  EXPECT_EQ(run.summary.at("step_cuts").number, reference.at("step_cuts").number);
  // The run is deterministic: with the same BLAS kernels (above) the values are identical.
  // With another compiler or libm, rounding of 1e-16 grows through the factorisations of
  // stiff contact systems (condition numbers up to about 1e10) to about 1e-6 relative at
  // most; any change of method changes them by far more (a different cut, spring or formula
  // moves the monitors by 1e-4 or more).
  constexpr double tolerance = 1e-6;
  EXPECT_NEAR(run.summary.at("time").number, reference.at("time").number,
              tolerance * reference.at("time").number);
  const Json& monitors = reference.at("monitors");
  for (const std::vector<std::string>& kind : kinds) {
    double scale = 0.0;
    for (const auto& [name, values] : monitors.members)
      for (const std::string& key : kind)
        scale = std::max(scale, std::abs(values.at(key).number));
    for (const auto& [name, values] : monitors.members) {
      for (const std::string& key : kind) {
        EXPECT_NEAR(run.monitor(name, key), values.at(key).number, tolerance * scale)
            << case_file << ": monitor " << name << "." << key;
      }
    }
  }
  // The deepest penetration follows the same solves.
  const double penetration = reference.at("max_penetration").number;
  EXPECT_NEAR(run.summary.at("max_penetration").number, penetration, tolerance * penetration)
      << case_file;
}

INSTANTIATE_TEST_SUITE_P(Examples,
                         ExampleReference,
                         ::testing::ValuesIn(reference_indices()),
                         [](const ::testing::TestParamInfo<std::size_t>& parameter) {
                           return test_name(parameter.param);
                         });

} // namespace
} // namespace nmm
