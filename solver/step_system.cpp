// SPDX-License-Identifier: MIT
#include "solver/step_system.hpp"

#include "manifold/boundary_conditions.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Appends the reduced unknowns of the raw unknowns @p raw to @p flat. Returns true when
/// every one is free (the common case: then they are appended in local order and the local
/// matrix scatters as it is); otherwise fills @p r and appends its sorted unknowns.
bool reduce(const DofMap& map, std::span<const int> raw, std::vector<int>& flat, Reduction& r) {
  bool identity = true;
  for (std::size_t i = 0; i < raw.size() && identity; ++i)
    identity = !map.is_slave(raw[i]);
  if (identity) {
    for (const int d : raw)
      flat.push_back(map.reduced(d));
    return true;
  }
  std::vector<DofExpansion> expansions;
  expansions.reserve(raw.size());
  r.reduced.clear();
  for (std::size_t i = 0; i < raw.size(); ++i) {
    expansions.push_back(map.expansion(raw[i]));
    for (const auto& [j, c] : expansions.back().terms)
      r.reduced.push_back(j);
  }
  std::sort(r.reduced.begin(), r.reduced.end());
  r.reduced.erase(std::unique(r.reduced.begin(), r.reduced.end()), r.reduced.end());
  const auto n = static_cast<Eigen::Index>(raw.size());
  r.transform = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(r.reduced.size()));
  r.constant = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const DofExpansion& e = expansions[static_cast<std::size_t>(i)];
    r.constant(i) = e.constant;
    for (const auto& [j, c] : e.terms) {
      const auto column =
          std::lower_bound(r.reduced.begin(), r.reduced.end(), j) - r.reduced.begin();
      r.transform(i, column) += c;
    }
  }
  flat.insert(flat.end(), r.reduced.begin(), r.reduced.end());
  return false;
}

/// The constraints at @p time (extensions, the order-1 dependencies, supports) and their
/// map. The last step's slaves are kept where they still may be: the same pattern, no new
/// symbolic analysis.
std::shared_ptr<const DofMap>
make_step_map(const StepContext& context, const StepSystemState& state, double time) {
  const Model& model = context.model;
  std::vector<LinearConstraint> constraints = model.extension_relations();
  constraints.insert(constraints.end(), state.dependencies.begin(), state.dependencies.end());
  const std::vector<LinearConstraint> supports =
      support_constraints(model, context.scene.supports, time);
  constraints.insert(constraints.end(), supports.begin(), supports.end());
  const std::vector<LinearConstraint> excavated = model.excavated_cover_relations();
  constraints.insert(constraints.end(), excavated.begin(), excavated.end());
  return std::make_shared<const DofMap>(model.n_dofs(), constraints, 1e-12, context.model_size,
                                        state.map.get());
}

/// Reduced unknowns of every coupling (StepCouplings). Every contact found at the start of
/// the step is in the pattern (DESIGN.md): the symbolic analysis runs once per step,
/// open-close iterations only refactorise.
StepCouplings
make_couplings(const StepContext& context, const DofMap& map, std::size_t expected_size) {
  const Model& model = context.model;
  const std::vector<SupportPoint>& supports = context.scene.supports;
  StepCouplings c;
  c.starts.reserve(model.elements.size() + supports.size() + 1);
  c.flat.reserve(expected_size);
  c.transform_of.assign(model.elements.size(), -1);
  for (int e = 0; e < model.n_elements(); ++e) {
    Reduction r;
    if (!reduce(map, model.element_dofs(e), c.flat, r)) {
      c.transform_of[at(e)] = static_cast<int>(c.transforms.size());
      c.transforms.push_back(std::move(r));
    }
    c.starts.push_back(static_cast<int>(c.flat.size()));
  }
  for (std::size_t s = 0; s < supports.size(); ++s) {
    const SupportPoint& support = supports[s];
    if (support.method == SupportMethod::penalty && support.point.element >= 0 &&
        !model.elements[at(support.point.element)].excavated) {
      const int e = support.point.element;
      c.flat.insert(c.flat.end(), c.flat.begin() + c.starts[at(e)],
                    c.flat.begin() + c.starts[at(e + 1)]);
      c.starts.push_back(static_cast<int>(c.flat.size()));
      c.spring_of.push_back(static_cast<int>(s));
    }
  }
  c.first_bar_plan = static_cast<int>(model.elements.size() + c.spring_of.size());
  for (const Bolt& bolt : context.scene.bolts) {
    for (const BoltBar& bar : bolt.bars) {
      append_bar_dofs(model, bar, c.bar_dofs);
      c.bar_start.push_back(static_cast<int>(c.bar_dofs.size()));
      Reduction r;
      c.bar_transform.push_back(-1);
      if (!reduce(map, c.bar_unknowns(c.bar_transform.size() - 1), c.flat, r)) {
        c.bar_transform.back() = static_cast<int>(c.transforms.size());
        c.transforms.push_back(std::move(r));
      }
      c.starts.push_back(static_cast<int>(c.flat.size()));
    }
  }
  if (context.contact) {
    context.contact->prepare_kinematics(model);
    for (int i = 0; i < context.contact->n_points(); ++i) {
      context.contact->append_point_dofs(model, i, c.contact_dofs);
      c.contact_start.push_back(static_cast<int>(c.contact_dofs.size()));
      Reduction r;
      c.contact_transform.push_back(-1);
      if (!reduce(map, c.contact_point_dofs(i), c.flat, r)) {
        c.contact_transform.back() = static_cast<int>(c.transforms.size());
        c.transforms.push_back(std::move(r));
      }
      c.starts.push_back(static_cast<int>(c.flat.size()));
    }
  }
  c.first_contact_plan = c.first_bar_plan + static_cast<int>(c.bar_transform.size());
  return c;
}

