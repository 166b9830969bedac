// SPDX-License-Identifier: MIT
#include "solver/time_stepper.hpp"

#include "contact/contact_system.hpp"
#include "manifold/simplex_integration.hpp"
#include "mesh/error.hpp"
#include "solver/assembler.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/low_rank_solve.hpp"
#include "solver/open_close.hpp"
#include "solver/sparsity.hpp"
#include "solver/step_context.hpp"
#include "solver/step_system.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <span>
#include <sstream>
#include <string_view>
#include <utility>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Why a dynamic step is refused by the energy check, naming the fastest cover.
std::string energy_message(
    const Model& model, const Eigen::VectorXd& velocity, long step, double kinetic, double budget) {
  int fastest = 0;
  double speed = 0.0;
  for (int c = 0; c < model.n_covers(); ++c) {
    const double v = Point2(velocity(model.dof(c, 0)), velocity(model.dof(c, 1))).norm();
    if (v > speed) {
      speed = v;
      fastest = c;
    }
  }
  std::ostringstream message;
  message << "step " << step << ": the kinetic energy (" << kinetic
          << " J) exceeds ten times what the run started with plus the work of the loads ("
          << budget << " J), even with the time step cut; the fastest cover (" << speed
          << " m/s) is near " << point_text(model.covers[at(fastest)].position, 6)
          << ": energy is coming from the contact springs there; try a smaller time_step or "
             "max_step_displacement, a smaller penalty, or a larger cover size near that point";
  return message.str();
}

} // namespace

struct TimeStepper::Impl {
  std::unique_ptr<ContactSystem> contact; // null when nothing can touch
  std::unique_ptr<LinearSolver> solver;
  Eigen::VectorXd acceleration; ///< (v1 - v0) / dt of the last step; zero after a static one
  StepSystemState system;       ///< what the step systems keep from step to step
  /// Kinetic energy at the first dynamic step plus the work of the loads in the initial
  /// equilibrium (stored in the springs, released later), J: with load_work, the most
  /// kinetic energy the run can have (the energy check).
  double start_energy = 0.0;
  bool energy_started = false;
  double load_work = 0.0; ///< StepReport::load_work
  /// Solver counters of the run before a restart.
  SolverCounters restored_counters;
};

TimeStepper::TimeStepper(Model& model,
                         Scene scene,
                         StepperOptions options,
                         std::unique_ptr<ContactSystem> contact)
    : model_(model), scene_(std::move(scene)), options_(options),
      velocity_(Eigen::VectorXd::Zero(model.n_dofs())), impl_(std::make_unique<Impl>()) {
  if (options_.conjugate_gradients)
    impl_->solver = std::make_unique<PcgSolver>(*options_.conjugate_gradients);
  else
    impl_->solver = std::make_unique<CholmodSolver>();
  impl_->acceleration.setZero(model.n_dofs());
  // Skip what the scene does not need: no contact search where nothing can touch.
  if (contact && ContactSystem::can_touch(model_))
    impl_->contact = std::move(contact);
  BoundingBox box;
  for (const ModelElement& e : model_.elements) {
    for (const Polygon& p : e.polygons) {
      for (const Point2& x : p.outer)
        box.extend(x);
    }
  }
  model_size_ = box.is_empty() ? 1.0 : std::max({box.size().x(), box.size().y(), 1e-300});
  // A dynamic run needs mass everywhere; a static one needs every body held.
  std::set<int> used_materials;
  for (const ModelElement& e : model_.elements)
    used_materials.insert(e.material);
  for (const int m : used_materials)
    has_mass_ = has_mass_ || model_.materials[at(m)].density > 0.0;
  if (options_.integration == TimeIntegration::dynamic) {
    for (const int m : used_materials) {
      if (!(model_.materials[at(m)].density > 0.0)) {
        throw InputError("material \"" + model_.materials[at(m)].name +
                         "\" has no density, but a dynamic analysis needs the mass of every "
                         "body: give [materials." +
                         model_.materials[at(m)].name + "] density in kg/m³");
      }
    }
  } else if (!impl_->contact) {
    std::set<int> held;
    for (const SupportPoint& s : scene_.supports) {
      if (s.point.element >= 0)
        held.insert(model_.elements[at(s.point.element)].block);
    }
    for (int e = 0; e < model_.n_elements(); ++e) {
      const ModelElement& element = model_.elements[at(e)];
      if (held.count(element.block) == 0) {
        throw InputError(
            "the body of material \"" + model_.materials[at(element.material)].name +
            "\" containing " + point_text(element.polygons.front().outer.front(), 6) +
            " can move freely: nothing holds it and a static analysis has no inertia to "
            "resist; add a [[boundary]] support on it, or use [analysis] kind = \"dynamic\"");
      }
    }
  }
  impl_->system.dependencies = model_.dependency_relations();
}

