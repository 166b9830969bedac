// SPDX-License-Identifier: MIT
#include "io/fos.hpp"

#include "io/atomic_file.hpp"
#include "io/block_results.hpp"
#include "io/case_runner.hpp"
#include "io/history.hpp"
#include "io/step_output.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <utility>

namespace nmm {

namespace {

bool has_strength(const JointProperties& p) {
  return p.friction_angle_degrees > 0.0 || p.cohesion > 0.0 || p.tensile_strength > 0.0;
}

/// The moving blocks of the failing trial of smallest factor in which blocks kept moving
/// (one that failed by a step that could not be cut enough may have none): the mechanism
/// nearest the limit.
std::vector<int> failing_blocks(const std::vector<FosTrial>& trials) {
  const FosTrial* nearest = nullptr;
  for (const FosTrial& t : trials)
    if (t.failed && !t.moving_blocks.empty() && (nearest == nullptr || t.factor < nearest->factor))
      nearest = &t;
  return nearest != nullptr ? nearest->moving_blocks : std::vector<int>{};
}

/// The trials' time step: [fos] time_step when given, else the case's (empty: Shi's
/// automatic step). A static step starts at rest, so a body that the reduced strength lets
/// slide with acceleration a moves a dt^2 / 2 in it: [fos] time_step may make that longer than
/// the case's dynamic step (docs/case-file.md, "[fos]").
std::optional<double> trial_time_step(const CaseSpec& spec) {
  return spec.fos.time_step_set ? spec.fos.time_step : spec.analysis.time_step;
}

/// The steps at each end of a trial that the criterion compares: a tenth of them.
int window_of(int steps) { return std::max(1, steps / 10); }

/// A model that fails keeps moving at the rate it began with (a block sliding on a plane:
/// last/first step displacement about 1), one that stands comes to rest (about 0). Where the
/// failing end of the bracket failed by its motion alone, and decayed less than twice as
/// slowly as the standing end, the two differ by the threshold `decay` and not by their
/// mechanics (elastic blocks creeping in the static steps, a mechanism slower than the trial):
/// the factor found is the factor at which the creep crosses `decay`, not a limit state.
std::string separation_warning(const FosResult& result, double decay) {
  const auto trial_at = [&](double factor) -> const FosTrial* {
    for (const FosTrial& t : result.trials)
      if (t.factor == factor)
        return &t;
    return nullptr;
  };
  const FosTrial* stands = trial_at(result.stable);
  const FosTrial* fails = trial_at(result.failing);
  if (stands == nullptr || fails == nullptr || !fails->error.empty() ||
      !(fails->measure < 2.0 * stands->measure))
    return {};
  return "the trials at F = " + number_text(result.stable, 4) +
         " (stands) and F = " + number_text(result.failing, 4) +
         " (fails) decay alike: last/first step displacement " + number_text(stands->measure, 3) +
         " and " + number_text(fails->measure, 3) +
         " on either side of decay = " + number_text(decay, 3) +
         ", where a sliding mechanism keeps about 1 and a model at rest about 0; the model "
         "creeps in the static steps at either strength, so the factor is where that creep "
         "crosses decay, not a limit state: check it with `nmm run` at the reduced strengths "
         "(kind = \"dynamic\"), with more [fos] steps, or with a longer [fos] time_step "
         "(a static step moves a sliding body a dt^2 / 2: the road cut of examples/18, DDA "
         "blocks, takes 0.05 s)";
}

} // namespace

const char* fos_status_name(FosStatus status) {
  switch (status) {
  case FosStatus::found:
    return "found";
  case FosStatus::fails_at_lower_bound:
    return "fails_at_lower_bound";
  case FosStatus::stable_at_upper_bound:
    return "stable_at_upper_bound";
  }
  return "found";
}

void require_strength(const CaseSpec& spec) {
  if (has_strength(spec.contact) ||
      std::any_of(spec.joints.begin(), spec.joints.end(),
                  [](const JointSpec& j) { return has_strength(j.properties); }))
    return;
  std::string have;
  int line = spec.fos.line;
  if (!spec.joints.empty()) {
    line = spec.joints.front().line;
    have = "[joints." + spec.joints.front().name + "]" +
           (spec.joints.size() > 1 ? " (and every other joint)" : "") +
           (spec.contact_line > 0 ? " and [contact] have" : " and [contact] (absent) have");
  } else if (spec.contact_line > 0) {
    line = spec.contact_line;
    have = "the case has no [joints.NAME] table, and [contact] has";
  } else {
    have = "the case has no [joints.NAME] and no [contact] table, so it has";
  }
  throw InputError(spec.file.string(), line, 0,
                   "nmm fos divides the strength of every joint and of [contact] by a factor, "
                   "but " +
                       have +
                       " none (friction_angle, cohesion and tensile_strength all 0): every "
                       "trial would be the same; give the joint along which the model may "
                       "fail a friction angle or cohesion, e.g. friction_angle = 30.0");
}

FosTrial run_fos_trial(const CaseSpec& base, double factor) {
  CaseSpec spec = base;
  const int steps = base.fos.steps;
  spec.analysis.kind = AnalysisKind::quasi_static;
  spec.analysis.steps = steps;
  spec.analysis.end_time.reset();
  spec.analysis.time_step = trial_time_step(base);
  // A lock at the chatter limit slides at its limit: held beyond it, it stands a block that
  // Coulomb's law at the reduced strength lets slide (a DDA block 0.6 m x 0.4 m on 30 degrees
  // with phi = 40 stood to F = 1.8, limit equilibrium 1.453), and a lock held a little beyond
  // its limit among a hundred blocks at rest would fail a trial without a mechanism (the
  // road cut of examples/18 with the automatic step: 1.04 to 1.14 times the limit, at rest).
  spec.analysis.static_chatter_slides = true;
  CaseAnalysis analysis(std::move(spec), {}, factor);
  if (analysis.stepper().contact() == nullptr)
    throw InputError(base.file.string(), base.fos.line, 0,
                     "nmm fos reduces the strength of contacts, but nothing in the model of " +
                         base.geometry.filename().string() +
                         " can touch (one block, no joint that cuts it): no strength acts; "
                         "cut the material by a [joints.NAME] along which it may fail");
  const Model& model = analysis.model();
  TimeStepper& stepper = analysis.stepper();
  FosTrial trial;
  trial.factor = factor;
  const int window = window_of(steps);
  double first = 0.0;
  double last = 0.0;
  try {
    if (base.analysis.initial_equilibrium)
      analysis.equilibrate();
    BlockTracker tracker(model, step_points(model));
    std::vector<Point2> before_last;
    for (int k = 1; k <= steps; ++k) {
      if (k == steps - window + 1)
        before_last = tracker.displacements();
      const StepReport report = stepper.step(std::numeric_limits<double>::infinity());
      tracker.update(model, report.dt);
      trial.steps = k;
      if (k <= window)
        first += report.max_displacement;
      if (k > steps - window) {
        last += report.max_displacement;
        trial.lock_excess = std::max(trial.lock_excess, report.lock_excess);
      }
    }
    trial.first_displacement = first / window;
    trial.last_displacement = last / window;
    trial.measure = first > 0.0 ? last / first : 0.0;
    trial.failed = trial.last_displacement > base.fos.rest && last > base.fos.decay * first;
    const std::vector<Point2> end = tracker.displacements();
    const double threshold = std::max(base.fos.decay * first, base.fos.rest * window);
    for (std::size_t b = 0; b < end.size(); ++b)
      if ((end[b] - before_last[b]).norm() > threshold)
        trial.moving_blocks.push_back(static_cast<int>(b));
  } catch (const NumericalError& error) {
    // A step that cannot be cut enough: the reduced strengths let the model run away.
    trial.failed = true;
    trial.error = error.what();
  }
  return trial;
}

FosResult find_factor_of_safety(const CaseSpec& spec, const FosOptions& options) {
  require_strength(spec);
  const FosSpec& fos = spec.fos;
  FosResult result;
  const int window = window_of(fos.steps);
  const std::optional<double> dt = trial_time_step(spec);
  const std::string step_text =
      dt ? "time step " + number_text(*dt, 6) + " s" : "the automatic time step of Shi 8.5";
  result.criterion =
      "Shi's static steps (velocities reset every step, " + step_text +
      ", a lock at the chatter limit sliding at its friction limit), " + std::to_string(fos.steps) +
      " a trial: a trial fails when the mean largest step displacement of its last " +
      std::to_string(window) + " steps is above rest = " + number_text(fos.rest, 6) +
      " m and above decay = " + number_text(fos.decay, 6) + " times that of its first " +
      std::to_string(window) + " steps (its motion does not die out), or when a step fails";
  bool has_failed = false;
  const auto run = [&](double factor) {
    result.trials.push_back(run_fos_trial(spec, factor));
    if (options.on_trial)
      options.on_trial(result.trials.back());
    return result.trials.back().failed;
  };
  const auto fail_at = [&](double factor) {
    result.failing = factor;
    has_failed = true;
  };
  // The low end must stand: halved while it fails.
  double low = fos.bracket_low;
  for (int k = 0;; ++k) {
    if (!run(low)) {
      result.stable = low;
      break;
    }
    fail_at(low);
    if (k == fos_bracket_growths) {
      result.status = FosStatus::fails_at_lower_bound;
      result.failing_blocks = failing_blocks(result.trials);
      return result;
    }
    low *= 0.5;
  }
  // The high end must fail: doubled while it stands (not needed when the low end was lowered).
  if (!has_failed) {
    double high = fos.bracket_high;
    for (int k = 0;; ++k) {
      if (run(high)) {
        fail_at(high);
        break;
      }
      result.stable = high;
      if (k == fos_bracket_growths) {
        result.status = FosStatus::stable_at_upper_bound;
        return result;
      }
      high *= 2.0;
    }
  }
  while (result.failing - result.stable > fos.tolerance * result.stable) {
    const double middle = 0.5 * (result.stable + result.failing);
    if (run(middle))
      fail_at(middle);
    else
      result.stable = middle;
  }
  result.status = FosStatus::found;
  result.factor_of_safety = 0.5 * (result.stable + result.failing);
  result.failing_blocks = failing_blocks(result.trials);
  if (std::string warning = separation_warning(result, fos.decay); !warning.empty())
    result.warnings.push_back(std::move(warning));
  return result;
}

std::string fos_json(const CaseSpec& spec, const FosResult& result) {
  const auto factor_or_null = [](double f) { return f > 0.0 ? json_number(f) : "null"; };
  std::string out = "{\n";
  out += "  \"factor_of_safety\": " +
         (result.status == FosStatus::found ? json_number(result.factor_of_safety) : "null") +
         ",\n";
  out += "  \"bracket\": [" + factor_or_null(result.stable) + ", " +
         factor_or_null(result.failing) + "],\n";
  out += "  \"status\": " + json_string(fos_status_name(result.status)) + ",\n";
  out += "  \"criterion\": " + json_string(result.criterion) + ",\n";
  out += "  \"tolerance\": " + json_number(spec.fos.tolerance) + ",\n";
  out += "  \"failing_blocks\": [";
  for (std::size_t k = 0; k < result.failing_blocks.size(); ++k)
    out += (k == 0 ? "" : ", ") + std::to_string(result.failing_blocks[k]);
  out += "],\n  \"warnings\": [";
  for (std::size_t k = 0; k < result.warnings.size(); ++k)
    out += (k == 0 ? "" : ", ") + json_string(result.warnings[k]);
  out += "],\n  \"trials\": [";
  for (std::size_t k = 0; k < result.trials.size(); ++k) {
    const FosTrial& t = result.trials[k];
    out += k == 0 ? "\n" : ",\n";
    out += "    {\"factor\": " + json_number(t.factor) +
           ", \"failed\": " + (t.failed ? "true" : "false") +
           ", \"steps\": " + std::to_string(t.steps) + ", \"measure\": " + json_number(t.measure) +
           ", \"first_displacement\": " + json_number(t.first_displacement) +
           ", \"last_displacement\": " + json_number(t.last_displacement) +
           ", \"lock_excess\": " + json_number(t.lock_excess);
    if (!t.error.empty())
      out += ", \"error\": " + json_string(t.error);
    out += "}";
  }
  out += result.trials.empty() ? "],\n" : "\n  ],\n";
  out += "  \"case\": " + json_string(spec.file.string()) + "\n}\n";
  return out;
}

void write_fos_json(const std::filesystem::path& file,
                    const CaseSpec& spec,
                    const FosResult& result) {
  const std::string text = fos_json(spec, result);
  write_file_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary);
    out << text;
    out.flush();
    return static_cast<bool>(out);
  });
}

std::string fos_result_line(const FosResult& result) {
  switch (result.status) {
  case FosStatus::found:
    return "factor of safety: " + number_text(result.factor_of_safety, 4) + " (stands at " +
           number_text(result.stable, 4) + ", fails at " + number_text(result.failing, 4) + ", " +
           std::to_string(result.trials.size()) + " trials)";
  case FosStatus::fails_at_lower_bound:
    return "factor of safety: not found: the model fails even at F = " +
           number_text(result.failing, 4) + " (its strengths multiplied by " +
           number_text(1.0 / result.failing, 4) +
           "); it fails for another reason than its joints' strength (a body no contact "
           "holds?), or lower [fos] bracket";
  case FosStatus::stable_at_upper_bound:
    return "factor of safety: not found: the model stands even at F = " +
           number_text(result.stable, 4) +
           " (its strengths divided by that): nothing fails along its joints; it may stand "
           "by its geometry alone, or raise [fos] bracket";
  }
  return {};
}

} // namespace nmm
