// SPDX-License-Identifier: MIT
// blocks.csv and summary.json's moved_blocks as a user reads them: the block of examples/03
// slides down its ramp (state sliding, its centroid moving as its monitor does), the same
// block on a ramp flatter than its friction angle rests, the moved blocks on both sides of
// [output] moved_threshold (restart_test.cpp compares blocks.csv of restarted runs).
#include "../support/case_fixtures.hpp"
#include "example_run.hpp"

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace nmm {
namespace {

namespace fs = std::filesystem;
using testing::Example;
using testing::ExampleRun;
using testing::read_text;
using testing::replaced;
using testing::write_text;

/// blocks.csv as rows of named fields (no quoted field in these cases).
std::vector<std::map<std::string, std::string>> read_blocks(const fs::path& file) {
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "step,time,block,material,x,y,ux,uy,rotation,vx,vy,omega,state");
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');)
    names.push_back(name);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::map<std::string, std::string> fields;
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ',') && k < names.size(); ++k)
      fields[names[k]] = cell;
    EXPECT_EQ(k, names.size()) << line;
    rows.push_back(fields);
  }
  return rows;
}

/// The row of material @p material at step @p step.
std::map<std::string, std::string>
row_of(const std::vector<std::map<std::string, std::string>>& rows,
       const std::string& material,
       long step) {
  for (const auto& row : rows)
    if (row.at("material") == material && std::stol(row.at("step")) == step)
      return row;
  ADD_FAILURE() << "no row of " << material << " at step " << step;
  return {};
}

double number(const std::map<std::string, std::string>& row, const std::string& key) {
  return row.count(key) ? std::stod(row.at(key)) : std::nan("");
}

class BlocksCsv : public Example {
protected:
  /// examples/03 with @p edits applied to its case file, run for @p steps steps into @p name.
  ExampleRun run_incline(const std::string& name,
                         const std::vector<std::pair<std::string, std::string>>& edits,
                         long steps) {
    const fs::path folder = fs::path(NMM_EXAMPLES_DIR) / "03_block_on_incline";
    std::string text = replaced(read_text(folder / "case.toml"), "geometry = \"incline.geo\"",
                                "geometry = \"" + (folder / "incline.geo").string() + "\"");
    for (const auto& [from, to] : edits)
      text = replaced(text, from, to);
    const fs::path case_file = dir() / (name + ".toml");
    write_text(case_file, text);
    return run_case(case_file, name, {"--steps", std::to_string(steps)});
  }
};

TEST_F(BlocksCsv, SlidingBlockSlidesWithItsMonitorAndTheRampRests) {
  const ExampleRun run =
      run_incline("slide", {{"every = 50", "every = 50\nmoved_threshold = 0.01"}}, 150);
  const auto rows = read_blocks(dir() / "slide" / "blocks.csv");
  ASSERT_EQ(rows.size(), 2u * 4u); // two blocks at steps 0, 50, 100, 150
  const auto block = row_of(rows, "block", 150);
  const auto ramp = row_of(rows, "ramp", 150);
  EXPECT_EQ(block.at("state"), "sliding");
  EXPECT_EQ(ramp.at("state"), "resting");
  // The monitor sits at the block's centroid: the centroid moves as it does, to the block's
  // elastic strain (the rows and history.csv are of the same step).
  const double ux = run.last("block.ux");
  const double uy = run.last("block.uy");
  EXPECT_LT(ux, -0.01); // down the ramp, to the lower left
  EXPECT_NEAR(number(block, "ux"), ux, 1e-4 * std::abs(ux));
  EXPECT_NEAR(number(block, "uy"), uy, 1e-4 * std::abs(uy));
  EXPECT_NEAR(number(block, "x"), run.last("block.x"), 1e-4 * std::abs(ux));
  EXPECT_NEAR(number(block, "vx"), run.last("block.vx"), 1e-3 * std::abs(run.last("block.vx")));
  EXPECT_NEAR(number(block, "rotation"), 0.0, 1e-4);
  EXPECT_NEAR(number(ramp, "ux"), 0.0, 1e-5);
  // Step 0: the start, nothing moved.
  EXPECT_EQ(number(row_of(rows, "block", 0), "ux"), 0.0);
  EXPECT_EQ(number(row_of(rows, "block", 0), "rotation"), 0.0);

  // moved_threshold 0.01 m: the block moved farther, the ramp did not.
  const auto& moved = run.summary.at("moved_blocks").items;
  ASSERT_EQ(moved.size(), 1u);
  EXPECT_EQ(moved[0].at("material").string, "block");
  EXPECT_EQ(moved[0].at("block").number, number(block, "block"));
  EXPECT_NEAR(moved[0].at("displacement").number, std::hypot(ux, uy), 1e-4 * std::hypot(ux, uy));

  // Just above the block's displacement, none; just below, the block.
  const double d = moved[0].at("displacement").number;
  const auto threshold = [](double value) {
    std::ostringstream text;
    text.precision(17);
    text << "every = 50\nmoved_threshold = " << value;
    return std::make_pair(std::string("every = 50"), text.str());
  };
  EXPECT_TRUE(
      run_incline("above", {threshold(d * 1.001)}, 150).summary.at("moved_blocks").items.empty());
  EXPECT_EQ(
      run_incline("below", {threshold(d * 0.999)}, 150).summary.at("moved_blocks").items.size(),
      1u);
}

TEST_F(BlocksCsv, BlockOnARampFlatterThanItsFrictionRests) {
  // Friction 60 degrees on the 45 degree ramp: the block stays put.
  const ExampleRun run =
      run_incline("rest",
                  {{"[joints.slip]\nfriction_angle = 30.0", "[joints.slip]\nfriction_angle = 60.0"},
                   {"[contact]              # the ramp's free surface that the block slides onto: "
                    "a contact takes\nfriction_angle = 30.0",
                    "[contact]\nfriction_angle = 60.0"}},
                  100);
  EXPECT_EQ(run.summary.find("moved_blocks"), nullptr); // no moved_threshold: no key
  const auto rows = read_blocks(dir() / "rest" / "blocks.csv");
  for (const long step : {50L, 100L}) {
    EXPECT_EQ(row_of(rows, "block", step).at("state"), "resting") << step;
    EXPECT_EQ(row_of(rows, "ramp", step).at("state"), "resting") << step;
  }
  EXPECT_LT(std::hypot(number(row_of(rows, "block", 100), "ux"),
                       number(row_of(rows, "block", 100), "uy")),
            1e-4);
}

} // namespace
} // namespace nmm