TimeStepper::~TimeStepper() = default;

SolverCounters TimeStepper::solver_counters() const {
  SolverCounters counters = impl_->solver->counters();
  counters.symbolic_analyses += impl_->restored_counters.symbolic_analyses;
  counters.factorizations += impl_->restored_counters.factorizations;
  counters.solves += impl_->restored_counters.solves;
  counters.iterations += impl_->restored_counters.iterations;
  counters.fallbacks += impl_->restored_counters.fallbacks;
  return counters;
}

int TimeStepper::n_unknowns() const { return impl_->system.pattern.n_dofs(); }

const SparseMatrix& TimeStepper::last_matrix() const { return impl_->system.stiffness->matrix(); }

double TimeStepper::contact_penetration() const {
  return impl_->contact ? impl_->contact->max_penetration() : 0.0;
}

const ContactSystem* TimeStepper::contact() const { return impl_->contact.get(); }

void TimeStepper::set_rigid_velocities(const std::vector<Point2>& block_velocity,
                                       const std::vector<double>& block_angular_velocity) {
  // Centre of each block: its centroid, from the first moments of its elements about the
  // block's first vertex (accurate far from 0).
  std::vector<Moments2> moments(model_.blocks.size());
  for (const ModelElement& e : model_.elements) {
    Moments2& m = moments[at(e.block)];
    for (const Polygon& p : e.polygons) {
      if (m.degree() < 0)
        m = Moments2(1, p.outer.front());
      m += polygon_moments(p, 1, m.origin());
    }
  }
  std::vector<Point2> centre(model_.blocks.size(), Point2::Zero());
  for (std::size_t b = 0; b < centre.size(); ++b) {
    if (moments[b].degree() >= 0 && moments[b].area() > 0.0)
      centre[b] = moments[b].centroid();
  }
  velocity_.setZero();
  for (int c = 0; c < model_.n_covers(); ++c) {
    const int b = model_.covers[at(c)].block;
    model_.set_rigid_motion(c, block_velocity[at(b)], block_angular_velocity[at(b)], centre[at(b)],
                            velocity_);
  }
}

Point2 TimeStepper::velocity_at(int element, const Point2& x) const {
  return model_.displacement(element, x, velocity_);
}

StepReport TimeStepper::step(double until) { return advance(until, false); }

StepReport TimeStepper::equilibrate() {
  try {
    return advance(time_, true);
  } catch (const NumericalError& e) {
    throw NumericalError(std::string("initial equilibrium: ") + e.what() +
                         " (the initial equilibrium needs every body held by supports or by "
                         "contacts that touch)");
  }
}

double TimeStepper::kinetic_energy(const Eigen::VectorXd& velocity) const {
  if (impl_->system.element_mass.empty())
    return 0.0;
  double kinetic = 0.0;
  Eigen::VectorXd values;
  for (int e = 0; e < model_.n_elements(); ++e) {
    model_.element_values(e, velocity, values);
    kinetic += impl_->system.element_mass[at(e)].energy(values);
  }
  return kinetic;
}

