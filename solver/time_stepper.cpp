// SPDX-License-Identifier: MIT
#include "solver/time_stepper.hpp"

#include "contact/contact_system.hpp"
#include "manifold/simplex_integration.hpp"
#include "mesh/error.hpp"
#include "solver/assembler.hpp"
#include "solver/cholmod_solver.hpp"
#include "solver/energy_balance.hpp"
#include "solver/geometry_update.hpp"
#include "solver/open_close.hpp"
#include "solver/step_context.hpp"
#include "solver/step_control.hpp"
#include "solver/step_system.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <utility>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

} // namespace

struct TimeStepper::Impl {
  std::unique_ptr<ContactSystem> contact; // null when nothing can touch
  std::unique_ptr<LinearSolver> solver;
  Eigen::VectorXd acceleration; ///< (v1 - v0) / dt of the last step; zero after a static one
  StepSystemState system;       ///< what the step systems keep from step to step
  EnergyBudget energy;          ///< of the energy check
  EnergyLedger ledger;          ///< of the energy balance
  /// Solver counters of the run before a restart.
  SolverCounters restored_counters;
  /// The order-1 dependency fixes are chosen again after every step (rechosen_dependencies()).
  bool rechoose_dependencies = false;
  /// Where the contact forces of the last excavation are in Scene::point_loads: from
  /// released_from on, released_count of them (material_removed(); later stages' loads follow).
  std::size_t released_from = 0;
  std::size_t released_count = 0;
};

namespace {

/// Whether the model's order-1 dependency fixes must follow the geometry: they fix gradient
/// unknowns of the global axes, chosen for the geometry they were chosen at; a block turned
/// exactly (exact_rotation) through a large angle can come to where they no longer pin its
/// flexes (a spinning order-1 plate's step matrix turned singular at 0.7 of a revolution).
bool rechosen_dependencies(const Model& model) {
  if (model.order == 0)
    return false;
  for (int e = 0; e < model.n_elements(); ++e) {
    if (model.elements[at(e)].kind == ElementKind::nmm && model.material_of(e).exact_rotation)
      return true;
  }
  return false;
}

} // namespace

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
  impl_->rechoose_dependencies = rechosen_dependencies(model_);
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

void TimeStepper::set_integration(TimeIntegration integration) {
  if (integration == options_.integration)
    return;
  if (integration == TimeIntegration::dynamic && !has_mass_)
    throw InputError("a dynamic stage needs the mass of every body: give every material a "
                     "density in kg/m³");
  options_.integration = integration;
  velocity_.setZero();
  impl_->acceleration.setZero(velocity_.size());
}

void TimeStepper::add_to_scene(const Scene& more) {
  scene_.supports.insert(scene_.supports.end(), more.supports.begin(), more.supports.end());
  scene_.body_loads.insert(scene_.body_loads.end(), more.body_loads.begin(), more.body_loads.end());
  scene_.point_loads.insert(scene_.point_loads.end(), more.point_loads.begin(),
                            more.point_loads.end());
  scene_.curve_loads.insert(scene_.curve_loads.end(), more.curve_loads.begin(),
                            more.curve_loads.end());
  scene_.bolts.insert(scene_.bolts.end(), more.bolts.begin(), more.bolts.end());
}

void TimeStepper::material_removed() {
  impl_->system.dependencies = model_.dependency_relations();
  std::vector<PointLoad>& loads = scene_.point_loads;
  const auto first = loads.begin() + static_cast<std::ptrdiff_t>(impl_->released_from);
  loads.erase(first, first + static_cast<std::ptrdiff_t>(impl_->released_count));
  impl_->released_from = loads.size();
  impl_->released_count = 0;
  if (!impl_->contact)
    return;
  for (const ContactSystem::PointForce& f : impl_->contact->forces_of_excavated(model_)) {
    PointLoad load;
    load.point = f.point;
    load.force = f.force;
    loads.push_back(load);
  }
  impl_->released_count = loads.size() - impl_->released_from;
}

void TimeStepper::set_contact_release(double left) {
  for (std::size_t k = 0; k < impl_->released_count; ++k)
    scene_.point_loads[impl_->released_from + k].scale = left;
}

StepReport TimeStepper::step(double until) { return advance(until, false); }

