// SPDX-License-Identifier: MIT
// solver/open_close.hpp — Shi's open-close iteration of one try of a time step (1997,
// section 8.2): the contact springs and friction loads follow the contacts' modes, solve
// after solve, until no contact changes its mode and friction agrees with the normal forces;
// augmented-Lagrange passes and friction coupled to the normal force in the solve.
#pragma once

#include "solver/step_context.hpp"
#include "solver/step_system.hpp"

#include <Eigen/Core>

#include <optional>

namespace nmm {

/// How a try's open-close iteration ended.
struct OpenCloseResult {
  bool converged = false;
  int iterations = 0;        ///< solves, friction solves included (StepReport)
  int factorisations = 0;    ///< refactorisations of the step matrix
  bool had_friction = false; ///< a sliding contact with friction in some iteration
  bool not_finite = false;   ///< a solve gave a step displacement that is not finite
  /// Iterations that changed a contact's mode, counted against @c limit (StepReport).
  int counted = 0;
  int limit = 0;
};

/// Shi's budget of open-close iterations a step (1997, 8.2 and 8.5 [3]: a step small enough
/// converges in less than six), the scene's budget when open_close_max is not given, before
/// it grows with the scene.
inline constexpr int open_close_base = 6;
/// The most open-close iterations of a try when open_close_max is not given.
inline constexpr int open_close_cap = 30;

/// The open-close iterations a try may count before it fails (docs/formulation.md,
/// "Open-close budget"): @p given (open_close_max) when the case gives it; otherwise
/// open_close_base, raised to twice the lesser of @p most_changes, the most contacts that
/// changed mode in one iteration of the try so far, and @p bodies, the bodies of the model,
/// at most open_close_cap. A block system where hundreds of contacts between many bodies
/// change at once (blocks landing, slabs starting to slide) gets the iterations those
/// changes take to settle, while a scene of at most three bodies, however many of its
/// contact points change together, keeps Shi's six: a block's base on an NMM ramp given
/// more iterations settles on too long a slide (docs/formulation.md, "Open-close budget"). Ten
/// times the given or base budget for a
/// @p settling step (the initial equilibrium, a static step that barely moves).
[[nodiscard]] int
open_close_limit(const std::optional<int>& given, int most_changes, int bodies, bool settling);

/// Iterates the try @p tries of @p system to convergence or to the iteration budget
/// (open_close_limit(), StepperOptions::friction_solves_max), with the laps
/// seconds_contact_springs, seconds_assembly (the right side), seconds_analysis,
/// seconds_factorization, seconds_solve and seconds_contact_modes. Without contact: one solve,
/// converged.
/// @p raw: the step displacement of the last solve, or of the converged one the contacts went
/// back to (ContactSystem::back_to_converged()); left as it was when the try's first coupled
/// solve does not converge.
/// @throws NumericalError when the step matrix is singular or a solve fails; a solve whose
///         step displacement is not finite ends the try (OpenCloseResult::not_finite).
OpenCloseResult iterate_open_close(const StepContext& context,
                                   const StepTries& tries,
                                   StepSystemState& state,
                                   StepSystem& system,
                                   StepClock& clock,
                                   Eigen::VectorXd& raw);

} // namespace nmm
