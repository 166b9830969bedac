// SPDX-License-Identifier: MIT
// io/progress.hpp — what `nmm run` prints while it runs and when it ends: one updating line
// on a terminal, plain lines about every 2 s otherwise, and the closing summary.
#pragma once

#include "io/case_runner.hpp"

#include <ostream>
#include <string>
#include <string_view>

namespace nmm {

/// How progress is shown.
enum class ProgressMode {
  terminal, ///< one line rewritten in place (carriage return), at most 10 times a second
  lines,    ///< a plain line about every 2 s of wall time (logs, pipes, CI)
  quiet     ///< nothing but the closing summary
};

/// "step 120/2000  t = 0.12 s  dt = 0.001 s  open-close 1  contacts 0  ETA 12 s".
/// The ETA extrapolates the wall time per step, or per simulated second when end_time
/// ends the run first; "ETA ?" before there is anything to extrapolate from.
[[nodiscard]] std::string progress_text(const RunProgress& progress);

/// Prints phases and step progress to one stream (stderr in `nmm run`).
class ProgressPrinter {
public:
  ProgressPrinter(std::ostream& out, ProgressMode mode) : out_(out), mode_(mode) {}
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  /// A line about what is being done ("reading slope.geo"); nothing when quiet.
  void phase(std::string_view text);
  /// A warning line; nothing when quiet (the closing summary lists warnings anyway).
  void warning(std::string_view text);
  /// After each step; prints as the mode says. The last step of a run should be passed
  /// with @p force so that the final state is shown.
  void step(const RunProgress& progress, bool force = false);
  /// Ends an open terminal line.
  void finish();

private:
  std::ostream& out_;
  ProgressMode mode_;
  double last_print_ = -1.0e300;
  bool line_open_ = false;
};

/// The closing summary of a run: status, steps, time, wall time, step cuts, warnings and
/// where the outputs are (with the ParaView hint).
void write_closing_summary(std::ostream& out, const RunResult& result, long steps_requested);

/// A duration for people: "0.84 s", "2 min 05 s", "1 h 02 min".
[[nodiscard]] std::string duration_text(double seconds);

} // namespace nmm
