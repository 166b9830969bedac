// SPDX-License-Identifier: MIT
#include "solver/open_close.hpp"

#include "mesh/error.hpp"
#include "solver/low_rank_solve.hpp"

#include <algorithm>
#include <sstream>
#include <string_view>
#include <utility>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// The coupled friction of the contacts (ContactSystem::FrictionCoupling) in the reduced
/// unknowns: for contact j, column j of U is -coef w and of V is a (an unsymmetric term
/// U V^T of the step matrix), and the load coef (c0 + a . t0) w is added to @p rhs.
std::pair<SparseMatrix, SparseMatrix>
reduce_coupling(const std::vector<ContactSystem::FrictionCoupling>& terms,
                const DofMap& map,
                const StepCouplings& couplings,
                Eigen::VectorXd& rhs) {
  std::vector<Eigen::Triplet<double>> u_entries;
  std::vector<Eigen::Triplet<double>> v_entries;
  auto add = [&](int column, int unknown, double along, double normal, double load) {
    u_entries.emplace_back(unknown, column, along);
    v_entries.emplace_back(unknown, column, normal);
    rhs(unknown) += load * along;
  };
  for (std::size_t j = 0; j < terms.size(); ++j) {
    const ContactSystem::FrictionCoupling& term = terms[j];
    const auto column = static_cast<int>(j);
    const int transform = couplings.contact_transform[at(term.point)];
    if (transform < 0) {
      const std::span<const int> dofs = couplings.contact_point_dofs(term.point);
      for (std::size_t l = 0; l < dofs.size(); ++l) {
        const auto i = static_cast<Eigen::Index>(l);
        add(column, map.reduced(dofs[l]), -term.coef * term.w(i), term.a(i), -term.c0);
      }
      continue;
    }
    const Reduction& r = couplings.transforms[at(transform)];
    const Eigen::VectorXd w = r.transform.transpose() * term.w;
    const Eigen::VectorXd gradient = r.transform.transpose() * term.a;
    const double c0 = term.c0 + term.a.dot(r.constant);
    for (std::size_t l = 0; l < r.reduced.size(); ++l) {
      const auto i = static_cast<Eigen::Index>(l);
      add(column, r.reduced[l], -term.coef * w(i), gradient(i), -c0);
    }
  }
  const auto n = static_cast<Eigen::Index>(map.n_reduced());
  const auto m = static_cast<Eigen::Index>(terms.size());
  std::pair<SparseMatrix, SparseMatrix> uv{SparseMatrix(n, m), SparseMatrix(n, m)};
  uv.first.setFromTriplets(u_entries.begin(), u_entries.end());
  uv.second.setFromTriplets(v_entries.begin(), v_entries.end());
  return uv;
}

/// Why the step matrix cannot be factorised, naming the body whose unknowns are free.
std::string
singular_message(const Model& model, const DofMap& map, long column, SolveStatus status) {
  std::ostringstream message;
  message << "the step matrix is singular (" << to_string(status) << ")";
  if (column < 0)
    return message.str();
  for (int d = 0; d < model.n_dofs(); ++d) {
    if (map.reduced(d) != column)
      continue;
    const ModelCover& cover = model.covers[at(model.cover_of_dof(d))];
    int material = -1;
    for (const ModelElement& e : model.elements) {
      if (e.block == cover.block)
        material = e.material;
    }
    message << " at the unknowns of the cover near " << point_text(cover.position, 6)
            << (material >= 0 ? " (material \"" + model.materials[at(material)].name + "\")"
                              : std::string())
            << ": this body can move freely in " << ((d % 2) == 0 ? "x" : "y")
            << "; hold it with a [[boundary]] support (static analysis) or give it mass "
               "(dynamic analysis)";
    break;
  }
  return message.str();
}

