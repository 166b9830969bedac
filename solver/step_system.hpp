// SPDX-License-Identifier: MIT
// solver/step_system.hpp — the linear system of one try of a time step: the constraints and
// the reduction of every coupling (elements, penalty supports, contact points) to the free
// unknowns, the sparsity pattern and scatter plans kept from step to step, and the assembly
// of K + 2M/dt² and its loads (Shi 1997, eq. 2.17-2.25).
#pragma once

#include "manifold/element.hpp"
#include "manifold/linear_constraint.hpp"
#include "mesh/state_archive.hpp"
#include "solver/assembler.hpp"
#include "solver/dof_map.hpp"
#include "solver/sparsity.hpp"
#include "solver/step_context.hpp"

#include <Eigen/Core>

#include <memory>
#include <span>
#include <vector>

namespace nmm {

/// The reduction of a coupling whose unknowns are not all free: d_local = T z + t0.
struct Reduction {
  std::vector<int> reduced;  ///< reduced unknowns z, sorted
  Eigen::MatrixXd transform; ///< local x reduced.size()
  Eigen::VectorXd constant;  ///< t0
};

/// The reduced unknowns of every coupling of a try: the elements, then the penalty supports
/// (the same unknowns as their element), then the bolts' bars (those of the elements of
/// their ends), then the contact points found at the start of the step. Only couplings
/// with slaves get a transform.
struct StepCouplings {
  /// Coupling k couples flat[starts[k]...starts[k + 1]).
  std::vector<int> starts{0};
  std::vector<int> flat;
  std::vector<int> transform_of; ///< element -> index in transforms, -1: all free
  std::vector<Reduction> transforms;
  std::vector<int> spring_of; ///< support index of each penalty coupling
  /// The raw unknowns of bar j (the scene's bolts' bars in order):
  /// bar_dofs[bar_start[j]...bar_start[j + 1]).
  std::vector<int> bar_dofs;
  std::vector<int> bar_start{0};
  std::vector<int> bar_transform; ///< bar -> index in transforms, -1: all free
  int first_bar_plan = 0;         ///< the plan (and coupling) of bar 0
  /// The raw unknowns of contact point i: contact_dofs[contact_start[i]...contact_start[i + 1]).
  std::vector<int> contact_dofs;
  std::vector<int> contact_start{0};
  std::vector<int> contact_transform; ///< contact point -> index in transforms, -1: all free
  int first_contact_plan = 0;         ///< the plan (and coupling) of contact point 0

  [[nodiscard]] std::span<const int> coupling(std::size_t k) const {
    return {flat.data() + starts[k], static_cast<std::size_t>(starts[k + 1] - starts[k])};
  }
  [[nodiscard]] std::span<const int> bar_unknowns(std::size_t j) const {
    return {bar_dofs.data() + bar_start[j],
            static_cast<std::size_t>(bar_start[j + 1] - bar_start[j])};
  }
  [[nodiscard]] std::span<const int> contact_point_dofs(int i) const {
    const auto k = static_cast<std::size_t>(i);
    return {contact_dofs.data() + contact_start[k],
            static_cast<std::size_t>(contact_start[k + 1] - contact_start[k])};
  }
};

/// What the step systems keep from step to step.
struct StepSystemState {
  std::vector<LinearConstraint> dependencies; ///< order-1 fixes, chosen once
  /// Of the last step (or try): the next one keeps its slaves where they still may be.
  std::shared_ptr<const DofMap> map;
  SparsityPattern pattern;
  std::unique_ptr<Assembler> stiffness;
  /// Consistent mass of every element (times density and thickness), kept from the assembly
  /// for the kinetic energy of the new velocities.
  std::vector<ElementMass> element_mass;
  /// Reduced unknowns of every coupling, flat, with their starts: what the current plans
  /// were made for, compared to the next step's.
  std::vector<int> coupling_start;
  std::vector<int> coupling_dofs;
  /// The couplings the sparsity pattern was built from (the plans may have changed since
  /// within it), for a restart checkpoint: the restored run rebuilds the same pattern, so
  /// the same ordering and factor.
  std::vector<int> pattern_start;
  std::vector<int> pattern_dofs;
  bool analysed = false; ///< the solver has the symbolic analysis of the pattern

  /// Writes the last map's slaves and the couplings of the pattern and of the plans, for a
  /// restart checkpoint (TimeStepper::save_state()).
  void save_state(StateWriter& out) const;
  /// Reads what save_state() wrote: a map with the same slaves (to be the next step's
  /// previous), the same pattern and plans, to be analysed again. @p n_dofs: raw unknowns
  /// of the model. @throws InputError when they are inconsistent.
  void load_state(StateReader& in, int n_dofs);
};

/// The linear system of one try: its map, couplings and loads, the matrix being in the
/// state's assembler.
struct StepSystem {
  std::shared_ptr<const DofMap> map;
  StepCouplings couplings;
  /// Loads of the end of the step with the inertia load 2M v0/dt and the supports' springs,
  /// raw unknowns; the contacts' are added per open-close iteration.
  Eigen::VectorXd f;
  /// The loads alone (point and curve loads, body forces, initial stresses; not the inertia
  /// load): they do the work of the energy check.
  Eigen::VectorXd loads;
  /// Of those, the loads alone without the initial stresses and stabilisation forces (point
  /// and curve loads, body forces): the external work of the energy balance.
  Eigen::VectorXd external;
  /// Right side from the constants t0 of the reductions, reduced unknowns.
  Eigen::VectorXd rhs_correction;
  bool rebuilt = false; ///< the pattern was built for this try: a new symbolic analysis

  /// Adds @p local of coupling @p plan to @p a, through the reduction @p transform (-1:
  /// its unknowns are all free, the local matrix scatters as it is).
  void scatter(Assembler& a, int plan, const Eigen::MatrixXd& local, int transform);
};

/// Builds the try's system for the time step @p dt: constraints at its end, couplings and
/// their reductions (lap seconds_constraints), the pattern and plans when they changed
/// (seconds_pattern), elements and supports assembled (seconds_assembly).
[[nodiscard]] StepSystem
build_step_system(const StepContext& context, StepSystemState& state, double dt, StepClock& clock);

} // namespace nmm
