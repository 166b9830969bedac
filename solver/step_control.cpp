// SPDX-License-Identifier: MIT
#include "solver/step_control.hpp"

#include "manifold/bolt.hpp"
#include "manifold/boundary_conditions.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Why a dynamic step is refused by the energy check, naming the fastest cover.
std::string energy_message(
    const Model& model, const Eigen::VectorXd& velocity, long step, double kinetic, double budget) {
  std::ostringstream message;
  message << "step " << step << ": the kinetic energy (" << kinetic
          << " J) exceeds ten times what the run started with plus the work of the loads ("
          << budget << " J), even with the time step cut; " << fastest_cover_text(model, velocity)
          << ": energy is coming from the contact springs there; try a smaller time_step or "
             "max_step_displacement, a smaller penalty, or a larger cover size near that point";
  return message.str();
}

/// The kinetic energy of a motion by the coordinates' rounding in a step of @p dt: every
/// body moving by 8 units in the last place of the largest coordinate, ½ M (2 δ / dt)²
/// (Shi eq. 2.18-2.19: v = 2 d / dt), M the model's mass.
double rounding_kinetic_energy(const Model& model, double dt) {
  double mass = 0.0;
  double largest = 0.0;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ElasticMaterial& material = model.material_of(e);
    mass += material.density * material.thickness_factor() * model.elements[at(e)].area;
  }
  for (const ModelCover& c : model.covers)
    largest = std::max(largest, c.position.cwiseAbs().maxCoeff());
  const double speed = 2.0 * 8.0 * std::numeric_limits<double>::epsilon() * largest / dt;
  return 0.5 * mass * speed * speed;
}

/// Shi 8.5: G dt² + V dt - D = 0 with G the largest load per mass, V the largest velocity,
/// D the allowed step displacement. A static analysis with contact keeps the inertia term
/// and starts every step at rest: V = 0, dt = sqrt(D / G) (a 1 s step let a free block fall
/// 4.9 m in one iteration).
double inertial_time_step(const StepContext& context) {
  const Model& model = context.model;
  const Scene& scene = context.scene;
  double g = 0.0;
  for (const BodyLoad& load : scene.body_loads)
    g = std::max(g, load.acceleration.norm() * load.ramp.at(context.time));
  double mass = 0.0;
  for (int e = 0; e < model.n_elements(); ++e)
    mass += model.material_of(e).density * model.elements[at(e)].area *
            model.material_of(e).thickness_factor();
  for (const PointLoad& load : scene.point_loads)
    g = std::max(g, load.force.norm() / std::max(mass, 1e-300));
  double v = 0.0; // static: every step starts at rest
  for (int c = 0; c < model.n_covers() && context.kind.dynamic; ++c)
    v = std::max(
        v, Point2(context.velocity(model.dof(c, 0)), context.velocity(model.dof(c, 1))).norm());
  const double limit = context.kind.limit;
  if (g > 0.0)
    return (-v + std::sqrt(v * v + 4.0 * g * limit)) / (2.0 * g);
  if (v > 0.0)
    return limit / v;
  return std::sqrt(2.0 * limit / 9.81);
}

/// Cuts the step to the time step @p dt, counting the cut under @p reason (one of
/// StepTries' cuts_*), or returns false when it was cut max_step_cuts times already.
bool cut(const StepContext& context, StepTries& tries, double dt, int StepTries::*reason) {
  if (tries.cuts >= context.options.max_step_cuts)
    return false;
  tries.dt = dt;
  ++tries.cuts;
  ++(tries.*reason);
  ++context.counters.step_cuts;
  return true;
}

} // namespace

std::string fastest_cover_text(const Model& model, const Eigen::VectorXd& velocity) {
  int fastest = 0;
  double speed = 0.0;
  for (int c = 0; c < model.n_covers(); ++c) {
    const double v = Point2(velocity(model.dof(c, 0)), velocity(model.dof(c, 1))).norm();
    if (v > speed) {
      speed = v;
      fastest = c;
    }
  }
  std::ostringstream text;
  text << "the fastest cover (" << speed << " m/s) is near "
       << point_text(model.covers[at(fastest)].position, 6);
  return text.str();
}

