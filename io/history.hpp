// SPDX-License-Identifier: MIT
// io/history.hpp — history.csv (one row per step) and summary.json of `nmm run` (DESIGN.md
// "Contracts users see / Output"; docs/output.md shows both with examples).
#pragma once

#include "io/row_file.hpp"
#include "mesh/cover_system.hpp"
#include "solver/linear_solver.hpp"
#include "solver/time_stepper.hpp"

#include <array>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nmm {

/// What history.csv records of one monitor at the end of a step, SI units.
struct MonitorValues {
  double x = 0.0;   ///< current position, m
  double y = 0.0;   ///< current position, m
  double ux = 0.0;  ///< total displacement since the start, m
  double uy = 0.0;  ///< total displacement since the start, m
  double vx = 0.0;  ///< velocity, m/s
  double vy = 0.0;  ///< velocity, m/s
  double sxx = 0.0; ///< stress of the element holding the point, at the point, Pa
  double syy = 0.0; ///< Pa
  double sxy = 0.0; ///< Pa

  /// The values in the order of monitor_value_names.
  [[nodiscard]] std::array<double, 9> values() const noexcept {
    return {x, y, ux, uy, vx, vy, sxx, syy, sxy};
  }
};

/// The per-monitor column suffixes of history.csv and the keys of summary.json's monitors,
/// in contract order.
inline constexpr std::array<std::string_view, 9> monitor_value_names{"x",  "y",   "ux",  "uy", "vx",
                                                                     "vy", "sxx", "syy", "sxy"};

/// The header line of history.csv (without the newline): `step,time,dt,
/// open_close_iterations,contacts,kinetic_energy` then `m.x,m.y,...,m.sxy` per monitor, then
/// `load_work` and the columns added since (docs/output.md), then `stage` (with stages) and
/// `b.force` per bolt.
[[nodiscard]] std::string history_header(std::span<const std::string> monitor_names,
                                         std::span<const std::string> bolt_names = {},
                                         bool stage = false);

/// history.csv, written row by row, each row by one write(2) (no buffer), so that a run
/// that stops at any moment leaves every completed step on disk; a row that the disk or a
/// file-size limit cuts short is taken back, so the file always ends with a whole row.
/// Reals are written with 17 significant digits (%.17g: they read back bit for bit).
class HistoryWriter {
public:
  /// Creates (truncates) @p file and writes the header.
  /// @throws InputError naming the file when it cannot be written.
  HistoryWriter(std::filesystem::path file,
                std::vector<std::string> monitor_names,
                std::vector<std::string> bolt_names = {},
                bool stage = false);
  /// Continues @p file after a restart: keeps its first @p keep_bytes bytes (the header and
  /// the rows up to the checkpoint's step; bytes() when the checkpoint was written), drops
  /// the rest (rows the interrupted run wrote after it) and appends after them.
  /// @throws InputError naming the file when it is missing, shorter than @p keep_bytes,
  ///         does not end a row there, or its header is not the one of @p monitor_names.
  HistoryWriter(std::filesystem::path file,
                std::vector<std::string> monitor_names,
                std::uintmax_t keep_bytes,
                std::vector<std::string> bolt_names = {});
  /// Appends the row of one step, whole or not at all.
  /// @pre monitors.size() == the number of monitor names, bolt_forces.size() that of bolts.
  /// @throws OutputWriteError naming the file and the reason ("disk full: ...", "file too
  ///         large: ...") when the write fails; the file then ends with the row before.
  void write_row(const StepReport& report,
                 std::span<const MonitorValues> monitors,
                 std::span<const double> bolt_forces = {},
                 std::string_view stage = {});

  [[nodiscard]] const std::filesystem::path& file() const noexcept { return rows_.file(); }
  /// Size of the file so far: header and every row written, bytes.
  [[nodiscard]] std::uintmax_t bytes() const noexcept { return rows_.bytes(); }

private:
  std::size_t n_monitors_ = 0;
  std::size_t n_bolts_ = 0;
  bool stage_ = false;
  RowFile rows_;
};

