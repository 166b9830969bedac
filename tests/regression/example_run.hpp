// SPDX-License-Identifier: MIT
// tests/regression/example_run.hpp — runs one bundled example as a user does,
// `nmm run examples/NAME/case.toml -o DIR --quiet`, and reads back its summary.json and its
// history.csv, for the checks of the examples' right answers.
#pragma once

#include "../support/json_reader.hpp"
#include "../support/process.hpp"
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace nmm::testing {

/// history.csv as columns by name (the header's names; one value per step).
inline std::map<std::string, std::vector<double>> read_history_columns(const fs::path& file) {
  std::istringstream in(read_text(file));
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::istringstream header(line);
  for (std::string name; std::getline(header, name, ',');)
    names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  for (const std::string& name : names)
    columns[name];
  while (std::getline(in, line)) {
    std::istringstream row(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ',') && k < names.size(); ++k) {
      // The `stage` column of a run in stages holds names: its numbers are none.
      char* end = nullptr;
      const double value = std::strtod(cell.c_str(), &end);
      if (end != cell.c_str())
        columns[names[k]].push_back(value);
    }
  }
  return columns;
}

/// The case file examples/@p example/@p case_file with @p line added at the top of its
/// [analysis] table and its geometry named by its full path: a variant of the example that
/// can be written to another folder.
inline std::string
example_variant(const std::string& example, const std::string& case_file, const std::string& line) {
  const fs::path folder = fs::path(NMM_EXAMPLES_DIR) / example;
  std::string text = read_text(folder / case_file);
  const std::string analysis = "[analysis]\n";
  const std::string geometry = "geometry = \"";
  const std::size_t at_analysis = text.find(analysis);
  const std::size_t at_geometry = text.find(geometry);
  const std::size_t name_end = text.find('"', at_geometry + geometry.size());
  EXPECT_NE(at_analysis, std::string::npos) << case_file;
  EXPECT_NE(name_end, std::string::npos) << case_file;
  if (at_analysis == std::string::npos || at_geometry == std::string::npos ||
      name_end == std::string::npos)
    return text;
  text.insert(at_analysis + analysis.size(), line + "\n");
  const std::size_t start = at_geometry + geometry.size();
  text.replace(start, name_end - start,
               (folder / text.substr(start, name_end - start)).generic_string());
  return text;
}

/// What one run of an example left: the program's output, summary.json, and history.csv.
struct ExampleRun {
  ProcessResult process;
  Json summary;
  std::map<std::string, std::vector<double>> history; ///< by column name

  /// The value of monitor @p monitor's key @p key (`uy`, `sxx`, ...) in summary.json.
  [[nodiscard]] double monitor(const std::string& monitor, const std::string& key) const {
    return summary.at("monitors").at(monitor).at(key).number;
  }
  /// The last step's value in history.csv's column @p column.
  [[nodiscard]] double last(const std::string& column) const {
    const std::vector<double>& values = history.at(column);
    EXPECT_FALSE(values.empty()) << "no step in history.csv";
    return values.empty() ? 0.0 : values.back();
  }
};

/// A fixture with a temporary folder that runs examples into it.
class Example : public ::testing::Test {
protected:
  Example() : dir_("nmm_example") {}

  /// Runs examples/@p name/case.toml into a folder of its own; checks that it completed.
  ExampleRun run(const std::string& name) {
    return run_case(fs::path(NMM_EXAMPLES_DIR) / name / "case.toml", name);
  }

  /// Runs @p case_file into the folder @p name of the fixture's, with @p options added to
  /// the command line (e.g. `--steps 10`); checks that it completed.
  ExampleRun run_case(const fs::path& case_file,
                      const std::string& name,
                      const std::vector<std::string>& options = {}) {
    const fs::path out = dir_.path() / name;
    const fs::path program = NMM_EXECUTABLE;
    ExampleRun result;
    std::vector<std::string> command{program.string(), "run",    case_file.string(), "-o",
                                     out.string(),     "--quiet"};
    command.insert(command.end(), options.begin(), options.end());
    result.process = run_process(command, out);
    EXPECT_EQ(result.process.exit_code, 0) << result.process.err;
    EXPECT_NE(result.process.out.find("completed"), std::string::npos) << result.process.out;
    result.summary = parse_json(read_text(out / "summary.json"));
    EXPECT_EQ(result.summary.at("status").string, "completed");
    result.history = read_history_columns(out / "history.csv");
    return result;
  }

  [[nodiscard]] const fs::path& dir() const { return dir_.path(); }

private:
  TempDir dir_;
};

} // namespace nmm::testing