StepKind make_step_kind(const StepperOptions& options,
                        bool equilibrium,
                        bool has_contact,
                        bool has_mass,
                        double model_size) {
  StepKind kind;
  kind.equilibrium = equilibrium;
  kind.dynamic = options.integration == TimeIntegration::dynamic && !equilibrium;
  // Static analysis without contact: one solve with the stiffness alone per step; with
  // contact, Shi's static keeps the inertia term and resets the velocity every step. The
  // initial equilibrium is a solve with the stiffness alone, at the current time.
  kind.with_mass = !equilibrium && (kind.dynamic || has_contact);
  // A static step with contact moves as far as its inertia term lets it: with mass, it is
  // sized and cut like a dynamic one (Shi 8.5); without (no density given), the inertia
  // term is nil and the step is a load step.
  kind.inertial = kind.with_mass && (kind.dynamic || has_mass);
  kind.limit = options.max_step_displacement * model_size;
  return kind;
}

double choose_time_step(const StepContext& context, double until) {
  double dt = 0.0;
  if (context.options.time_step)
    dt = *context.options.time_step;
  else if (!context.kind.inertial)
    dt = 1.0; // a static load step: one solve with the stiffness alone
  else
    dt = inertial_time_step(context);
  return context.kind.equilibrium ? 0.0 : std::min(dt, std::max(until - context.time, 1e-300));
}

TryVerdict
judge_iteration(const StepContext& context, const OpenCloseResult& iteration, StepTries& tries) {
  if (iteration.converged)
    return TryVerdict::accept;
  const StepperOptions& options = context.options;
  const bool equilibrium = context.kind.equilibrium;
  if (iteration.not_finite) {
    // A shorter step is a better-conditioned system (the mass term grows as 1/dt²).
    if (!equilibrium && cut(context, tries, tries.dt / 3.0, &StepTries::cuts_not_finite))
      return TryVerdict::again;
    if (equilibrium) // (TimeStepper::equilibrate() says where)
      throw NumericalError("the step displacement is not finite");
    throw NumericalError("step " + std::to_string(context.step) +
                         ": the step displacement is not finite even with a time step cut " +
                         std::to_string(options.max_step_cuts) +
                         " times; check the penalty, the supports and the time step");
  }
  if (!tries.coupled && iteration.had_friction && !equilibrium && options.coupled_friction) {
    // Friction as loads from the normal forces of the last iteration can keep the iteration
    // from converging where the contact springs are much stiffer than the bodies (the
    // pairs along a sliding block's base opening and closing in turn, iteration after
    // iteration): the step is tried again with friction coupled to the normal force in the
    // solve, before it is cut (docs/formulation.md, "Coupled friction").
    tries.coupled = true;
    ++context.counters.coupled_friction_tries;
    return TryVerdict::again;
  }
  // Shi 8.2: not converged within the allowed iterations: the step is cut to a third.
  if (!equilibrium && cut(context, tries, tries.dt / 3.0, &StepTries::cuts_open_close))
    return TryVerdict::again;
  const std::string where =
      equilibrium ? "the open-close iteration does not converge in " +
                        std::to_string(iteration.factorisations) + " iterations"
                  : "step " + std::to_string(context.step) +
                        ": the open-close iteration does not converge even with a time "
                        "step cut " +
                        std::to_string(options.max_step_cuts) + " times";
  throw NumericalError(where + "; the contacts keep changing mode (e.g. " +
                       context.contact->describe(context.contact->last_changed()) +
                       "); check the penalty and the time step");
}