/// Adds the warning that a step's augmented-Lagrange passes ended (or, @p unsettled, that
/// the iteration after one did not converge and the step kept its least penetrating
/// converged solve) with the contacts still penetrating by @p penetration, more than the
/// tolerance (once a run for each).
void warn_penetration(const StepContext& context,
                      double penetration,
                      const ContactOptions& options,
                      bool unsettled) {
  std::vector<std::string>& warnings = context.warnings;
  // One warning a run for each of the two ways the passes end short of the tolerance.
  const std::string_view what =
      unsettled ? "after an augmented-Lagrange pass the contacts" : "augmented-Lagrange passes";
  if (penetration <= options.penetration_tolerance ||
      std::any_of(warnings.begin(), warnings.end(),
                  [&](const std::string& w) { return w.find(what) != std::string::npos; }))
    return;
  std::ostringstream w;
  w << "step " << context.step << ": ";
  if (unsettled)
    w << what << " changed mode without settling, so the step kept its least penetrating "
      << "converged solve, where a contact penetrated by " << penetration << " m";
  else
    w << "after its " << what << " (at most " << options.augment_max
      << ", fewer when one leaves the deepest contact no shallower) a contact still "
         "penetrated by "
      << penetration << " m";
  w << ", more than penetration_tolerance (" << options.penetration_tolerance
    << " m); the step went on so. ";
  if (unsettled)
    w << "The passes push the contacts apart further than they settle in a step (many "
         "bodies landing at once): a larger penetration_tolerance, or a larger penalty, "
         "needs smaller pushes";
  else
    w << "They converge slowly where the pressure concentrates (the corners of pressed "
         "faces, a tolerance near the hard-contact limit): a larger penetration_tolerance, or "
         "a larger penalty, holds it in fewer passes";
  warnings.push_back(w.str());
}

/// The open-close iteration of one try (Shi 8.2): the elements and supports stay, the
/// contact springs and friction loads follow the modes until no contact changes its mode and
/// friction agrees with the normal forces. An iteration in which only the friction loads
/// changed has the same matrix: it reuses the factor (one more solve, no refactorisation).
class OpenCloseIteration {
public:
  OpenCloseIteration(const StepContext& context,
                     const StepTries& tries,
                     StepSystemState& state,
                     StepSystem& system,
                     StepClock& clock,
                     Eigen::VectorXd& raw);
  OpenCloseIteration(const OpenCloseIteration&) = delete;
  OpenCloseIteration& operator=(const OpenCloseIteration&) = delete;
  OpenCloseIteration(OpenCloseIteration&&) = delete;
  OpenCloseIteration& operator=(OpenCloseIteration&&) = delete;
  /// The solver's solves are to its own tolerance again, however the iteration ended.
  ~OpenCloseIteration() { context_.solver.set_loose(false); }
  OpenCloseResult run();

private:
  /// One solve: contact springs, right side, analysis and factorisation where needed.
  /// Returns false when a coupled solve does not converge (the try fails).
  bool solve();
  void add_contact_springs(Eigen::VectorXd& f);
  void factorize();
  /// A solve with coupled friction: the sliding contacts' terms of rank one and loads in the
  /// reduced unknowns (reduce_coupling()), solved by GMRES preconditioned with the factor of
  /// the symmetric matrix.
  LowRankSolveReport solve_coupled(const Eigen::VectorXd& rhs);
  /// After a solve that did not converge: whether the iteration stops (its budget spent).
  bool is_spent(const ModeUpdate& update);

  const StepContext& context_;
  const StepTries& tries_;
  StepSystemState& state_;
  StepSystem& system_;
  StepClock& clock_;
  Eigen::VectorXd& raw_;
  Assembler& matrix_;
  std::vector<double> base_values_;
  Eigen::VectorXd base_correction_;
  /// The solution in the reduced unknowns; an iterative solver's first guess.
  Eigen::VectorXd reduced_;
  bool assemble_ = true;
  /// The solves are to the iterative solver's loose tolerance (until no mode changes).
  bool loose_ = false;
  int friction_solves_ = 0;
  int open_close_ = 0;   ///< iterations that changed a contact's mode
  int most_changes_ = 0; ///< the most contacts one counted iteration changed (open_close_limit())
  int augmentations_ = 0;
  OpenCloseResult result_;
};