/// Plan k of couplings first, first + 1, ... (in order), or -1 when it is not in the
/// pattern. The points of an edge-to-edge pair couple the same unknowns: one plan for them
/// (looking further back, for all the contacts of two elements, costs as much as it saves
/// at 10,004 DDA blocks).
int plan_coupling(Assembler& a, const StepCouplings& c, std::size_t k, std::size_t first) {
  if (k > first && std::ranges::equal(c.coupling(k), c.coupling(k - 1)))
    return a.plan_as(static_cast<int>(k) - 1);
  return a.plan_if_in_pattern(c.coupling(k));
}

/// The sparsity pattern: rebuilt only when a coupling needs an entry it does not have.
/// Couplings that changed within it (the expansion of a slave gaining or losing a term
/// whose coefficient cancels to rounding as supports move) only get new plans: no new
/// symbolic analysis. Returns whether the pattern was rebuilt.
bool update_pattern(StepSystemState& state,
                    const StepCouplings& c,
                    int n_reduced,
                    StepperCounters& counters) {
  const std::vector<int>& starts = c.starts;
  const std::vector<int>& flat = c.flat;
  const bool same_size = state.stiffness && state.pattern.n_dofs() == n_reduced;
  const bool same = same_size && state.coupling_start == starts && state.coupling_dofs == flat;
  // The elements and supports come first and rarely change: when only the contacts did,
  // their plans stay and only the contacts' are made again.
  const auto fixed = static_cast<std::size_t>(c.first_contact_plan);
  const bool fixed_same =
      !same && same_size && state.coupling_start.size() > fixed &&
      std::equal(starts.begin(), starts.begin() + static_cast<std::ptrdiff_t>(fixed) + 1,
                 state.coupling_start.begin()) &&
      std::equal(flat.begin(), flat.begin() + starts[fixed], state.coupling_dofs.begin());
  const std::size_t first_new = fixed_same ? fixed : 0;
  bool planned = false; // new plans in the last pattern
  if (!same && same_size) {
    state.stiffness->truncate_plans(static_cast<int>(first_new));
    planned = true;
    for (std::size_t k = first_new; k + 1 < starts.size() && planned; ++k)
      planned = plan_coupling(*state.stiffness, c, k, first_new) >= 0;
  }
  if (planned) {
    state.coupling_start = starts;
    state.coupling_dofs = flat;
    ++counters.plan_rebuilds;
    return false;
  }
  if (same)
    return false;
  SparsityBuilder builder(n_reduced);
  builder.reserve(starts.size() - 1, flat.size());
  for (std::size_t k = 0; k + 1 < starts.size(); ++k)
    builder.add(c.coupling(k));
  state.pattern = builder.build();
  state.stiffness = std::make_unique<Assembler>(state.pattern);
  for (std::size_t k = 0; k + 1 < starts.size(); ++k) {
    const int id = plan_coupling(*state.stiffness, c, k, 0);
    NMM_ASSERT(id >= 0, "every coupling is in the pattern built from them");
  }
  state.coupling_start = starts;
  state.coupling_dofs = flat;
  state.pattern_start = starts;
  state.pattern_dofs = flat;
  ++counters.pattern_builds;
  return true;
}

/// Workspaces of the element loop: the same size element after element, so no allocation
/// in the loop.
struct ElementWork {
  Eigen::MatrixXd local;
  Eigen::VectorXd loads;
  Eigen::VectorXd velocity;
  Eigen::VectorXd inertia_load;
  Eigen::VectorXd stress_load;
};

