// SPDX-License-Identifier: MIT
#include "io/progress.hpp"

#include "io/text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <utility>

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

void EtaEstimate::start(double time, long step) {
  now_ = {0.0, time, step};
  samples_.assign(1, now_);
}

void EtaEstimate::add(double wall_seconds, double time, long step) {
  now_ = {wall_seconds, time, step};
  // Samples about window_ / 32 apart keep the list short however fast the steps come.
  if (samples_.empty() || wall_seconds - samples_.back().wall >= window_ / 32.0)
    samples_.push_back(now_);
  // The base is the latest sample at least a window old (the start before there is one).
  while (samples_.size() > 1 && samples_[1].wall <= wall_seconds - window_)
    samples_.erase(samples_.begin());
}

double EtaEstimate::seconds_left(long steps, double end_time) const {
  constexpr double unknown = std::numeric_limits<double>::quiet_NaN();
  if (samples_.empty())
    return unknown;
  const Sample& base = samples_.front();
  const double wall = now_.wall - base.wall;
  double left = std::numeric_limits<double>::infinity();
  if (std::isfinite(end_time) && now_.time > base.time)
    left = std::max(end_time - now_.time, 0.0) * wall / (now_.time - base.time);
  if (steps > 0 && now_.step > base.step)
    left = std::min(left, static_cast<double>(std::max(steps - now_.step, 0L)) * wall /
                              static_cast<double>(now_.step - base.step));
  return wall > 0.0 && std::isfinite(left) ? left : unknown;
}

std::string cut_reasons_text(const CutCounts& cuts, long earlier) {
  const std::pair<const char*, long> parts[] = {{"open-close", cuts.open_close},
                                                {"displacement", cuts.displacement},
                                                {"energy", cuts.energy},
                                                {"not finite", cuts.not_finite},
                                                {"before the restart", earlier}};
  std::string text;
  for (const auto& [reason, n] : parts) {
    if (n <= 0)
      continue;
    if (!text.empty())
      text += ", ";
    text += std::string(reason) + ' ' + std::to_string(n);
  }
  return text;
}

std::string progress_text(const RunProgress& progress, double eta_seconds) {
  const StepReport& r = *progress.report;
  std::ostringstream out;
  out << "step " << r.step << '/' << progress.steps << "  t = " << number_text(r.time, 6)
      << " s  dt = " << number_text(r.dt, 3) << " s  open-close ";
  if (r.open_close_limit > 0)
    out << r.open_close_counted << '/' << r.open_close_limit;
  else
    out << r.open_close_iterations;
  out << "  contacts " << r.contacts;
  if (progress.step_cuts > 0)
    out << "  cuts " << progress.step_cuts << " ("
        << cut_reasons_text(progress.cuts, progress.step_cuts - progress.cuts.total()) << ')';
  out << "  ETA " << duration_text(eta_seconds);
  return out.str();
}

std::string state_text(const RunProgress& progress, const CutCounts& cuts, long since) {
  const StepReport& r = *progress.report;
  std::ostringstream out;
  out << "step " << r.step << " t = " << number_text(r.time, 6) << " s: ";
  if (r.contacts == 0)
    out << "no contact closed";
  else
    out << r.contacts << (r.contacts == 1 ? " contact" : " contacts") << " closed, " << r.sliding
        << " sliding, deepest penetration " << number_text(r.max_penetration, 2) << " m";
  const long n = cuts.total();
  out << "; " << (n == 0 ? std::string("no") : std::to_string(n)) << (n == 1 ? " cut" : " cuts")
      << " since step " << since;
  if (n > 0)
    out << " (" << cut_reasons_text(cuts) << ')';
  // The energy balance (work of the loads against the energies) is not computed here.
  if (!progress.energy_balance.empty())
    out << "; " << progress.energy_balance;
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
  if (mode_ == ProgressMode::quiet)
    return;
  const StepReport& report = *progress.report;
  if (!started_) {
    eta_.start(progress.start_time, progress.start_step);
    state_since_ = progress.start_step;
    started_ = true;
  }
  eta_.add(progress.wall_seconds, report.time, report.step);
  state_cuts_.add(report);
  if (progress.wall_seconds - last_state_ >= state_interval) {
    // On its own line, never overwritten: on a terminal it replaces the progress line, which
    // comes back below it.
    last_state_ = progress.wall_seconds;
    if (mode_ == ProgressMode::terminal)
      out_ << '\r' << state_text(progress, state_cuts_, state_since_) << "\033[K\n";
    else
      out_ << state_text(progress, state_cuts_, state_since_) << '\n';
    out_ << std::flush;
    line_open_ = false;
    state_since_ = report.step;
    state_cuts_ = {};
    force = true;
  }
  const double interval = mode_ == ProgressMode::terminal ? 0.1 : 2.0;
  if (!force && progress.wall_seconds - last_print_ < interval)
    return;
  last_print_ = progress.wall_seconds;
  const std::string text =
      progress_text(progress, eta_.seconds_left(progress.steps, progress.end_time));
  if (mode_ == ProgressMode::terminal) {
    // Carriage return, the line, then erase whatever a longer previous line left.
    out_ << '\r' << text << "\033[K" << std::flush;
    line_open_ = true;
  } else {
    out_ << text << '\n' << std::flush;
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