OpenCloseIteration::OpenCloseIteration(const StepContext& context,
                                       const StepTries& tries,
                                       StepSystemState& state,
                                       StepSystem& system,
                                       StepClock& clock,
                                       Eigen::VectorXd& raw)
    : context_(context), tries_(tries), state_(state), system_(system), clock_(clock), raw_(raw),
      matrix_(*state.stiffness), base_correction_(system.rhs_correction) {
  if (context_.contact)
    base_values_.assign(matrix_.values().begin(), matrix_.values().end());
  result_.converged = !context_.contact;
  // The limit of a try that converges before is_spent() judges it (a settling static step's
  // tenfold limit is known only once a solve has moved less than its 1%); none without
  // contact, which has no open-close iteration.
  if (context_.contact)
    result_.limit =
        open_close_limit(context_.options.open_close_max, 0, 0, context_.kind.equilibrium);
  // Contacts' modes are decided on solves to conjugate gradients' loose tolerance; the
  // solve after which no mode changes is repeated to their own, and judged again.
  if (context_.contact && context_.options.conjugate_gradients)
    loose_ = context_.solver.set_loose(true);
  // An iterative solver's first guess: Shi's step displacement d = v dt + a dt^2 / 2 with
  // the last step's acceleration (zero in static steps); then each open-close iteration
  // starts from the last one's solution. At 10,004 DDA blocks falling from rest the guess
  // with the acceleration takes 17.5 iterations a solve, without it (d = v dt) 41.
  if (context_.options.conjugate_gradients) {
    const DofMap& map = *system_.map;
    const double dt = tries_.dt;
    reduced_.setZero(map.n_reduced());
    if (context_.kind.dynamic) {
      for (int r = 0; r < map.n_raw(); ++r) {
        if (!map.is_slave(r))
          reduced_(map.reduced(r)) =
              (context_.velocity(r) + 0.5 * dt * context_.acceleration(r)) * dt;
      }
    }
  }
}

OpenCloseResult OpenCloseIteration::run() {
  ContactSystem* contact = context_.contact;
  for (;;) {
    ++result_.iterations;
    if (!solve())
      break; // the try fails (its step is cut)
    if (!contact)
      break;
    const ModeUpdate update = contact->update_modes(context_.model, raw_);
    clock_.lap(context_.counters.seconds_contact_modes);
    if (contact->converged(update)) {
      if (loose_) {
        context_.solver.set_loose(false);
        loose_ = false;
        assemble_ = false; // the same matrix: the same springs and modes
        continue;
      }
      // Augmented Lagrange: contacts still penetrating by more than the tolerance move
      // their springs' zeros by it and the step is solved again with the same factor.
      const ContactOptions& options = contact->options();
      if (augmentations_ < options.augment_max && contact->augment(raw_)) {
        ++augmentations_;
        ++context_.counters.augmentations;
        open_close_ = 0; // the pass changed the loads: a new iteration, with its own budget
        assemble_ = false;
        continue;
      }
      if (augmentations_ > 0) // the passes ran out or stopped shrinking it: say so once
        warn_penetration(context_, contact->max_penetration(), options, false);
      result_.converged = true;
      break;
    }
    if (is_spent(update))
      break;
  }
  if (!result_.converged && !result_.not_finite && contact->back_to_converged(raw_)) {
    // A pass moved the springs' zeros and the contacts no longer settle: the step keeps
    // its least penetrating converged solve (a penalty solution, only deeper) rather than
    // being cut. Cutting these steps, the 1000-block pile of bench/stress.py
    // pile_1000_al was cut 2504 times in 750 steps and never settled.
    result_.converged = true;
    warn_penetration(context_, contact->max_penetration(), contact->options(), true);
  }
  result_.counted = open_close_;
  return result_;
}