StepReport TimeStepper::advance(double until, bool equilibrium) {
  StepClock clock;
  impl_->solver->start_step();
  const bool dynamic = options_.integration == TimeIntegration::dynamic && !equilibrium;
  // Static analysis without contact: one solve with the stiffness alone per step; with
  // contact, Shi's static keeps the inertia term and resets the velocity every step. The
  // initial equilibrium is a solve with the stiffness alone, at the current time.
  const bool with_mass = !equilibrium && (dynamic || impl_->contact != nullptr);
  // A static step with contact moves as far as its inertia term lets it: with mass, it is
  // sized and cut like a dynamic one (Shi 8.5); without (no density given), the inertia
  // term is nil and the step is a load step.
  const bool inertial = with_mass && (dynamic || has_mass_);
  const double limit = options_.max_step_displacement * model_size_;

  double dt = 0.0;
  if (options_.time_step) {
    dt = *options_.time_step;
  } else if (!inertial) {
    dt = 1.0; // a static load step: one solve with the stiffness alone
  } else {
    // Shi 8.5: G dt² + V dt - D = 0 with G the largest load per mass, V the largest
    // velocity, D the allowed step displacement. A static analysis with contact keeps the
    // inertia term and starts every step at rest: V = 0, dt = sqrt(D / G) (a 1 s step let a
    // free block fall 4.9 m in one iteration).
    double g = 0.0;
    for (const BodyLoad& load : scene_.body_loads)
      g = std::max(g, load.acceleration.norm() * load.ramp.at(time_));
    double mass = 0.0;
    for (int e = 0; e < model_.n_elements(); ++e)
      mass += model_.material_of(e).density * model_.elements[at(e)].area *
              model_.material_of(e).thickness_factor();
    for (const PointLoad& load : scene_.point_loads)
      g = std::max(g, load.force.norm() / std::max(mass, 1e-300));
    double v = 0.0; // static: every step starts at rest
    for (int c = 0; c < model_.n_covers() && dynamic; ++c)
      v = std::max(v, Point2(velocity_(model_.dof(c, 0)), velocity_(model_.dof(c, 1))).norm());
    if (g > 0.0)
      dt = (-v + std::sqrt(v * v + 4.0 * g * limit)) / (2.0 * g);
    else if (v > 0.0)
      dt = limit / v;
    else
      dt = std::sqrt(2.0 * limit / 9.81);
  }
  dt = equilibrium ? 0.0 : std::min(dt, std::max(until - time_, 1e-300));

  StepReport report;
  Eigen::VectorXd raw;
  Eigen::VectorXd new_velocity; // of a dynamic step, checked before it is committed
  // Contacts are found once per step. A cut step starts the open-close iteration again from
  // the contact state at the start of the step (Shi 8.2 continues it from the modes the
  // longer step reached; with edge-to-edge springs that go where the edges press, those
  // include a pressed part and anchors fitted to a motion the shorter step does not have:
  // examples/10 lost its pivot that way). Rules tried: docs/formulation.md, "Friction".
  clock.lap(counters_.seconds_step_control);
  if (impl_->contact) {
    impl_->contact->begin_step(model_, limit);
    impl_->contact->set_hold_shear(equilibrium);
    impl_->contact->set_dynamic(dynamic);
    ++counters_.contact_searches;
  }
  clock.lap(counters_.seconds_detection);
  double work = 0.0; // of the loads in the step (its last try)
  // Whether this try couples friction to the normal force in the solve (docs/formulation.md,
  // "Coupled friction"): a step whose open-close iteration does not converge with friction as
  // loads from the last iteration is tried again that way before it is cut.
  bool coupled = false;
  const StepContext context{.model = model_,
                            .scene = scene_,
                            .options = options_,
                            .kind = {equilibrium, dynamic, with_mass, inertial, limit},
                            .contact = impl_->contact.get(),
                            .solver = *impl_->solver,
                            .counters = counters_,
                            .warnings = warnings_,
                            .step = step_ + 1,
                            .time = time_,
                            .model_size = model_size_,
                            .velocity = velocity_,
                            .acceleration = impl_->acceleration};
  for (int attempt = 0;; ++attempt) {
    const int cut = report.step_cuts;
    clock.lap(counters_.seconds_step_control); // the checks of a try that was cut
    if (attempt > 0 && impl_->contact)
      impl_->contact->restart_step();
    if (impl_->contact)
      impl_->contact->set_coupled_friction(coupled);
    clock.lap(counters_.seconds_detection); // (the contact states back to the step's start)
    StepSystem system = build_step_system(context, impl_->system, dt, clock);
    const Eigen::VectorXd& loads = system.loads;
    const StepTries this_try{.dt = dt, .coupled = coupled, .cuts = cut};
    const OpenCloseResult iteration =
        iterate_open_close(context, this_try, impl_->system, system, clock, raw);
    const bool converged = iteration.converged;
    const int factorisations = iteration.factorisations;
    const bool had_friction = iteration.had_friction;
    report.open_close_iterations = iteration.iterations;
    if (!converged && !coupled && had_friction && !equilibrium && options_.coupled_friction) {
      // Friction as loads from the normal forces of the last iteration can keep the iteration
      // from converging where the contact springs are much stiffer than the bodies (the
      // pairs along a sliding block's base opening and closing in turn, iteration after
      // iteration): the step is tried again with friction coupled to the normal force in the
      // solve, before it is cut (docs/formulation.md, "Coupled friction").
      coupled = true;
      ++counters_.coupled_friction_tries;
      continue;
    }
    if (!converged) {
      // Shi 8.2: not converged within the allowed iterations: the step is cut to a third.
      if (cut < options_.max_step_cuts && !equilibrium) {
        dt /= 3.0;
        ++report.step_cuts;
        ++counters_.step_cuts;
        continue;
      }
      const std::string where =
          equilibrium ? "the open-close iteration does not converge in " +
                            std::to_string(factorisations) + " iterations"
                      : "step " + std::to_string(step_ + 1) +
                            ": the open-close iteration does not converge even with a time "
                            "step cut " +
                            std::to_string(options_.max_step_cuts) + " times";
      throw NumericalError(where + "; the contacts keep changing mode (e.g. " +
                           impl_->contact->describe(impl_->contact->last_changed()) +
                           "); check the penalty and the time step");
    }

    const double largest = model_.largest_displacement(raw);
    report.max_displacement = largest;
    // Dynamic steps, and static ones with contact (their inertia term lets free bodies move
    // by g dt² / 2 in a step), are cut to the step displacement limit (Shi 8.5).
    if (largest > limit && inertial) {
      if (!options_.time_step && cut < options_.max_step_cuts) {
        dt *= std::max(0.1, 0.9 * limit / largest);
        ++report.step_cuts;
        ++counters_.step_cuts;
        continue;
      }
      if (options_.time_step && warnings_.empty()) {
        std::ostringstream w;
        w << "step " << step_ + 1 << " moved " << largest << " m, more than max_step_displacement ("
          << limit << " m): the fixed time step is too large for Shi's small-step "
          << "assumption; consider time_step = \"auto\"";
        warnings_.push_back(w.str());
      }
    }
    work = loads.dot(raw);
    if (dynamic) {
      // Energy check: the kinetic energy can never exceed what the run started with plus the
      // work the loads have done (initial stresses included: their release is that work);
      // elastic and contact springs only store it, friction only dissipates it. A step that
      // ends above ten times that budget gained energy from nowhere (contact springs pushed
      // through a penetration they never had): it is cut, and the run stops if cutting
      // cannot cure it, rather than carry on with a meaningless answer.
      if (!impl_->energy_started) {
        impl_->start_energy += kinetic_energy(velocity_);
        impl_->energy_started = true;
      }
      new_velocity = (2.0 / dt) * raw - velocity_; // Shi eq. 2.18-2.19: v1 = 2 d / dt - v0
      const double kinetic = kinetic_energy(new_velocity);
      const double budget = std::max(impl_->start_energy + impl_->load_work + work, 0.0);
      if (kinetic > 10.0 * budget + std::numeric_limits<double>::min()) {
        if (cut < options_.max_step_cuts) {
          dt /= 3.0;
          ++report.step_cuts;
          ++counters_.step_cuts;
          continue;
        }
        throw NumericalError(energy_message(model_, new_velocity, step_ + 1, kinetic, budget));
      }
      report.kinetic_energy = kinetic; // with the step's element masses
    } else if (equilibrium) {
      impl_->start_energy += work;
    }
    break;
  }
  if (!equilibrium)
    impl_->load_work += work;
  report.load_work = impl_->load_work;
  clock.lap(counters_.seconds_step_control);

  // Commit: velocities (computed and checked above), stresses, geometry.
  if (dynamic) {
    impl_->acceleration = (new_velocity - velocity_) / dt;
    velocity_ = std::move(new_velocity);
  } else {
    velocity_.setZero();
    impl_->acceleration.setZero(velocity_.size());
  }
  if (impl_->contact) {
    // Closed contacts carry over with the kinematics of this step (before the geometry moves).
    impl_->contact->end_step(model_, raw);
    report.contacts = impl_->contact->n_closed();
    report.max_penetration = impl_->contact->max_penetration();
    // Of the solve the step ends on (after augmented-Lagrange passes, the converged one kept).
    const FrictionHolds held = impl_->contact->holds();
    report.lock_excess = held.lock_excess;
    report.slide_feed = held.slide_feed;
    if (held.lock_excess > 0.0) {
      ++counters_.locks_beyond_friction;
      counters_.max_lock_excess = std::max(counters_.max_lock_excess, held.lock_excess);
    }
    if (held.slide_feed > 0.0) {
      ++counters_.slides_against_motion;
      counters_.slide_feed_work += held.slide_feed;
    }
  }
  model_.accumulate_stress(raw);
  ++counters_.stress_updates;
  model_.turn_exactly(raw, velocity_);
  std::vector<MaterialPoint> points;
  for (const SupportPoint& s : scene_.supports)
    points.push_back(s.point);
  for (const PointLoad& l : scene_.point_loads)
    points.push_back(l.point);
  for (const MaterialPoint& p : scene_.monitors)
    points.push_back(p);
  model_.move(raw, points);
  std::size_t k = 0;
  for (SupportPoint& s : scene_.supports)
    s.point = points[k++];
  for (PointLoad& l : scene_.point_loads)
    l.point = points[k++];
  for (MaterialPoint& p : scene_.monitors)
    p = points[k++];

  if (!equilibrium) {
    time_ += dt;
    ++step_;
    ++counters_.steps;
  }
  report.step = step_;
  report.time = time_;
  report.dt = dt;

  clock.lap(counters_.seconds_update);
  counters_.seconds_steps += clock.elapsed();
  return report;
}