/// Adds element @p e's stiffness, body forces and initial-stress load, and with the mass its
/// inertia 2 M / dt² and inertia load 2 M v0 / dt (Shi eq. 2.22-2.23), from one set of
/// moments.
void assemble_element(const StepContext& context,
                      int e,
                      double dt,
                      StepSystemState& state,
                      StepSystem& system,
                      ElementWork& work) {
  const Model& model = context.model;
  const ModelElement& element = model.elements[at(e)];
  const ElasticMaterial& material = model.material_of(e);
  const ElementShape shape = model.shape(e);
  const ElementIntegrals integrals(shape, element.polygons);
  const std::span<const int> dofs = model.element_dofs(e);
  const double t1 = context.time + dt;
  integrals.stiffness(elasticity_matrix(material), material.thickness_factor(), work.local);
  element_load(model, e, integrals, context.scene.body_loads, t1, work.loads);
  // The carried stresses' part of the loads, not external work (the energy balance).
  Eigen::VectorXd& stress_load = work.stress_load;
  integrals.loads(Point2::Zero(), element.stress, material.thickness_factor(), stress_load);
  integrals.add_stabilisation_load(element.stabilisation_force, stress_load);
  if (element.excavated) {
    // Only what is left of its loads, on its covers; no stiffness, no mass.
    work.loads *= element.release;
    stress_load *= element.release;
    work.local.setZero();
  }
  for (std::size_t i = 0; i < dofs.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    system.f(dofs[i]) += work.loads(k);
    system.loads(dofs[i]) += work.loads(k);
    system.external(dofs[i]) += work.loads(k) - stress_load(k);
  }
  if (context.kind.with_mass) {
    const double inertia = 2.0 / (dt * dt);
    ElementMass& mass = state.element_mass[at(e)];
    integrals.mass(element.excavated ? 0.0 : material.density * material.thickness_factor(), mass);
    mass.add_to(work.local, inertia);
    model.element_values(e, context.velocity, work.velocity);
    mass.times(work.velocity, work.inertia_load);
    for (std::size_t i = 0; i < dofs.size(); ++i)
      system.f(dofs[i]) += (2.0 / dt) * work.inertia_load(static_cast<Eigen::Index>(i));
  }
  system.scatter(*state.stiffness, e, work.local, system.couplings.transform_of[at(e)]);
}

/// The bolts' bars (bar_spring()): their stiffness into @p a, their forces into the loads.
void assemble_bolts(const StepContext& context, Assembler& a, StepSystem& system) {
  const StepCouplings& couplings = system.couplings;
  Eigen::MatrixXd stiffness;
  Eigen::VectorXd load;
  std::size_t j = 0;
  for (const Bolt& bolt : context.scene.bolts) {
    for (const BoltBar& bar : bolt.bars) {
      const std::span<const int> dofs = couplings.bar_unknowns(j);
      bar_spring(context.model, bolt, bar, dofs, stiffness, load);
      for (std::size_t i = 0; i < dofs.size(); ++i)
        system.f(dofs[i]) += load(static_cast<Eigen::Index>(i));
      system.scatter(a, couplings.first_bar_plan + static_cast<int>(j), stiffness,
                     couplings.bar_transform[j]);
      ++j;
    }
  }
}

/// The loads of the end of the step, the elements, the penalty supports and the bolts, into the
/// state's assembler and @p system's loads.
void assemble_step(const StepContext& context,
                   double dt,
                   StepSystemState& state,
                   StepSystem& system) {
  const Model& model = context.model;
  const Scene& scene = context.scene;
  const double t1 = context.time + dt;
  Assembler& a = *state.stiffness;
  a.zero();
  // Loads of the end of the step (point and curve loads here, body forces and initial
  // stresses per element).
  system.f = Eigen::VectorXd::Zero(model.n_dofs());
  for (const PointLoad& load : scene.point_loads)
    add_point_load(model, load, t1, system.f);
  for (const CurveLoad& load : scene.curve_loads)
    add_curve_load(model, load, t1, system.f);
  system.loads = system.f;
  system.external = system.f;
  system.rhs_correction = Eigen::VectorXd::Zero(system.map->n_reduced());
  if (context.kind.with_mass)
    state.element_mass.resize(model.elements.size());
  ElementWork work;
  for (int e = 0; e < model.n_elements(); ++e)
    assemble_element(context, e, dt, state, system, work);
  const std::vector<int>& spring_of = system.couplings.spring_of;
  for (std::size_t s = 0; s < spring_of.size(); ++s) {
    const SupportPoint& support = scene.supports[at(spring_of[s])];
    const SupportSpring spring =
        support_spring(model, support, context.options.spring_stiffness, t1);
    const std::span<const int> dofs = model.element_dofs(support.point.element);
    for (std::size_t i = 0; i < dofs.size(); ++i)
      system.f(dofs[i]) += spring.load(static_cast<Eigen::Index>(i));
    system.scatter(a, static_cast<int>(model.elements.size() + s), spring.stiffness,
                   system.couplings.transform_of[at(support.point.element)]);
  }
  assemble_bolts(context, a, system);
}

} // namespace

