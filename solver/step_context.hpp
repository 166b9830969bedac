// SPDX-License-Identifier: MIT
// solver/step_context.hpp — what the parts of one time step share (time_stepper.cpp,
// step_control, step_system, open_close, geometry_update): the kind of step, the stepper's
// inputs for it, the state of its tries, and the clock whose laps are StepperCounters'
// seconds_*.
#pragma once

#include "contact/contact_system.hpp"
#include "manifold/model.hpp"
#include "solver/linear_solver.hpp"
#include "solver/time_stepper.hpp"

#include <Eigen/Core>

#include <chrono>
#include <string>
#include <vector>

namespace nmm {

/// What kind of step is being made, fixed for all its tries.
struct StepKind {
  bool equilibrium = false; ///< the initial equilibrium (TimeStepper::equilibrate())
  bool dynamic = false;     ///< velocity carried over (not static, not the equilibrium)
  /// The inertia term 2M/dt² is assembled: a dynamic step, or a static one with contact
  /// (Shi's static keeps it and resets the velocity every step).
  bool with_mass = false;
  /// The step moves as far as its inertia term lets it: sized and cut to the step
  /// displacement limit (Shi 8.5); false for a static load step.
  bool inertial = false;
  double limit = 0.0; ///< largest allowed step displacement, m (Shi's g2 times the size)
};

/// The tries of one step: the time step, cut on every failed try (step control), and how
/// friction is solved.
struct StepTries {
  double dt = 0.0; ///< of the current try, s
  /// This try couples friction to the normal force in the solve (docs/formulation.md,
  /// "Coupled friction"): a step whose open-close iteration does not converge with friction
  /// as loads from the last iteration is tried again that way before it is cut.
  bool coupled = false;
  int cuts = 0; ///< times the step was cut (StepReport::step_cuts)
  /// The cuts by reason (StepReport::cuts_open_close ...).
  int cuts_open_close = 0;
  int cuts_displacement = 0;
  int cuts_energy = 0;
  int cuts_not_finite = 0;
};

/// The stepper's inputs and outputs for one step, shared by its parts. The references are
/// to TimeStepper's members; they live as long as the step.
struct StepContext {
  Model& model;
  const Scene& scene;
  const StepperOptions& options;
  StepKind kind;
  ContactSystem* contact; ///< null when nothing can touch
  LinearSolver& solver;
  StepperCounters& counters;
  std::vector<std::string>& warnings;
  long step = 0;                       ///< the step being made, 1-based
  double time = 0.0;                   ///< at the start of the step, s
  double model_size = 1.0;             ///< m (TimeStepper::model_size())
  const Eigen::VectorXd& velocity;     ///< raw velocity at the start of the step
  const Eigen::VectorXd& acceleration; ///< of the last step (zero after a static one)
};

/// One clock lapping through a step: every part's time is the time since the last lap, so
/// the parts add up to the whole (StepperCounters).
class StepClock {
public:
  using Clock = std::chrono::steady_clock;
  /// Adds the time since the last lap to @p total.
  void lap(double& total) {
    const Clock::time_point now = Clock::now();
    total += std::chrono::duration<double>(now - last_).count();
    last_ = now;
  }
  /// Seconds since the clock started, up to the last lap.
  [[nodiscard]] double elapsed() const {
    return std::chrono::duration<double>(last_ - start_).count();
  }

private:
  Clock::time_point start_ = Clock::now();
  Clock::time_point last_ = start_;
};

} // namespace nmm