namespace {

void save_point(StateWriter& out, const MaterialPoint& point) {
  out.put(static_cast<std::int64_t>(point.element));
  out.put(point.position);
}

void load_point(StateReader& in, MaterialPoint& point, int n_elements) {
  const std::int64_t element = in.integer();
  if (element < -1 || element >= n_elements)
    in.fail("a material point in element " + std::to_string(element) + " of " +
            std::to_string(n_elements));
  point.element = static_cast<int>(element);
  point.position = in.point();
}

std::vector<double*> time_counters(StepperCounters& c) {
  return {&c.seconds_steps,           &c.seconds_step_control,  &c.seconds_detection,
          &c.seconds_constraints,     &c.seconds_pattern,       &c.seconds_assembly,
          &c.seconds_contact_springs, &c.seconds_analysis,      &c.seconds_factorization,
          &c.seconds_solve,           &c.seconds_contact_modes, &c.seconds_update};
}

std::vector<long*> work_counters(StepperCounters& c) {
  return {&c.steps,
          &c.step_cuts,
          &c.contact_searches,
          &c.pattern_builds,
          &c.plan_rebuilds,
          &c.stress_updates,
          &c.friction_terms,
          &c.augmentations,
          &c.locks_beyond_friction,
          &c.slides_against_motion,
          &c.coupled_friction_tries,
          &c.coupled_friction_iterations};
}

} // namespace