/// A block that moved farther than `[output] moved_threshold` (summary.json's moved_blocks).
struct MovedBlock {
  int block = 0;             ///< the block id (blocks.csv, the step files' cell array `block`)
  std::string material;      ///< its material (blocks.csv's `material`)
  double displacement = 0.0; ///< length of its centroid's displacement since the start, m
};

/// A bolt at the last completed step (summary.json's bolts).
struct BoltSummary {
  std::string name;
  double force = 0.0;    ///< Bolt::force(), N (per metre in plane strain), tension positive
  std::string state;     ///< bolt_state_name() of Bolt::state()
  int bars = 0;          ///< its bars: 1 end-anchored, one per element crossed grouted
  int yielding_bars = 0; ///< of those, yielding at the step
  int ruptured_bars = 0; ///< of those, broken
};

/// A `[[stage]]` of the run (summary.json's stages).
struct StageSummary {
  std::string name;
  long first_step = 0; ///< 1-based
  long steps = 0;
};

/// Everything summary.json holds. The first group of members is DESIGN.md's contract, the
/// rest are extensions (docs/output.md).
struct RunSummary {
  /// "running" while the run goes on, "completed", "interrupted", or the error message of
  /// the failure that stopped it.
  std::string status = "running";
  long steps = 0;            ///< steps completed
  double time = 0.0;         ///< simulated time reached, s
  double wall_seconds = 0.0; ///< since the case file was read
  long dofs = 0;             ///< raw unknowns: covers x unknowns per cover
  int covers = 0;
  int elements = 0;
  int blocks = 0;
  std::vector<std::string> warnings;
  /// Monitor name and its values at the last completed step (the start if none).
  std::vector<std::pair<std::string, MonitorValues>> monitors;

  // Extensions.
  std::string title;
  std::string case_file;
  std::string geometry;
  long unknowns = 0; ///< unknowns of the linear system after eliminating constraints
  long step_cuts = 0;
  /// Deepest penetration of a closed contact at the end of any step so far, m.
  double max_penetration = 0.0;
  StepperCounters counters;
  SolverCounters solver_counters;
  /// Times the elements' stresses were recovered for output (centroid values, principal
  /// stresses and directions): once per step file, never in between.
  long stress_recoveries = 0;
  CoverMesherStats mesher;
  /// The blocks that moved farther than `[output] moved_threshold`, by block id; no value
  /// (and no key in summary.json) without that key.
  std::optional<std::vector<MovedBlock>> moved_blocks;
  /// The case's bolts, in the order of history.csv's columns; no key without bolts.
  std::vector<BoltSummary> bolts;
  /// The `[[stage]]` of the last step ("" before the first), and every stage; no keys
  /// without stages.
  std::string stage;
  std::vector<StageSummary> stages;
};

/// summary.json's text: an object with the keys in the order of RunSummary, two-space
/// indentation, strings escaped as JSON requires, reals with 17 significant digits except
/// wall-clock seconds (6), non-finite reals as null.
[[nodiscard]] std::string summary_json(const RunSummary& summary);

/// Writes summary_json(@p summary) to @p file atomically (as `file.tmp`, then renamed), with
/// 64 KiB allocated beyond its end: when the disk is full, so that the temporary file
/// cannot be written, the summary is written over the old one in place, into those blocks.
/// @throws InputError naming the file or directory when it cannot be written.
void write_summary_json(const std::filesystem::path& file, const RunSummary& summary);

/// @p text as a JSON string literal, quotes included: `"`, `\` and control characters
/// escaped; other bytes (UTF-8) are copied as they are.
[[nodiscard]] std::string json_string(std::string_view text);

/// @p value as a JSON number with 17 significant digits (%.17g), or `null` when it is not
/// finite (JSON has no NaN or infinity).
[[nodiscard]] std::string json_number(double value);

} // namespace nmm
