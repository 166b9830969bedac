// SPDX-License-Identifier: MIT
// tests/regression/example_run.hpp — runs one bundled example as a user does,
// `nmm run examples/NAME/case.toml -o DIR --quiet`, and reads back its summary.json and the
// last row of its history.csv, for the checks of the examples' right answers.
#pragma once

#include "../support/json_reader.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace nmm::testing {

/// What one run of an example left: the program's output, summary.json, and the last row of
/// history.csv by column name.
struct ExampleRun {
  ProcessResult process;
  Json summary;
  std::map<std::string, double> last_row;

  /// The value of monitor @p monitor's key @p key (`uy`, `sxx`, ...) in summary.json.
  [[nodiscard]] double monitor(const std::string& monitor, const std::string& key) const {
    return summary.at("monitors").at(monitor).at(key).number;
  }
};

/// A fixture with a temporary folder that runs examples into it.
class Example : public ::testing::Test {
protected:
  Example() : dir_("nmm_example") {}

  /// Runs examples/@p name/case.toml into a folder of its own; checks that it completed.
  ExampleRun run(const std::string& name) {
    const fs::path out = dir_.path() / name;
    const fs::path program = NMM_EXECUTABLE;
    const fs::path case_file = fs::path(NMM_EXAMPLES_DIR) / name / "case.toml";
    ExampleRun result;
    result.process = run_process(
        {program.string(), "run", case_file.string(), "-o", out.string(), "--quiet"}, out);
    EXPECT_EQ(result.process.exit_code, 0) << result.process.err;
    EXPECT_NE(result.process.out.find("completed"), std::string::npos) << result.process.out;
    result.summary = parse_json(read_text(out / "summary.json"));
    EXPECT_EQ(result.summary.at("status").string, "completed");
    // history.csv: the header, then one row per step; keep the last.
    std::istringstream history(read_text(out / "history.csv"));
    std::string header;
    std::string row;
    std::getline(history, header);
    for (std::string line; std::getline(history, line);)
      row = line;
    std::istringstream names(header);
    std::istringstream values(row);
    std::string name_of_column;
    std::string value;
    while (std::getline(names, name_of_column, ',') && std::getline(values, value, ','))
      result.last_row[name_of_column] = std::stod(value);
    EXPECT_FALSE(result.last_row.empty()) << "no step in history.csv";
    return result;
  }

private:
  TempDir dir_;
};

} // namespace nmm::testing
