// SPDX-License-Identifier: MIT
// solver/time_stepper.hpp — Shi's time steps (1997, eq. 2.17-2.25; chapter 8): assemble
// K + 2M/dt² with the inertia load 2M v0/dt, solve for the step displacement, update
// velocities, stresses and geometry; static analysis with the velocity reset every step,
// and a single solve per step (no mass) when nothing can touch; step control from the
// maximum step displacement (section 8.5).
#pragma once

#include "contact/contact_system.hpp"
#include "manifold/bolt.hpp"
#include "manifold/boundary_conditions.hpp"
#include "manifold/model.hpp"
#include "solver/dof_map.hpp"
#include "solver/linear_solver.hpp"
#include "solver/pcg_solver.hpp"

#include <Eigen/Core>

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace nmm {

/// Dynamic (velocity carried over) or static (Shi's static: velocity reset every step).
enum class TimeIntegration { dynamic, static_reset };

/// Options of the time stepper.
struct StepperOptions {
  TimeIntegration integration = TimeIntegration::dynamic;
  /// Fixed time step in s; empty: automatic from max_step_displacement (Shi 8.5).
  std::optional<double> time_step;
  /// Largest allowed step displacement as a fraction of the model size (Shi's g2).
  double max_step_displacement = 0.01;
  /// Stiffness of penalty supports, N/m (Shi's p, 40 E by default from the case file).
  double spring_stiffness = 0.0;
  /// How often a step may be cut (to a half in automatic mode for the displacement limit,
  /// to a third when the open-close iteration does not converge) before the run stops.
  int max_step_cuts = 10;
  /// Open-close iterations with mode changes (each a refactorisation) per step before the
  /// step is cut (Shi 8.2). In a dynamic step, iterations that only move edge-to-edge
  /// springs along their overlaps do not count; no step has more than ten times this many
  /// refactorisations (ten times open_close_base without it). Empty: the budget of the scene
  /// (open_close_limit(): 6, or twice the most contacts one iteration of the try changed, at most
  /// twice the bodies and 30).
  std::optional<int> open_close_max;
  /// Solves with the same factor for friction alone (no mode changed, the friction loads
  /// still moving) per step before the step is cut.
  int friction_solves_max = 50;
  /// A step whose open-close iteration does not converge with friction as loads from the
  /// last iteration, with a sliding contact that has friction, is tried again with friction
  /// coupled to the normal force in the solve before it is cut (docs/formulation.md,
  /// "Coupled friction"); false: it is cut at once.
  bool coupled_friction = true;
  /// A try with coupled friction solves each system by GMRES to this relative residual ...
  double coupled_friction_tolerance = 1e-12;
  /// ... in at most this many iterations (one solve with the factor each; fewer when there
  /// are fewer sliding contacts: GMRES ends within their number + 1), or the try is cut.
  int coupled_friction_iterations_max = 100;
  /// Solve the step systems by conjugate gradients with these settings (PcgSolver, CHOLMOD
  /// where they do not converge); empty: by CHOLMOD.
  std::optional<PcgOptions> conjugate_gradients;
  /// A step whose energy balance misses by more than this fraction of its largest term
  /// (StepReport::energy_error) adds a warning (the first such step of the run).
  double energy_tolerance = 0.05;
  /// A step whose energy balance misses by more than this stops the run (NumericalError);
  /// empty: only the energy check's ten times the budget does (judge_energy()).
  std::optional<double> energy_error_limit;
  /// Shi's dynamic ratio k01: a dynamic step starts from this fraction of the last step's
  /// end velocities, in (0, 1]; below 1 it damps the high-frequency flip of contact
  /// springs at rest (v1 = 2d/dt - v0), the kinetic energy it removes counted as
  /// dissipated (docs/formulation.md, "Energy balance"). 1: the velocities carry over.
  double velocity_ratio = 1.0;
  /// A lock that has switched between lock and slide chatter_limit times in a static step
  /// slides at its friction limit for the rest of the step, as in a dynamic step, instead of
  /// being held locked beyond it (docs/formulation.md, "Chatter rule"). For the trials of a
  /// strength reduction (`nmm fos`): a lock held beyond Coulomb's limit stands a block that
  /// the reduced strength lets slide, and whether it slides is what a trial asks.
  bool static_chatter_slides = false;
};

/// What stays defined through the run: supports, loads and the material points to follow.
struct Scene {
  std::vector<SupportPoint> supports;
  std::vector<BodyLoad> body_loads;
  std::vector<PointLoad> point_loads;
  std::vector<CurveLoad> curve_loads;
  /// Material points followed for monitors (moved with the material every step).
  std::vector<MaterialPoint> monitors;
  /// Rock bolts: their bars couple the elements of their ends, their forces change with the
  /// steps (advance_bolts()).
  std::vector<Bolt> bolts;
};

/// One completed step (a row of history.csv).
struct StepReport {
  long step = 0;                 ///< 1-based
  double time = 0.0;             ///< at the end of the step, s
  double dt = 0.0;               ///< s
  int open_close_iterations = 0; ///< solves of the last try of the step (with friction solves)
  int contacts = 0;
  int step_cuts = 0;             ///< times this step was cut and redone
  double kinetic_energy = 0.0;   ///< J (per metre in plane strain)
  double max_displacement = 0.0; ///< largest step displacement, m
  /// Work of the loads (body forces, point and curve loads, the release of initial stresses
  /// and of VEM blocks' carried stabilisation forces) on the step displacements since the
  /// first step, the initial equilibrium not counted;
  /// with the kinetic energy it shows a run's energy balance, J (per metre in plane strain).
  double load_work = 0.0;
  /// Deepest penetration of a closed contact at the end of the step, m (0 without contact).
  double max_penetration = 0.0;
  /// Largest shear over friction limit of a contact held locked beyond it at the end of the
  /// step (ModeUpdate::lock_excess; 0: every lock within friction).
  double lock_excess = 0.0;
  /// Work of the friction of contacts held sliding at their limit by the chatter rule along
  /// motions that turned back against it in the step (ModeUpdate::slide_feed), J (per metre
  /// in plane strain); 0: friction opposed every slide.
  double slide_feed = 0.0;
  // Why the step was cut and how close its iteration came to its limit (the progress line,
  // io/progress.hpp); the cuts by reason add up to step_cuts.
  int cuts_open_close = 0;   ///< cuts because the open-close iteration did not converge
  int cuts_displacement = 0; ///< cuts to the step displacement limit (Shi 8.5)
  int cuts_energy = 0;       ///< cuts by the energy check (judge_energy())
  int cuts_not_finite = 0;   ///< cuts because a solve's step displacement was not finite
  /// Open-close iterations of the last try that count against the limit (those that changed
  /// a contact's mode), and that limit: open_close_max (or the scene's budget when it is not
  /// given, open_close_limit()), ten times it for a settling step; 0 without contact (no
  /// open-close iteration).
  int open_close_counted = 0;
  int open_close_limit = 0;
  int sliding = 0; ///< closed contact points sliding at the end of the step
  // Energy balance (docs/formulation.md, "Energy balance"), J (per metre in plane strain),
  // measured from the start of the first time step (the initial equilibrium not counted).
  /// Work of the loads alone (body forces, point and curve loads) since the first step.
  double external_work = 0.0;
  /// Change of the elements' elastic energy (stabilisation included) since the first step:
  /// negative where initial stresses were released.
  double strain_energy = 0.0;
  /// Energy in the closed contacts' springs at the end of the step.
  double contact_energy = 0.0;
  /// Friction work at sliding contacts and the numerical dissipation of the time
  /// integration in the elements, since the first step.
  double dissipated_energy = 0.0;
  /// |kinetic + strain + contact + dissipated - initial - external_work| over the largest
  /// of those terms (0 when all are 0).
  double energy_error = 0.0;
};

/// Work counters, for summary.json (issue 8: "skip what the scene does not need").
struct StepperCounters {
  long steps = 0;
  long step_cuts = 0;
  long contact_searches = 0;
  long pattern_builds = 0;
  long plan_rebuilds = 0;  ///< couplings changed within the pattern: new plans, same analysis
  long stress_updates = 0; ///< element stresses advanced by a step's strain (every step)
  /// Friction loads assembled (a sliding, pressed contact point with friction, per open-close
  /// iteration): 0 in a frictionless scene.
  long friction_terms = 0;
  /// Augmented-Lagrange passes (ContactOptions::penetration_tolerance): solves again with the
  /// same matrix after the springs' zeros moved by their penetrations.
  long augmentations = 0;
  /// Tries of a step with friction coupled to the normal force in the solve, after the
  /// open-close iteration did not converge with friction as loads, and their GMRES
  /// iterations (one solve with the factor each).
  long coupled_friction_tries = 0;
  long coupled_friction_iterations = 0;
  /// Steps that ended with a contact held locked beyond its friction limit by the chatter
  /// rule (ModeUpdate::lock_excess), and the largest shear over limit among them (0: Coulomb's
  /// law held at every contact at the end of every step, to a negligible force).
  long locks_beyond_friction = 0;
  double max_lock_excess = 0.0;
  /// Steps of a dynamic analysis that ended with a contact held sliding at its friction
  /// limit against a motion that turned back (StepReport::slide_feed), and the work that
  /// friction did along those motions over the run, J.
  long slides_against_motion = 0;
  double slide_feed_work = 0.0;
  /// Wall time of each part of the steps so far, s (bench/step_bench.cpp and
  /// bench/block_bench.py report them). The parts are laps of one clock through a step, so
  /// they add up to seconds_steps (every try of a cut step included).
  double seconds_steps = 0.0;           ///< the whole of step() and equilibrate()
  double seconds_step_control = 0.0;    ///< time step choice; displacement limit, energy check
  double seconds_detection = 0.0;       ///< contact detection, transfer (and restart) of states
  double seconds_constraints = 0.0;     ///< DofMap and the reduction of every coupling
  double seconds_pattern = 0.0;         ///< sparsity pattern and scatter plans (when rebuilt)
  double seconds_assembly = 0.0;        ///< element integrals, matrices and loads; right side
  double seconds_contact_springs = 0.0; ///< contact springs and friction loads, per iteration
  double seconds_analysis = 0.0;        ///< symbolic analysis (when the pattern changed)
  double seconds_factorization = 0.0;   ///< numeric factorisation
  double seconds_solve = 0.0;           ///< triangular solves, expansion to raw unknowns
  double seconds_contact_modes = 0.0;   ///< open-close mode updates after every solve
  double seconds_update = 0.0;          ///< velocities, stresses, contact states, geometry
};

// The parts of a step (solver/step_context.hpp, step_control.hpp).
struct StepContext;
struct StepKind;
struct StepTries;
struct TrySolution;
class StepClock;

/// Advances a model through time steps.
class TimeStepper {
public:
  /// @throws InputError for a scene that cannot be solved: a dynamic analysis with a
  ///         massless material, or a static one with a body that nothing holds (naming the
  ///         material and a point of the body).
  /// @param contact  the contact system, or null: a model in which nothing can touch (one
  ///                 block, no joint face) never searches for contact.
  TimeStepper(Model& model,
              Scene scene,
              StepperOptions options,
              std::unique_ptr<ContactSystem> contact = nullptr);
  ~TimeStepper();
  TimeStepper(const TimeStepper&) = delete;
  TimeStepper& operator=(const TimeStepper&) = delete;

  /// Sets the velocity of every cover from a velocity field v(x) = v0 + omega J (x - centre)
  /// per block (material initial_velocity and initial_angular_velocity).
  void set_rigid_velocities(const std::vector<Point2>& block_velocity,
                            const std::vector<double>& block_angular_velocity);

  /// A stage's change of analysis kind (`[[stage]] kind`): the next steps are of
  /// @p integration; a static one starts from rest.
  void set_integration(TimeIntegration integration);
  /// A stage's new supports, loads and bolts (`[[stage.boundary]]`, ...), added to the
  /// scene for the next steps. @p more's monitors are ignored.
  void add_to_scene(const Scene& more);
  /// Elements were excavated (ModelElement::excavated): the order-1 dependencies are chosen
  /// again for the material left, and the forces with which the last step's contacts of the
  /// excavated material held the rest become point loads on the rest
  /// (ContactSystem::forces_of_excavated()), released by set_contact_release() (those of an
  /// earlier excavation, released by now, are dropped).
  void material_removed();
  /// The part @p left (1 to 0) of the contact forces of the last excavation still applied.
  void set_contact_release(double left);

  /// One time step ending at most at @p until (s). @throws NumericalError when the step
  /// cannot be solved even after max_step_cuts cuts, with what went wrong.
  StepReport step(double until);

  /// Initial equilibrium (a geostatic step): one static solve of the loads at the current
  /// time with every contact that touches locked (no sliding; contacts in tension open), so
  /// that the contact springs carry the weight and the stresses start in equilibrium before
  /// the first step; the geometry moves by the (small) settlement, the velocities stay zero,
  /// time and step count do not advance. Without it, bodies resting on each other start
  /// with unloaded springs and drop into them during the first steps.
  /// @throws NumericalError when a body is held neither by supports nor by contacts.
  StepReport equilibrate();

  /// Raw velocity of every unknown (m/s).
  [[nodiscard]] const Eigen::VectorXd& velocity() const noexcept { return velocity_; }
  [[nodiscard]] double time() const noexcept { return time_; }
  [[nodiscard]] const Scene& scene() const noexcept { return scene_; }
  [[nodiscard]] const StepperCounters& counters() const noexcept { return counters_; }
  /// The linear solver's counters, those of the run before a restart included.
  [[nodiscard]] SolverCounters solver_counters() const;
  /// Number of unknowns of the linear system.
  [[nodiscard]] int n_unknowns() const;
  /// Velocity of the material at @p x in @p element.
  [[nodiscard]] Point2 velocity_at(int element, const Point2& x) const;
  /// Warnings gathered during the run (e.g. a fixed time step exceeding the displacement
  /// limit), each reported once.
  [[nodiscard]] const std::vector<std::string>& warnings() const noexcept { return warnings_; }
  /// The matrix of the last step's linear system (upper triangle), for benchmarks.
  [[nodiscard]] const SparseMatrix& last_matrix() const;
  /// Largest penetration of a closed contact at the end of the last step (m); 0 without
  /// contact.
  [[nodiscard]] double contact_penetration() const;
  /// Closed contacts and contact points at the end of the last step, for output.
  [[nodiscard]] const ContactSystem* contact() const;
  /// The model size used for max_step_displacement (m).
  [[nodiscard]] double model_size() const noexcept { return model_size_; }

  /// Writes everything the next step starts from (velocities, time, counters, warnings, the
  /// moving support, load and monitor points, the energy budget, the last step's slaves and
  /// sparsity pattern, the contact states) and the model's state, for a restart checkpoint:
  /// a run restarted from it takes the same steps to the last bit (tests/regression
  /// restart_test.cpp). Call between steps.
  void save_state(StateWriter& out) const;
  /// Reads what save_state() wrote into a stepper built for the same case, before its
  /// first step. @throws InputError when the checkpoint is of another model.
  void load_state(StateReader& in);

private:
  struct Impl;
  /// One step: its time step, its tries (try_until_accepted()) and commit_step().
  StepReport advance(double until, bool equilibrium);
  /// Tries the step, cut or with friction coupled after each try refused (step_control.hpp),
  /// until one is accepted: its solution.
  TrySolution try_until_accepted(const StepContext& context,
                                 StepTries& tries,
                                 StepReport& report,
                                 StepClock& clock);
  /// Velocities, contact states, stresses and geometry take the accepted step; time advances.
  void commit_step(const StepKind& kind, double dt, TrySolution& solution, StepReport& report);
  Model& model_;
  Scene scene_;
  StepperOptions options_;
  Eigen::VectorXd velocity_;
  double time_ = 0.0;
  long step_ = 0;
  double model_size_ = 1.0;
  bool has_mass_ = false; ///< some material has a density
  StepperCounters counters_;
  std::vector<std::string> warnings_;
  std::unique_ptr<Impl> impl_;
};

} // namespace nmm
