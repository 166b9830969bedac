// SPDX-License-Identifier: MIT
// io/fos.hpp — the factor of safety by strength reduction (`nmm fos`, docs/output.md
// "fos.json"): the case's own model is run in trials, each with tan(phi), cohesion and
// tensile strength of every joint and of [contact] divided by a factor F
// (reduced_strength(), contact/joint_law.hpp); a bisection on F finds where the model passes
// from standing to failing, by the criterion of the case's `[fos]` table (io/fos_spec.hpp).
#pragma once

#include "io/case_file.hpp"

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace nmm {

/// One trial: the case's model with its strengths divided by @p factor, run for `[fos]
/// steps` of Shi's static steps.
struct FosTrial {
  double factor = 1.0;
  /// By the criterion (FosSpec: still moving at the end), or because a step failed (error).
  bool failed = false;
  /// Static steps run.
  long steps = 0;
  /// Mean largest step displacement of the first and the last tenth of the steps, m.
  double first_displacement = 0.0;
  double last_displacement = 0.0;
  /// last_displacement / first_displacement (0 when the first tenth did not move at all).
  double measure = 0.0;
  /// The largest StepReport::lock_excess of the last tenth of the steps: a contact held
  /// locked beyond its friction limit by the chatter rule (shear over limit; 0: none). A
  /// trial lets such locks slide at their limit (StepperOptions::static_chatter_slides), so
  /// it is 0; fos.json keeps the field.
  double lock_excess = 0.0;
  /// Blocks (Model::blocks ids) whose centroid moved over the last tenth of the steps more
  /// than `decay` times the sum of the first tenth's largest step displacements, and more than
  /// `rest` per step: the blocks that keep moving.
  std::vector<int> moving_blocks;
  /// A step that failed (NumericalError): its message; the trial counts as failed.
  std::string error;
};

/// How the search ended.
enum class FosStatus {
  found,                 ///< a bracket [stable, failing] no wider than the tolerance
  fails_at_lower_bound,  ///< the model fails even with its strengths multiplied by 1/low
  stable_at_upper_bound, ///< the model stands even with its strengths divided by high
};

/// "found", "fails_at_lower_bound", "stable_at_upper_bound" (fos.json's `status`).
[[nodiscard]] const char* fos_status_name(FosStatus status);

/// What the search found.
struct FosResult {
  FosStatus status = FosStatus::found;
  /// The middle of the final bracket (found only), within tolerance / 2 of both ends.
  double factor_of_safety = 0.0;
  /// The largest factor a trial stood at and the smallest one it failed at; 0 when none.
  double stable = 0.0;
  double failing = 0.0;
  /// moving_blocks of the failing trial of smallest factor in which blocks kept moving (the
  /// mechanism nearest the limit; a trial that failed by a step that could not be cut enough
  /// may have none).
  std::vector<int> failing_blocks;
  /// Every trial, in the order run.
  std::vector<FosTrial> trials;
  /// What a trial's failure means, in words (fos.json's `criterion`).
  std::string criterion;
  /// What the user must know about the result (fos.json's `warnings`): a bracket whose
  /// standing and failing trials the criterion hardly tells apart (separation_warning()).
  std::vector<std::string> warnings;
};

/// What find_factor_of_safety() reports as it goes; may be empty.
struct FosOptions {
  std::function<void(const FosTrial&)> on_trial;
};

/// Refuses a case with no strength to reduce: every `[joints.NAME]` and `[contact]` without
/// friction angle, cohesion and tensile strength.
/// @throws InputError "case.toml:LINE: ..." naming the table (the first joint's line, else
///         [contact]'s, else [fos]'s) and what to give.
void require_strength(const CaseSpec& spec);

/// Runs one trial of @p spec at @p factor (its `[analysis]` turned into `[fos] steps` static
/// steps, without end_time; `initial_equilibrium` as the case says). Writes no file.
/// @throws InputError as CaseAnalysis does, and when nothing in the model can touch (no
///         contact, so no strength acts).
[[nodiscard]] FosTrial run_fos_trial(const CaseSpec& spec, double factor);

/// The search: a trial at `[fos] bracket`'s low end, which must stand (else it is halved,
/// at most fos_bracket_growths times), one at its high end, which must fail (else doubled as
/// often), then bisection until (failing - stable) / stable <= `[fos] tolerance`.
/// @throws InputError as require_strength() and run_fos_trial().
[[nodiscard]] FosResult find_factor_of_safety(const CaseSpec& spec, const FosOptions& options = {});

/// fos.json's text (docs/output.md, "fos.json"), two-space indented, one key a line.
[[nodiscard]] std::string fos_json(const CaseSpec& spec, const FosResult& result);

/// Writes fos_json() to @p file atomically.
/// @throws InputError / OutputWriteError naming the file when it cannot be written.
void write_fos_json(const std::filesystem::path& file,
                    const CaseSpec& spec,
                    const FosResult& result);

/// The line `nmm fos` prints: "factor of safety: 1.074 (stable at 1.07, fails at 1.078)", or
/// "factor of safety: not found: ..." saying why.
[[nodiscard]] std::string fos_result_line(const FosResult& result);

} // namespace nmm
