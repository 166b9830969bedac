// SPDX-License-Identifier: MIT
// manifold/bolt.hpp — rock bolts: axial bars between material points, elastic, then
// yielding with an optional linear hardening, broken at a rupture force (docs/formulation.md,
// "Rock bolts"). An end-anchored bolt is
// one bar between its two anchors; a grouted bolt is a chain of bars through every element
// it crosses, so that the grout couples each of them.
#pragma once

#include "manifold/model.hpp"

#include <Eigen/Core>

#include <limits>
#include <span>
#include <string>
#include <vector>

namespace nmm {

/// `[[bolt]] kind`.
enum class BoltKind {
  end_anchored, ///< one bar from `from` to `to`, free between its anchors
  grouted       ///< bars between the mid-points of its chords through each element it crosses
};

/// What a bar of a bolt does.
enum class BoltState {
  elastic,  ///< force = pretension + stiffness x elongation, within the yield force
  yielding, ///< past its yield force, stretching (or shortening) plastically
  ruptured  ///< broken: no force, no stiffness
};

/// The Int32 and text of a state in the boundary .vtp and summary.json: 0 elastic,
/// 1 yielding, 2 ruptured.
[[nodiscard]] const char* bolt_state_name(BoltState state);

/// One bar of a bolt between two material points (of one element or of two).
struct BoltBar {
  MaterialPoint a;
  MaterialPoint b;
  /// Axial stiffness, N/m (per metre of thickness in plane strain): EA over the bar's
  /// length at installation.
  double stiffness = 0.0;
  /// Axial force at the end of the last step, N, tension positive.
  double force = 0.0;
  /// |force| at which it yields (next): the bolt's yield force, raised by hardening.
  double yield_force = std::numeric_limits<double>::infinity();
  BoltState state = BoltState::elastic;

  /// N^2 / (2k), J (per metre in plane strain).
  [[nodiscard]] double elastic_energy() const { return force * force / (2.0 * stiffness); }
};

/// A bolt: its bars and strength. Forces and stiffnesses are per metre of thickness in plane
/// strain (a bolt's own over its spacing out of the plane).
struct Bolt {
  std::string name;
  BoltKind kind = BoltKind::end_anchored;
  std::vector<BoltBar> bars;
  /// |force| at which a bar breaks, N; infinity: never.
  double rupture_force = std::numeric_limits<double>::infinity();
  /// Stiffness of a yielding bar over its elastic stiffness, in [0, 1): 0 is perfectly
  /// plastic (a bar yielding below its rupture force then never breaks).
  double hardening = 0.0;

  /// The largest |force| of its bars (its force in history.csv), N, with its sign.
  [[nodiscard]] double force() const;
  /// The state of the bar of largest |force|; ruptured when every bar is.
  [[nodiscard]] BoltState state() const;
};

/// The bars of a bolt from @p from to @p to through the model's elements, each with
/// stiffness @p axial_rigidity / length (EA, N), force @p pretension and yield force
/// @p yield_force: one bar for an
/// end-anchored bolt; for a grouted one a bar between the mid-points of consecutive chords
/// of the segment through the elements (the first from @p from, the last to @p to).
/// Returns no bar when an end lies outside the material.
[[nodiscard]] std::vector<BoltBar> make_bolt_bars(const Model& model,
                                                  BoltKind kind,
                                                  const Point2& from,
                                                  const Point2& to,
                                                  double axial_rigidity,
                                                  double pretension,
                                                  double yield_force,
                                                  double tolerance);

/// Appends the raw unknowns a bar couples: its first element's, then those of its second
/// that the first does not have (neighbouring NMM elements share covers).
void append_bar_dofs(const Model& model, const BoltBar& bar, std::vector<int>& dofs);

/// A bar's contribution to a step on its unknowns @p dofs (append_bar_dofs()): stiffness k b b^T
/// (hardening x k while yielding, zero when ruptured) and load -N b, with b^T d the bar's
/// elongation along its current direction and N its force at the start of the step (Shi's step
/// equilibrium with the bar's force carried like an element's initial stress).
void bar_spring(const Model& model,
                const Bolt& bolt,
                const BoltBar& bar,
                std::span<const int> dofs,
                Eigen::MatrixXd& stiffness,
                Eigen::VectorXd& load);

/// What the bars did in a step, J (per metre in plane strain).
struct BoltWork {
  double elastic_change = 0.0; ///< change of the bars' elastic energy N^2 / (2k)
  double dissipated = 0.0;     ///< plastic work, and the elastic energy of bars that broke
  /// k_t d^2 / 2 with the tangent stiffness of the step's solve: what the inertia term's
  /// step (the equilibrium at its end) dissipates, as it does d K d / 2 of the elements.
  double quadratic = 0.0;
};

/// The bars' elastic energy, sum of N^2 / (2k), J (per metre in plane strain): what a
/// pretension stores for the steps to release.
[[nodiscard]] double elastic_energy(std::span<const Bolt> bolts);

/// Advances every bar by the step displacement @p raw (before the geometry moves): its
/// elongation along its direction at the start of the step, elastic, then along the
/// hardening line from where it passes its yield force, broken where it reaches the rupture
/// force, elastic again where a yielding bar unloads.
BoltWork advance_bolts(const Model& model, std::span<Bolt> bolts, const Eigen::VectorXd& raw);

} // namespace nmm
