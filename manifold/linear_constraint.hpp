// SPDX-License-Identifier: MIT
// manifold/linear_constraint.hpp — a linear relation between raw unknowns. The model states
// them (tiny covers, fixed points, order-1 dependencies); solver/dof_map eliminates them.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace nmm {

/// One linear constraint on raw unknowns: sum coefficient_i d_i = value.
struct LinearConstraint {
  std::vector<std::pair<int, double>> terms;
  double value = 0.0;
  /// The raw unknown this constraint should eliminate if it can (e.g. a tiny cover's own
  /// unknown), or -1 to let the elimination pick the largest coefficient.
  int preferred_slave = -1;
  /// What the constraint is, for messages ("fixed curve base at (x, y)").
  std::string origin;
};

} // namespace nmm