bool OpenCloseIteration::solve() {
  Eigen::VectorXd f_iteration = system_.f;
  if (context_.contact)
    add_contact_springs(f_iteration);
  clock_.lap(context_.counters.seconds_contact_springs);
  const DofMap& map = *system_.map;
  const Eigen::VectorXd rhs = map.restrict(f_iteration) + system_.rhs_correction;
  clock_.lap(context_.counters.seconds_assembly);
  factorize();
  SolveStatus solved = SolveStatus::ok;
  if (tries_.coupled) {
    const LowRankSolveReport gmres = solve_coupled(rhs);
    solved = gmres.status;
    if (solved == SolveStatus::ok && !gmres.converged)
      return false;
  } else {
    solved = context_.solver.solve(rhs, reduced_);
  }
  if (solved == SolveStatus::not_positive_definite) // found by CHOLMOD after CG failed
    throw NumericalError(
        singular_message(context_.model, map, context_.solver.failed_column(), solved));
  if (solved != SolveStatus::ok)
    throw NumericalError("the solve of the step system failed");
  raw_ = map.expand(reduced_);
  if (!raw_.allFinite()) {
    result_.converged = false;
    result_.not_finite = true;
    return false;
  }
  clock_.lap(context_.counters.seconds_solve);
  return true;
}

void OpenCloseIteration::add_contact_springs(Eigen::VectorXd& f) {
  ContactSystem& contact = *context_.contact;
  const StepCouplings& couplings = system_.couplings;
  if (assemble_ && result_.iterations > 1)
    matrix_.assign_values(base_values_);
  if (assemble_)
    system_.rhs_correction = base_correction_;
  Eigen::MatrixXd spring;
  Eigen::VectorXd load;
  for (int i = 0; i < contact.n_points(); ++i) {
    const ContactPoint& point = contact.points()[at(i)];
    if (point.mode == ContactMode::open && !point.bonded)
      continue; // no spring, no load (an open bond pulls with its tensile strength)
    // The upper triangle is what the assembler reads; a transform to the reduced
    // unknowns needs the whole matrix.
    const bool upper = couplings.contact_transform[at(i)] < 0;
    if (contact.contribution(context_.model, i, assemble_ ? &spring : nullptr, load, upper)) {
      ++context_.counters.friction_terms;
      result_.had_friction = true;
    }
    const std::span<const int> dofs = couplings.contact_point_dofs(i);
    NMM_ASSERT(static_cast<std::size_t>(load.size()) == dofs.size(),
               "a contact point's unknowns stay those of the step's start");
    for (std::size_t j = 0; j < dofs.size(); ++j)
      f(dofs[j]) += load(static_cast<Eigen::Index>(j));
    if (assemble_)
      system_.scatter(matrix_, couplings.first_contact_plan + i, spring,
                      couplings.contact_transform[at(i)]);
  }
}

void OpenCloseIteration::factorize() {
  LinearSolver& solver = context_.solver;
  if (system_.rebuilt || !state_.analysed) {
    if (solver.analyze(matrix_.matrix()) != SolveStatus::ok)
      throw NumericalError("the symbolic analysis of the step matrix failed");
    state_.analysed = true;
    system_.rebuilt = false;
  }
  clock_.lap(context_.counters.seconds_analysis);
  if (assemble_) {
    const SolveStatus factor = solver.factorize(matrix_.matrix());
    if (factor != SolveStatus::ok)
      throw NumericalError(
          singular_message(context_.model, *system_.map, solver.failed_column(), factor));
    ++result_.factorisations;
  }
  clock_.lap(context_.counters.seconds_factorization);
}

