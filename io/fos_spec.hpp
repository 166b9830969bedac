// SPDX-License-Identifier: MIT
// io/fos_spec.hpp — the `[fos]` table of a case file: how `nmm fos` searches the factor of
// safety by strength reduction (docs/case-file.md, "[fos]"; io/fos.hpp does the search).
#pragma once

#include <optional>

namespace nmm {

/// `[fos]`: every key optional. A trial at factor F runs `steps` of Shi's static steps with
/// tan(phi), cohesion and tensile strength of every joint and of [contact] divided by F; it
/// fails when the mean largest step displacement of its last tenth of steps is above `rest`
/// and above `decay` times that of its first tenth (docs/case-file.md, "[fos]").
struct FosSpec {
  /// Static steps per trial, 10..1e6.
  int steps = 100;
  /// The last tenth's step displacement over the first tenth's above which a trial fails,
  /// in (0, 1).
  double decay = 0.1;
  /// Mean largest step displacement (m) at or below which the last tenth counts as at rest,
  /// > 0.
  double rest = 1e-10;
  /// The first bracket [stable, failing] the search starts from, 0 < low < high (grown
  /// down or up by halving or doubling, at most fos_bracket_growths times, when it does not
  /// bracket).
  double bracket_low = 1.0;
  double bracket_high = 2.0;
  /// The bisection stops when (failing - stable) / stable is at most this, in [1e-4, 0.5].
  double tolerance = 0.01;
  /// The trials' time step: when time_step_set, time_step (s; empty: "auto", Shi's automatic
  /// step, 8.5) replaces `[analysis] time_step`; else the case's own is kept.
  bool time_step_set = false;
  std::optional<double> time_step;
  /// Line of `[fos]` in the case file; 0 when it has none.
  int line = 0;
};

/// How many times the search halves the bracket's lower end (or doubles its upper end) when
/// the bracket does not hold the factor of safety, before it reports why not.
inline constexpr int fos_bracket_growths = 6;

} // namespace nmm