StepReport TimeStepper::equilibrate() {
  const auto failure = [](const std::string& what) {
    return NumericalError("initial equilibrium: " + what +
                          " (the initial equilibrium needs every body held by supports or by "
                          "contacts that touch)");
  };
  try {
    return advance(time_, true);
  } catch (const NumericalError& e) {
    if (!impl_->contact)
      throw failure(e.what());
  }
  // Locked contacts could not hold a body: one that only tension holds (a block under a
  // ceiling whose springs open), or one that must tip (its base's springs lift off to a
  // corner, a mechanism). Tied (ContactSystem::set_tie()), every touching contact holds;
  // then a pair of blocks that pulls on each other, net, beyond its bond's strength cannot
  // start from rest, and one whose contacts only press where it tips starts tipping.
  impl_->contact->set_tie(true);
  StepReport report;
  try {
    report = advance(time_, true);
  } catch (const NumericalError& e) {
    impl_->contact->set_tie(false);
    throw failure(e.what());
  }
  impl_->contact->set_tie(false);
  if (const std::string pulled = impl_->contact->untenable_tension(model_); !pulled.empty())
    throw NumericalError("initial equilibrium: " + pulled);
  return report;
}

StepReport TimeStepper::advance(double until, bool equilibrium) {
  StepClock clock;
  impl_->solver->start_step();
  const StepContext context{.model = model_,
                            .scene = scene_,
                            .options = options_,
                            .kind = make_step_kind(options_, equilibrium, impl_->contact != nullptr,
                                                   has_mass_, model_size_),
                            .contact = impl_->contact.get(),
                            .solver = *impl_->solver,
                            .counters = counters_,
                            .warnings = warnings_,
                            .step = step_ + 1,
                            .time = time_,
                            .model_size = model_size_,
                            .velocity = velocity_,
                            .acceleration = impl_->acceleration};
  StepTries tries{.dt = choose_time_step(context, until)};
  StepReport report;
  clock.lap(counters_.seconds_step_control);
  // Contacts are found once per step. A cut step starts the open-close iteration again from
  // the contact state at the start of the step (Shi 8.2 continues it from the modes the
  // longer step reached; with edge-to-edge springs that go where the edges press, those
  // include a pressed part and anchors fitted to a motion the shorter step does not have:
  // examples/10 lost its pivot that way). Rules tried: docs/formulation.md, "Friction".
  if (impl_->contact) {
    impl_->contact->begin_step(model_, context.kind.limit);
    impl_->contact->set_hold_shear(equilibrium);
    impl_->contact->set_chatter_slides(context.kind.dynamic || options_.static_chatter_slides);
    ++counters_.contact_searches;
  }
  clock.lap(counters_.seconds_detection);
  TrySolution solution = try_until_accepted(context, tries, report, clock);
  if (!equilibrium)
    impl_->energy.load_work += solution.work;
  report.load_work = impl_->energy.load_work;
  const BoltWork bolts = advance_bolts(model_, scene_.bolts, solution.raw);
  account_energy(context, impl_->system, solution.external, solution.raw, tries.dt,
                 solution.kinetic, bolts, impl_->ledger, report);
  if (!equilibrium)
    judge_balance(context, report, solution.new_velocity, solution.largest, impl_->ledger.warned);
  clock.lap(counters_.seconds_step_control);
  commit_step(context.kind, tries.dt, solution, report);
  clock.lap(counters_.seconds_update);
  counters_.seconds_steps += clock.elapsed();
  return report;
}

TrySolution TimeStepper::try_until_accepted(const StepContext& context,
                                            StepTries& tries,
                                            StepReport& report,
                                            StepClock& clock) {
  TrySolution solution;
  for (int attempt = 0;; ++attempt) {
    clock.lap(counters_.seconds_step_control); // the checks of a try that was cut
    if (attempt > 0 && impl_->contact)
      impl_->contact->restart_step();
    if (impl_->contact)
      impl_->contact->set_coupled_friction(tries.coupled);
    clock.lap(counters_.seconds_detection); // (the contact states back to the step's start)
    StepSystem system = build_step_system(context, impl_->system, tries.dt, clock);
    const OpenCloseResult iteration =
        iterate_open_close(context, tries, impl_->system, system, clock, solution.raw);
    report.open_close_iterations = iteration.iterations;
    report.open_close_counted = iteration.counted;
    report.open_close_limit = iteration.limit;
    if (judge_iteration(context, iteration, tries) == TryVerdict::again ||
        judge_displacement(context, solution, tries) == TryVerdict::again)
      continue;
    solution.work = system.loads.dot(solution.raw);
    if (judge_energy(context, impl_->system.element_mass, impl_->energy, solution, tries) ==
        TryVerdict::accept) {
      solution.external = std::move(system.external);
      break;
    }
  }
  report.step_cuts = tries.cuts;
  report.cuts_open_close = tries.cuts_open_close;
  report.cuts_displacement = tries.cuts_displacement;
  report.cuts_energy = tries.cuts_energy;
  report.cuts_not_finite = tries.cuts_not_finite;
  report.max_displacement = solution.largest;
  report.kinetic_energy = solution.kinetic;
  return solution;
}

