// SPDX-License-Identifier: MIT
// io/progress.hpp — what `nmm run` prints while it runs and when it ends: one updating line
// on a terminal, plain lines about every 2 s otherwise, a state line every 30 s, and the
// closing summary.
#pragma once

#include "io/case_runner.hpp"

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace nmm {

/// How progress is shown.
enum class ProgressMode {
  terminal, ///< one line rewritten in place (carriage return), at most 10 times a second
  lines,    ///< a plain line about every 2 s of wall time (logs, pipes, CI)
  quiet     ///< nothing but the closing summary
};

/// The time a run still needs, from the wall time per simulated second and per step over
/// the last @c window seconds of wall time (since the run started before that): cut steps,
/// shorter and with more tries each, slow it down as much as they recently did. The run ends
/// at `[analysis] steps` or `end_time`, whichever comes first, so the estimate is the
/// smaller of the two.
class EtaEstimate {
public:
  explicit EtaEstimate(double window = 30.0) : window_(window) {}
  /// Where the run started: @p time (s) at step @p step, at wall time 0.
  void start(double time, long step);
  /// After a step: @p wall_seconds since the start, the simulated @p time (s) and @p step.
  void add(double wall_seconds, double time, long step);
  /// Wall seconds to `[analysis] steps` @p steps or @p end_time (s; +infinity: none),
  /// whichever the run reaches first; NaN before there is anything to extrapolate from.
  [[nodiscard]] double seconds_left(long steps, double end_time) const;

private:
  struct Sample {
    double wall = 0.0;
    double time = 0.0;
    long step = 0;
  };
  double window_;
  std::vector<Sample> samples_; ///< oldest first, about window_ / 32 apart; front: the base
  Sample now_;
};

/// "step 120/2000  t = 0.12 s  dt = 0.001 s  open-close 2/6  contacts 14  cuts 3 (open-close
/// 2, displacement 1)  ETA 12 s": the open-close iterations of the step's last try that count
/// against their limit (StepReport::open_close_counted) and that limit, the run's step cuts by
/// reason (when there are any), and the wall time still needed (@p eta_seconds, "ETA ?" when
/// not finite).
[[nodiscard]] std::string progress_text(const RunProgress& progress, double eta_seconds);

/// "open-close 1, displacement 1": the reasons of @p cuts, with before the restart @p earlier
/// cuts whose reasons are not known; empty without cuts.
[[nodiscard]] std::string cut_reasons_text(const CutCounts& cuts, long earlier = 0);

/// "step 1200 t = 0.6 s: 114 contacts closed, 37 sliding, deepest penetration 3.1e-08 m; 2
/// cuts since step 1000 (open-close 1, displacement 1)", then the energy balance's part when
/// RunProgress::energy_balance has one. @p cuts: since step @p since.
[[nodiscard]] std::string
state_text(const RunProgress& progress, const CutCounts& cuts, long since);

/// Prints phases and step progress to one stream (stderr in `nmm run`).
class ProgressPrinter {
public:
  /// Wall time between two state lines, s.
  static constexpr double state_interval = 30.0;

  ProgressPrinter(std::ostream& out, ProgressMode mode) : out_(out), mode_(mode) {}
  ProgressPrinter(const ProgressPrinter&) = delete;
  ProgressPrinter& operator=(const ProgressPrinter&) = delete;

  /// A line about what is being done ("reading slope.geo"); nothing when quiet.
  void phase(std::string_view text);
  /// A warning line; nothing when quiet (the closing summary lists warnings anyway).
  void warning(std::string_view text);
  /// After each step (every one: the ETA and the state line's cuts count them all); prints
  /// as the mode says, and a state line (state_text()) on its own line every state_interval
  /// seconds of wall time. The last step of a run should be passed with @p force so that
  /// the final state is shown.
  void step(const RunProgress& progress, bool force = false);
  /// Ends an open terminal line.
  void finish();

private:
  std::ostream& out_;
  ProgressMode mode_;
  double last_print_ = -1.0e300;
  bool line_open_ = false;
  EtaEstimate eta_;
  bool started_ = false;
  double last_state_ = 0.0;
  long state_since_ = 0; ///< the step of the last state line (the run's start before)
  CutCounts state_cuts_; ///< since then
};

/// The closing summary of a run: status, steps, time, wall time, step cuts, warnings and
/// where the outputs are (with the ParaView hint).
void write_closing_summary(std::ostream& out, const RunResult& result, long steps_requested);

/// A duration for people: "0.84 s", "2 min 05 s", "1 h 02 min".
[[nodiscard]] std::string duration_text(double seconds);

} // namespace nmm