void StepSystem::scatter(Assembler& a, int plan, const Eigen::MatrixXd& local, int transform) {
  if (transform < 0) {
    a.add(plan, local);
    return;
  }
  const Reduction& r = couplings.transforms[at(transform)];
  a.add(plan, r.transform.transpose() * local * r.transform);
  if (!r.constant.isZero()) {
    const Eigen::VectorXd correction = r.transform.transpose() * (local * r.constant);
    for (std::size_t j = 0; j < r.reduced.size(); ++j)
      rhs_correction(r.reduced[j]) -= correction(static_cast<Eigen::Index>(j));
  }
}

StepSystem
build_step_system(const StepContext& context, StepSystemState& state, double dt, StepClock& clock) {
  StepSystem system;
  state.map = make_step_map(context, state, context.time + dt);
  system.map = state.map;
  system.couplings = make_couplings(context, *system.map, state.coupling_dofs.size());
  clock.lap(context.counters.seconds_constraints);
  system.rebuilt =
      update_pattern(state, system.couplings, system.map->n_reduced(), context.counters);
  clock.lap(context.counters.seconds_pattern);
  assemble_step(context, dt, state, system);
  clock.lap(context.counters.seconds_assembly);
  return system;
}

void StepSystemState::save_state(StateWriter& out) const {
  // The last step's slaves: the next step's elimination prefers them (DofMap's previous).
  std::vector<int> slaves;
  if (map) {
    for (int raw = 0; raw < map->n_raw(); ++raw) {
      if (map->is_slave(raw))
        slaves.push_back(raw);
    }
  }
  out.put(map != nullptr);
  out.put(slaves);
  out.put(stiffness != nullptr);
  if (stiffness) {
    out.put(static_cast<std::int64_t>(pattern.n_dofs()));
    out.put(pattern_start);
    out.put(pattern_dofs);
    out.put(coupling_start);
    out.put(coupling_dofs);
  }
}

void StepSystemState::load_state(StateReader& in, int n_dofs) {
  const bool had_map = in.boolean();
  const std::vector<int> slaves = in.integers();
  map.reset();
  if (had_map) {
    // A map whose only use is to be the next step's "previous": each saved slave is the
    // preferred pivot of a row of its own, so exactly those are slaves.
    std::vector<LinearConstraint> rows;
    rows.reserve(slaves.size());
    for (const int raw : slaves) {
      if (raw < 0 || raw >= n_dofs)
        in.fail("a slave unknown " + std::to_string(raw) + " of " + std::to_string(n_dofs));
      rows.push_back(LinearConstraint{{{raw, 1.0}}, 0.0, raw, "restart"});
    }
    map = std::make_shared<const DofMap>(n_dofs, rows);
  }
  stiffness.reset();
  analysed = false;
  if (in.boolean()) {
    const std::int64_t n = in.integer();
    pattern_start = in.integers();
    pattern_dofs = in.integers();
    coupling_start = in.integers();
    coupling_dofs = in.integers();
    auto check = [&](const std::vector<int>& starts, const std::vector<int>& dofs) {
      if (starts.empty() || starts.front() != 0 || !std::is_sorted(starts.begin(), starts.end()) ||
          starts.back() != static_cast<int>(dofs.size()))
        in.fail("the couplings of the sparsity pattern are inconsistent");
      for (const int d : dofs) {
        if (d < -1 || d >= n)
          in.fail("the couplings of the sparsity pattern are inconsistent");
      }
    };
    check(pattern_start, pattern_dofs);
    check(coupling_start, coupling_dofs);
    SparsityBuilder builder(static_cast<int>(n));
    for (std::size_t k = 0; k + 1 < pattern_start.size(); ++k)
      builder.add(std::span<const int>(pattern_dofs.data() + pattern_start[k],
                                       at(pattern_start[k + 1] - pattern_start[k])));
    pattern = builder.build();
    stiffness = std::make_unique<Assembler>(pattern);
    for (std::size_t k = 0; k + 1 < coupling_start.size(); ++k) {
      const std::span<const int> dofs(coupling_dofs.data() + coupling_start[k],
                                      at(coupling_start[k + 1] - coupling_start[k]));
      for (const int i : dofs) {
        for (const int j : dofs) {
          if (i >= 0 && j >= i && !pattern.contains(i, j))
            in.fail("a coupling lies outside the sparsity pattern");
        }
      }
      (void)stiffness->plan(dofs);
    }
  }
}

} // namespace nmm