TryVerdict judge_displacement(const StepContext& context, TrySolution& solution, StepTries& tries) {
  const double limit = context.kind.limit;
  const double largest = context.model.largest_displacement(solution.raw);
  solution.largest = largest;
  // The initial equilibrium is of small deformations: a solve that moves a point farther
  // than the model's size found a body held by nothing but a near-mechanism (its springs
  // lifted off to a corner), not an equilibrium.
  if (context.kind.equilibrium && !(largest <= context.model_size)) {
    std::ostringstream w;
    w << "a solve moves a point by " << largest << " m, more than the model's size ("
      << context.model_size << " m)";
    throw NumericalError(w.str());
  }
  // Dynamic steps, and static ones with contact (their inertia term lets free bodies move
  // by g dt² / 2 in a step), are cut to the step displacement limit (Shi 8.5).
  if (!(largest > limit && context.kind.inertial))
    return TryVerdict::accept;
  const bool fixed = context.options.time_step.has_value();
  if (!fixed && cut(context, tries, tries.dt * std::max(0.1, 0.9 * limit / largest),
                    &StepTries::cuts_displacement))
    return TryVerdict::again;
  if (fixed && context.warnings.empty()) {
    std::ostringstream w;
    w << "step " << context.step << " moved " << largest << " m, more than max_step_displacement ("
      << limit << " m): the fixed time step is too large for Shi's small-step "
      << "assumption; consider time_step = \"auto\"";
    context.warnings.push_back(w.str());
  }
  return TryVerdict::accept;
}

TryVerdict judge_energy(const StepContext& context,
                        const std::vector<ElementMass>& element_mass,
                        EnergyBudget& energy,
                        TrySolution& solution,
                        StepTries& tries) {
  if (!context.kind.dynamic) {
    if (context.kind.equilibrium)
      energy.start_energy += solution.work;
    return TryVerdict::accept;
  }
  // Energy check: the kinetic energy can never exceed what the run started with plus the
  // work the loads have done (initial stresses included: their release is that work);
  // elastic and contact springs only store it, friction only dissipates it. A step that
  // ends above ten times that budget gained energy from nowhere (contact springs pushed
  // through a penetration they never had): it is cut, and the run stops if cutting
  // cannot cure it, rather than carry on with a meaningless answer.
  const Model& model = context.model;
  if (!energy.started) {
    // (with what the bolts' pretension stores)
    energy.start_energy +=
        kinetic_energy(model, element_mass, context.velocity) + elastic_energy(context.scene.bolts);
    energy.started = true;
  }
  // Shi eq. 2.18-2.19: v1 = 2 d / dt - v0.
  solution.new_velocity = (2.0 / tries.dt) * solution.raw - context.velocity;
  const double kinetic = kinetic_energy(model, element_mass, solution.new_velocity);
  const double budget = std::max(energy.start_energy + energy.load_work + solution.work, 0.0);
  // A body at rest in exact equilibrium (a rock mass under its [in_situ] stress and gravity,
  // its joints' springs pre-loaded) moves by the rounding only, and the loads' work on that
  // motion has either sign: the budget is then 0 or less, and such a motion (1e-14 m/s, 8e-23
  // J in a 10 m box of DDA blocks) is no energy gained. So the check starts above the kinetic
  // energy of a motion by the coordinates' rounding (at 10 m and 1 ms, 3e-16 J for 250 t).
  if (kinetic > 10.0 * budget + std::numeric_limits<double>::min() &&
      kinetic > rounding_kinetic_energy(model, tries.dt)) {
    if (cut(context, tries, tries.dt / 3.0, &StepTries::cuts_energy))
      return TryVerdict::again;
    throw NumericalError(
        energy_message(model, solution.new_velocity, context.step, kinetic, budget));
  }
  solution.kinetic = kinetic; // with the step's element masses
  return TryVerdict::accept;
}

double kinetic_energy(const Model& model,
                      const std::vector<ElementMass>& element_mass,
                      const Eigen::VectorXd& velocity) {
  if (element_mass.empty())
    return 0.0;
  double kinetic = 0.0;
  Eigen::VectorXd values;
  for (int e = 0; e < model.n_elements(); ++e) {
    model.element_values(e, velocity, values);
    kinetic += element_mass[at(e)].energy(values);
  }
  return kinetic;
}

} // namespace nmm
