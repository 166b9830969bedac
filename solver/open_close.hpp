// SPDX-License-Identifier: MIT
// solver/open_close.hpp — Shi's open-close iteration of one try of a time step (1997,
// section 8.2): the contact springs and friction loads follow the contacts' modes, solve
// after solve, until no contact changes its mode and friction agrees with the normal forces;
// augmented-Lagrange passes and friction coupled to the normal force in the solve.
#pragma once

#include "solver/step_context.hpp"
#include "solver/step_system.hpp"

#include <Eigen/Core>

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

/// Iterates the try @p tries of @p system to convergence or to the iteration budget
/// (StepperOptions::open_close_max, friction_solves_max), with the laps seconds_contact_springs,
/// seconds_assembly (the right side), seconds_analysis, seconds_factorization, seconds_solve
/// and seconds_contact_modes. Without contact: one solve, converged.
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