void TimeStepper::save_state(StateWriter& out) const {
  model_.save_state(out);
  out.section("STEP");
  out.put(velocity_);
  out.put(time_);
  out.put(static_cast<std::int64_t>(step_));
  StepperCounters counters = counters_;
  for (const long* c : work_counters(counters))
    out.put(static_cast<std::int64_t>(*c));
  for (const double* c : time_counters(counters))
    out.put(*c);
  out.put(counters.max_lock_excess);
  out.put(counters.slide_feed_work);
  const SolverCounters solver = solver_counters();
  out.put(static_cast<std::int64_t>(solver.symbolic_analyses));
  out.put(static_cast<std::int64_t>(solver.factorizations));
  out.put(static_cast<std::int64_t>(solver.solves));
  out.put(static_cast<std::int64_t>(solver.iterations));
  out.put(static_cast<std::int64_t>(solver.fallbacks));
  out.put(impl_->solver->carried());
  out.put_count(warnings_.size());
  for (const std::string& w : warnings_)
    out.put(w);
  out.put_count(scene_.supports.size());
  for (const SupportPoint& s : scene_.supports)
    save_point(out, s.point);
  out.put_count(scene_.point_loads.size());
  for (const PointLoad& l : scene_.point_loads)
    save_point(out, l.point);
  out.put_count(scene_.monitors.size());
  for (const MaterialPoint& p : scene_.monitors)
    save_point(out, p);
  out.put(impl_->start_energy);
  out.put(impl_->energy_started);
  out.put(impl_->load_work);
  out.put(impl_->acceleration);
  // The last step's slaves: the next step's elimination prefers them (DofMap's previous).
  std::vector<int> slaves;
  if (impl_->system.map) {
    for (int raw = 0; raw < impl_->system.map->n_raw(); ++raw) {
      if (impl_->system.map->is_slave(raw))
        slaves.push_back(raw);
    }
  }
  out.put(impl_->system.map != nullptr);
  out.put(slaves);
  out.put(impl_->system.stiffness != nullptr);
  if (impl_->system.stiffness) {
    out.put(static_cast<std::int64_t>(impl_->system.pattern.n_dofs()));
    out.put(impl_->system.pattern_start);
    out.put(impl_->system.pattern_dofs);
    out.put(impl_->system.coupling_start);
    out.put(impl_->system.coupling_dofs);
  }
  out.put(impl_->contact != nullptr);
  if (impl_->contact)
    impl_->contact->save_state(out);
}

