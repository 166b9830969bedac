// SPDX-License-Identifier: MIT
// solver/step_control.hpp — the time step (Shi 1997, section 8.5: from the largest step
// displacement allowed) and the judgement of each try of a step: accepted, tried again with
// friction coupled in the solve, cut (to a third when the open-close iteration does not
// converge or the energy check fails, to the displacement limit when it moved too far), or
// the run stops.
#pragma once

#include "manifold/element.hpp"
#include "solver/open_close.hpp"
#include "solver/step_context.hpp"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace nmm {

/// The energy check's budget, kept through the run.
struct EnergyBudget {
  /// Kinetic energy and the bolts' elastic energy at the first dynamic step plus the work of
  /// the loads in the initial equilibrium (stored in the springs, released later), J: with
  /// load_work, the most kinetic energy the run can have.
  double start_energy = 0.0;
  bool started = false;   ///< start_energy has the first dynamic step's kinetic energy
  double load_work = 0.0; ///< StepReport::load_work
};

/// What a try of a step leaves, the last one's kept.
struct TrySolution {
  Eigen::VectorXd raw;          ///< step displacement of every raw unknown, m
  Eigen::VectorXd new_velocity; ///< of a dynamic step, checked before it is committed
  double work = 0.0;            ///< of the loads in the try, J
  double largest = 0.0;         ///< largest step displacement, m
  double kinetic = 0.0;         ///< kinetic energy of new_velocity (dynamic steps), J
  Eigen::VectorXd external;     ///< StepSystem::external of the accepted try
};

/// A try's judgement: accepted, or to be made again (@p tries changed: cut or coupled).
enum class TryVerdict { accept, again };

/// The kind of a step (StepKind) from the options: @p has_contact, a contact system;
/// @p has_mass, some material has a density.
[[nodiscard]] StepKind make_step_kind(const StepperOptions& options,
                                      bool equilibrium,
                                      bool has_contact,
                                      bool has_mass,
                                      double model_size);

/// The time step of a step ending at most at @p until: fixed, 1 s for a static load step, or
/// Shi's from the largest step displacement allowed (8.5); 0 for the initial equilibrium.
[[nodiscard]] double choose_time_step(const StepContext& context, double until);

/// Judges the open-close iteration: a try that did not converge is tried again with coupled
/// friction (once, when friction took part) or cut to a third; one whose step displacement
/// was not finite is cut to a third.
/// @throws NumericalError when it cannot be cut any more (or is the initial equilibrium).
[[nodiscard]] TryVerdict
judge_iteration(const StepContext& context, const OpenCloseResult& iteration, StepTries& tries);

/// Judges the step displacement against the limit (Shi 8.5): an automatic step that moved
/// further is cut to it; a fixed one is warned of once. Sets @p solution.largest.
[[nodiscard]] TryVerdict
judge_displacement(const StepContext& context, TrySolution& solution, StepTries& tries);

/// The energy check of a dynamic try: its new velocities' kinetic energy (with the try's
/// element masses) may not exceed ten times what the run started with plus the work of the
/// loads; a try beyond it is cut to a third. Sets @p solution's new_velocity and kinetic;
/// adds the initial equilibrium's work to the budget.
/// @throws NumericalError when it cannot be cut any more.
[[nodiscard]] TryVerdict judge_energy(const StepContext& context,
                                      const std::vector<ElementMass>& element_mass,
                                      EnergyBudget& energy,
                                      TrySolution& solution,
                                      StepTries& tries);

/// "the fastest cover (v m/s) is near (x, y)" of @p velocity (raw unknowns), for messages.
[[nodiscard]] std::string fastest_cover_text(const Model& model, const Eigen::VectorXd& velocity);

/// 1/2 v^T M v with the element masses @p element_mass (none: 0), J.
[[nodiscard]] double kinetic_energy(const Model& model,
                                    const std::vector<ElementMass>& element_mass,
                                    const Eigen::VectorXd& velocity);

} // namespace nmm