void TimeStepper::commit_step(const StepKind& kind,
                              double dt,
                              TrySolution& solution,
                              StepReport& report) {
  // Velocities (computed and checked by the energy check), stresses, geometry.
  Eigen::VectorXd& raw = solution.raw;
  if (kind.dynamic) {
    impl_->acceleration = (solution.new_velocity - velocity_) / dt;
    velocity_ = std::move(solution.new_velocity);
    if (options_.velocity_ratio < 1.0)
      velocity_ *= options_.velocity_ratio; // Shi's k01; the acceleration keeps v1 - v0
  } else {
    velocity_.setZero();
    impl_->acceleration.setZero(velocity_.size());
  }
  if (impl_->contact) {
    // Closed contacts carry over with the kinematics of this step (before the geometry moves).
    impl_->contact->end_step(model_, raw);
    report.contacts = impl_->contact->n_closed();
    report.sliding = impl_->contact->n_sliding();
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
  update_geometry(model_, scene_, raw, velocity_, time_ + dt);
  if (impl_->rechoose_dependencies)
    impl_->system.dependencies = model_.dependency_relations();
  if (!kind.equilibrium) {
    time_ += dt;
    ++step_;
    ++counters_.steps;
  }
  report.step = step_;
  report.time = time_;
  report.dt = dt;
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
  if (!scene_.bolts.empty()) { // (a case without bolts keeps its checkpoint's layout)
    out.section("BOLT");
    for (const Bolt& bolt : scene_.bolts) {
      out.put_count(bolt.bars.size());
      for (const BoltBar& bar : bolt.bars) {
        save_point(out, bar.a);
        save_point(out, bar.b);
        out.put(bar.force);
        out.put(bar.yield_force);
        out.put(static_cast<std::int64_t>(bar.state));
      }
    }
  }
  out.put(impl_->energy.start_energy);
  out.put(impl_->energy.started);
  out.put(impl_->energy.load_work);
  impl_->ledger.save_state(out);
  out.put(impl_->acceleration);
  impl_->system.save_state(out);
  out.put(impl_->contact != nullptr);
  if (impl_->contact)
    impl_->contact->save_state(out);
}

void TimeStepper::load_state(StateReader& in) {
  NMM_ASSERT(step_ == 0 && counters_.steps == 0, "a checkpoint is loaded before the first step");
  model_.load_state(in);
  if (impl_->rechoose_dependencies)
    impl_->system.dependencies = model_.dependency_relations(); // as after the step it ended
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
  if (!scene_.bolts.empty()) {
    in.section("BOLT");
    for (Bolt& bolt : scene_.bolts) {
      in.expect_count(bolt.bars.size(), "bars of bolt \"" + bolt.name + "\"");
      for (BoltBar& bar : bolt.bars) {
        load_point(in, bar.a, model_.n_elements());
        load_point(in, bar.b, model_.n_elements());
        bar.force = in.real();
        bar.yield_force = in.real();
        const std::int64_t state = in.integer();
        if (state < 0 || state > static_cast<std::int64_t>(BoltState::ruptured))
          in.fail("a bolt bar in state " + std::to_string(state));
        bar.state = static_cast<BoltState>(state);
      }
    }
  }
  impl_->energy.start_energy = in.real();
  impl_->energy.started = in.boolean();
  impl_->energy.load_work = in.real();
  impl_->ledger.load_state(in);
  impl_->acceleration = in.vector();
  if (impl_->acceleration.size() != model_.n_dofs())
    in.fail("its accelerations have " + std::to_string(impl_->acceleration.size()) +
            " unknowns, the case has " + std::to_string(model_.n_dofs()));
  impl_->system.load_state(in, model_.n_dofs());
  const bool had_contact = in.boolean();
  if (had_contact != (impl_->contact != nullptr))
    in.fail(had_contact ? "it has contacts, the case cannot touch"
                        : "it has no contacts, the case has");
  if (impl_->contact)
    impl_->contact->load_state(in);
}

} // namespace nmm