void TimeStepper::load_state(StateReader& in) {
  NMM_ASSERT(step_ == 0 && counters_.steps == 0, "a checkpoint is loaded before the first step");
  model_.load_state(in);
  in.section("STEP");
  velocity_ = in.vector();
  if (velocity_.size() != model_.n_dofs())
    in.fail("it has " + std::to_string(velocity_.size()) + " unknowns, the case has " +
            std::to_string(model_.n_dofs()));
  time_ = in.real();
  step_ = static_cast<long>(in.integer());
  for (long* c : work_counters(counters_))
    *c = static_cast<long>(in.integer());
  for (double* c : time_counters(counters_))
    *c = in.real();
  counters_.max_lock_excess = in.real();
  counters_.slide_feed_work = in.real();
  impl_->restored_counters.symbolic_analyses = static_cast<long>(in.integer());
  impl_->restored_counters.factorizations = static_cast<long>(in.integer());
  impl_->restored_counters.solves = static_cast<long>(in.integer());
  impl_->restored_counters.iterations = static_cast<long>(in.integer());
  impl_->restored_counters.fallbacks = static_cast<long>(in.integer());
  const std::vector<int> carried = in.integers();
  if (!impl_->solver->restore_carried(carried))
    in.fail("its linear solver's state (" + std::to_string(carried.size()) +
            " numbers) is not one of " + impl_->solver->name());
  warnings_.resize(in.count());
  for (std::string& w : warnings_)
    w = in.text();
  in.expect_count(scene_.supports.size(), "support points");
  for (SupportPoint& s : scene_.supports)
    load_point(in, s.point, model_.n_elements());
  in.expect_count(scene_.point_loads.size(), "point loads");
  for (PointLoad& l : scene_.point_loads)
    load_point(in, l.point, model_.n_elements());
  in.expect_count(scene_.monitors.size(), "monitors");
  for (MaterialPoint& p : scene_.monitors)
    load_point(in, p, model_.n_elements());
  impl_->start_energy = in.real();
  impl_->energy_started = in.boolean();
  impl_->load_work = in.real();
  impl_->acceleration = in.vector();
  if (impl_->acceleration.size() != model_.n_dofs())
    in.fail("its accelerations have " + std::to_string(impl_->acceleration.size()) +
            " unknowns, the case has " + std::to_string(model_.n_dofs()));
  const bool had_map = in.boolean();
  const std::vector<int> slaves = in.integers();
  impl_->system.map.reset();
  if (had_map) {
    // A map whose only use is to be the next step's "previous": each saved slave is the
    // preferred pivot of a row of its own, so exactly those are slaves.
    std::vector<LinearConstraint> rows;
    rows.reserve(slaves.size());
    for (const int raw : slaves) {
      if (raw < 0 || raw >= model_.n_dofs())
        in.fail("a slave unknown " + std::to_string(raw) + " of " +
                std::to_string(model_.n_dofs()));
      rows.push_back(LinearConstraint{{{raw, 1.0}}, 0.0, raw, "restart"});
    }
    impl_->system.map = std::make_shared<const DofMap>(model_.n_dofs(), rows);
  }
  impl_->system.stiffness.reset();
  impl_->system.analysed = false;
  if (in.boolean()) {
    const std::int64_t n = in.integer();
    impl_->system.pattern_start = in.integers();
    impl_->system.pattern_dofs = in.integers();
    impl_->system.coupling_start = in.integers();
    impl_->system.coupling_dofs = in.integers();
    auto check = [&](const std::vector<int>& starts, const std::vector<int>& dofs) {
      if (starts.empty() || starts.front() != 0 || !std::is_sorted(starts.begin(), starts.end()) ||
          starts.back() != static_cast<int>(dofs.size()))
        in.fail("the couplings of the sparsity pattern are inconsistent");
      for (const int d : dofs) {
        if (d < -1 || d >= n)
          in.fail("the couplings of the sparsity pattern are inconsistent");
      }
    };
    check(impl_->system.pattern_start, impl_->system.pattern_dofs);
    check(impl_->system.coupling_start, impl_->system.coupling_dofs);
    SparsityBuilder builder(static_cast<int>(n));
    for (std::size_t k = 0; k + 1 < impl_->system.pattern_start.size(); ++k)
      builder.add(std::span<const int>(
          impl_->system.pattern_dofs.data() + impl_->system.pattern_start[k],
          at(impl_->system.pattern_start[k + 1] - impl_->system.pattern_start[k])));
    impl_->system.pattern = builder.build();
    impl_->system.stiffness = std::make_unique<Assembler>(impl_->system.pattern);
    for (std::size_t k = 0; k + 1 < impl_->system.coupling_start.size(); ++k) {
      const std::span<const int> dofs(
          impl_->system.coupling_dofs.data() + impl_->system.coupling_start[k],
          at(impl_->system.coupling_start[k + 1] - impl_->system.coupling_start[k]));
      for (const int i : dofs) {
        for (const int j : dofs) {
          if (i >= 0 && j >= i && !impl_->system.pattern.contains(i, j))
            in.fail("a coupling lies outside the sparsity pattern");
        }
      }
      (void)impl_->system.stiffness->plan(dofs);
    }
  }
  const bool had_contact = in.boolean();
  if (had_contact != (impl_->contact != nullptr))
    in.fail(had_contact ? "it has contacts, the case cannot touch"
                        : "it has no contacts, the case has");
  if (impl_->contact)
    impl_->contact->load_state(in);
}

} // namespace nmm