LowRankSolveReport OpenCloseIteration::solve_coupled(const Eigen::VectorXd& rhs) {
  const StepperOptions& options = context_.options;
  const std::vector<ContactSystem::FrictionCoupling> terms =
      context_.contact->friction_coupling(context_.model);
  if (terms.empty()) {
    LowRankSolveReport direct;
    direct.status = context_.solver.solve(rhs, reduced_);
    direct.converged = true;
    return direct;
  }
  Eigen::VectorXd b = rhs;
  const auto [u, v] = reduce_coupling(terms, *system_.map, system_.couplings, b);
  const Eigen::Index m = u.cols();
  // GMRES ends within m + 1 iterations but for the rounding; a try that needs more than
  // the budget is cut as before.
  const int budget =
      static_cast<int>(std::min<Eigen::Index>(m + 10, options.coupled_friction_iterations_max));
  // Conjugate gradients solve to their own tolerance: GMRES can reach no better.
  const bool exact = !options.conjugate_gradients;
  const double tolerance =
      exact ? options.coupled_friction_tolerance
            : std::max(options.coupled_friction_tolerance, options.conjugate_gradients->tolerance);
  const LowRankSolveReport gmres = solve_low_rank_update(context_.solver, matrix_.matrix(), u, v, b,
                                                         reduced_, tolerance, budget, exact);
  context_.counters.coupled_friction_iterations += gmres.iterations;
  return gmres;
}

bool OpenCloseIteration::is_spent(const ModeUpdate& update) {
  const StepKind& kind = context_.kind;
  const StepperOptions& options = context_.options;
  assemble_ = update.changes > 0;
  // Shi's open-close iterations are those that open, close, stick or slip a contact. In a
  // dynamic step, an iteration that only moves the springs of closed edge-to-edge
  // contacts along their overlaps (the lift-off points converging on where the pressure
  // ends) is none: a shorter step does not make those moves fewer, so they never cut it;
  // they only count against the cap of ten times open_close_max (or open_close_base)
  // refactorisations.
  // Counted as open-close iterations, they would cut the steps of a block sliding on a
  // ramp many times over for nothing. A static step counts them: its inertia term only
  // steadies it, and where bodies fall onto others a cut step is what keeps them apart
  // (docs/formulation.md, "Static steps").
  if (assemble_ && (update.changes > update.moves || !kind.dynamic)) {
    ++open_close_;
    most_changes_ =
        std::max(most_changes_, kind.dynamic ? update.changes - update.moves : update.changes);
  }
  // The initial equilibrium cannot be cut: it has ten times the iterations. So has a step
  // of a static analysis whose last solve moved less than 1% of the step displacement
  // limit: it is short in Shi's sense already (8.5 [1]), and its modes change because
  // slip spreads along the joints, one contact further each iteration, which a cut does
  // not shorten: it only carries less of the load (docs/formulation.md, "Static steps").
  const bool settling =
      kind.equilibrium ||
      (!kind.dynamic && context_.model.largest_displacement(raw_) < 0.01 * kind.limit);
  const auto bodies = static_cast<int>(context_.model.blocks.size());
  result_.limit = open_close_limit(options.open_close_max, most_changes_, bodies, settling);
  const int factorisations_max = 10 * options.open_close_max.value_or(open_close_base);
  return assemble_ ? open_close_ >= result_.limit || result_.factorisations >= factorisations_max
                   : ++friction_solves_ >= options.friction_solves_max;
}

} // namespace

int open_close_limit(const std::optional<int>& given, int most_changes, int bodies, bool settling) {
  if (settling)
    return 10 * given.value_or(open_close_base);
  if (given)
    return *given;
  return std::clamp(2 * std::min(most_changes, bodies), open_close_base, open_close_cap);
}

OpenCloseResult iterate_open_close(const StepContext& context,
                                   const StepTries& tries,
                                   StepSystemState& state,
                                   StepSystem& system,
                                   StepClock& clock,
                                   Eigen::VectorXd& raw) {
  return OpenCloseIteration(context, tries, state, system, clock, raw).run();
}

} // namespace nmm
