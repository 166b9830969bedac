// SPDX-License-Identifier: MIT
#include "io/progress.hpp"

#include "io/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace nmm {

namespace {

constexpr std::size_t max_listed_warnings = 10;

} // namespace

std::string duration_text(double seconds) {
  char text[48];
  if (!std::isfinite(seconds) || seconds < 0.0)
    return "?";
  if (seconds < 60.0) {
    if (seconds < 10.0)
      std::snprintf(text, sizeof text, "%.2f s", seconds);
    else
      std::snprintf(text, sizeof text, "%.0f s", seconds);
  } else if (seconds < 3600.0) {
    const long s = std::lround(seconds);
    std::snprintf(text, sizeof text, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60.0);
    std::snprintf(text, sizeof text, "%ld h %02ld min", m / 60, m % 60);
  }
  return text;
}

std::string progress_text(const RunProgress& progress) {
  const StepReport& r = *progress.report;
  std::ostringstream out;
  out << "step " << r.step << '/' << progress.steps << "  t = " << number_text(r.time, 6)
      << " s  dt = " << number_text(r.dt, 3) << " s  open-close " << r.open_close_iterations
      << "  contacts " << r.contacts;
  if (progress.step_cuts > 0)
    out << "  cuts " << progress.step_cuts;
  double done =
      progress.steps > 0 ? static_cast<double>(r.step) / static_cast<double>(progress.steps) : 0.0;
  if (std::isfinite(progress.end_time) && progress.end_time > 0.0)
    done = std::max(done, r.time / progress.end_time);
  done = std::min(done, 1.0);
  out << "  ETA ";
  if (done > 0.0 && progress.wall_seconds > 0.0)
    out << duration_text(progress.wall_seconds * (1.0 - done) / done);
  else
    out << '?';
  return out.str();
}

void ProgressPrinter::phase(std::string_view text) {
  if (mode_ == ProgressMode::quiet)
    return;
  finish();
  out_ << "nmm: " << text << '\n' << std::flush;
}

void ProgressPrinter::warning(std::string_view text) {
  if (mode_ == ProgressMode::quiet)
    return;
  finish();
  out_ << "warning: " << text << '\n' << std::flush;
}

void ProgressPrinter::step(const RunProgress& progress, bool force) {
  const double interval = mode_ == ProgressMode::terminal ? 0.1 : 2.0;
  if (mode_ == ProgressMode::quiet || (!force && progress.wall_seconds - last_print_ < interval))
    return;
  last_print_ = progress.wall_seconds;
  if (mode_ == ProgressMode::terminal) {
    // Carriage return, the line, then erase whatever a longer previous line left.
    out_ << '\r' << progress_text(progress) << "\033[K" << std::flush;
    line_open_ = true;
  } else {
    out_ << progress_text(progress) << '\n' << std::flush;
  }
}

void ProgressPrinter::finish() {
  if (line_open_) {
    out_ << '\n' << std::flush;
    line_open_ = false;
  }
}

void write_closing_summary(std::ostream& out, const RunResult& result, long steps_requested) {
  const bool completed = result.status == RunStatus::completed;
  out << "nmm: " << (completed ? "completed" : "interrupted") << ": " << result.steps
      << (completed ? "" : " of " + std::to_string(steps_requested))
      << (result.steps == 1 ? " step" : " steps") << ", simulated time "
      << number_text(result.time, 6) << " s, wall time " << duration_text(result.wall_seconds)
      << ", " << result.step_cuts << (result.step_cuts == 1 ? " step cut" : " step cuts");
  if (result.max_penetration > 0.0)
    out << ", max contact penetration " << number_text(result.max_penetration, 3) << " m";
  out << '\n';
  if (result.slides_against_motion > 0) {
    out << "  friction: " << result.slides_against_motion
        << (result.slides_against_motion == 1 ? " step" : " steps")
        << " ended with a contact held sliding at its friction limit against a motion that "
           "turned back ("
        << number_text(result.slide_feed_work, 3) << " J of friction work along it";
    if (result.load_work > 0.0)
      out << ", " << number_text(100.0 * result.slide_feed_work / result.load_work, 2)
          << "% of the work of the loads";
    // Halving the time step of the 100-block pile of bench/stress.py cut it 6.6 times.
    out << "; the chatter rule, less with a shorter time step)\n";
  }
  if (result.cg_iterations > 0 || result.cg_fallbacks > 0) {
    // [analysis] solver = "pcg": what the conjugate gradients did, and where they did not pay.
    out << "  linear solves: " << result.solves << " (conjugate gradients: " << result.cg_iterations
        << " iterations; " << result.cg_fallbacks << " solves left to CHOLMOD)";
    if (2 * result.cg_fallbacks > result.solves)
      out << "; most systems were not for conjugate gradients (static steps, stiff springs on "
             "light blocks): solver = \"cholmod\" is faster for this case";
    out << '\n';
  }
  if (result.warnings.empty()) {
    out << "  warnings: none\n";
  } else {
    out << "  warnings: " << result.warnings.size() << '\n';
    for (std::size_t k = 0; k < std::min(result.warnings.size(), max_listed_warnings); ++k)
      out << "    " << result.warnings[k] << '\n';
    if (result.warnings.size() > max_listed_warnings)
      out << "    ... (all of them in summary.json)\n";
  }
  const std::string dir = result.output_dir.string();
  out << "  outputs:  " << dir << "/case.pvd (" << result.output_steps
      << (result.output_steps == 1 ? " step file" : " step files") << "; open it in ParaView), "
      << dir << "/history.csv, " << dir << "/summary.json\n";
}

} // namespace nmm
