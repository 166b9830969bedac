// SPDX-License-Identifier: MIT
// contact/lift_off.hpp — where the springs of an edge-to-edge contact end: the lift-off
// point's search (docs/formulation.md, "Lift-off").
#pragma once

namespace nmm {

/// A part [from, to] of an edge-to-edge overlap (slave parameters u), or none.
struct OverlapPart {
  bool found = false;
  double from = 0.0;
  double to = 0.0;
};

/// One end of the part of an edge-to-edge overlap that has springs, as the lift-off
/// iteration moves it (docs/formulation.md, "Lift-off"). Where the springs should end is
/// a root of wanted(x) - x, wanted(x) being where the edges stop pressing when the springs
/// end at x: more springs, less pressed. A search finds it by false position (Illinois)
/// between the two last places, one on each side.
struct LiftOffEnd {
  double moved = 0.0;     ///< the last move (its sign: which way the end went)
  bool bracketed = false; ///< the root lies between a and b
  double a = 0.0;         ///< a place of the end, and wanted - a there
  double ga = 0.0;
  double b = 0.0; ///< another, with wanted - b of the other sign
  double gb = 0.0;
  int kept = 0; ///< the bracket end the last search step kept (+1: b, -1: a)
  /// The next place of a searching end now at @p now whose edges stop pressing at
  /// @p wanted: @p wanted until a move goes back, then false position in the bracket of the
  /// last two places; a bracket narrower than @p negligible no longer holds the root (the
  /// pair's motion changed under it), and the end goes to @p wanted again.
  [[nodiscard]] double next(double now, double wanted, double negligible);
};

} // namespace nmm
