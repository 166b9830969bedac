// SPDX-License-Identifier: MIT
// solver/energy_balance.hpp — the run's energy balance, step by step: the work of the loads,
// the elements' strain energy, the contacts' spring energy and what friction and the time
// integration dissipate (docs/formulation.md, "Energy balance").
#pragma once

#include "mesh/state_archive.hpp"
#include "solver/step_context.hpp"
#include "solver/step_system.hpp"
#include "solver/time_stepper.hpp"

#include <Eigen/Core>

namespace nmm {

class ContactSystem;

/// The terms of the balance kept through the run, J (per metre in plane strain).
struct EnergyLedger {
  bool started = false;           ///< the first time step was accounted
  bool after_equilibrium = false; ///< an initial equilibrium came before the first step
  double initial = 0.0;           ///< kinetic + contact energy at the start of the first step
  double external_work = 0.0;     ///< StepReport::external_work
  double strain_energy = 0.0;     ///< StepReport::strain_energy
  double dissipated = 0.0;        ///< StepReport::dissipated_energy
  double contact_energy = 0.0;    ///< at the end of the last step (or equilibrium)
  /// External loads of the last step (a static step without inertia applies its loads
  /// quasi-statically: the trapezoidal rule between the last step's loads and its own).
  Eigen::VectorXd last_external;
  bool warned = false; ///< the energy_tolerance warning was given

  void save_state(StateWriter& out) const;
  void load_state(StateReader& in);
};

/// The step just accepted, of time step @p dt, displacement @p raw, external loads
/// @p external (StepSystem::external), new kinetic energy @p kinetic and what the bolts'
/// bars did (@p bolts, advance_bolts(): their elastic energy counts as strain energy), into
/// @p ledger and @p report's energy fields. @p state: the step system's element masses (the
/// element matrices are integrated again for the strain energy). Call before the contacts'
/// end_step() and before the stresses and geometry move. The initial equilibrium only
/// records its spring energy.
void account_energy(const StepContext& context,
                    const StepSystemState& state,
                    const Eigen::VectorXd& external,
                    const Eigen::VectorXd& raw,
                    double dt,
                    double kinetic,
                    const BoltWork& bolts,
                    EnergyLedger& ledger,
                    StepReport& report);

/// The balance of a dynamic step just accounted against the options' energy_tolerance (a warning
/// into the context's warnings, the first time: @p warned) and energy_error_limit
/// (@throws NumericalError). @p velocity: the step's new velocities (raw unknowns), to name
/// where the energy went. A static load step (no inertia term) whose solve moved a point by
/// @p largest, more than the model's size, with a balance that misses by more than 0.1 is a
/// mechanism (@throws NumericalError).
void judge_balance(const StepContext& context,
                   const StepReport& report,
                   const Eigen::VectorXd& velocity,
                   double largest,
                   bool& warned);

} // namespace nmm
