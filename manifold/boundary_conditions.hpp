// SPDX-License-Identifier: MIT
// manifold/boundary_conditions.hpp — supports and loads of a model: fixed points by exact
// constraints or by Shi's stiff springs (1997, eq. 2.26-2.27), point loads (eq. 2.11-2.12),
// body forces (eq. 2.13-2.14), tractions and pressures on curves.
#pragma once

#include "manifold/linear_constraint.hpp"
#include "manifold/model.hpp"

#include <Eigen/Core>

#include <functional>
#include <span>
#include <string>
#include <vector>

namespace nmm {

/// How a support holds its points.
enum class SupportMethod {
  exact,  ///< the displacement is eliminated exactly (DofMap); the default
  penalty ///< Shi's two stiff springs per point, stiffness SupportSet::spring_stiffness
};

/// Linear ramp of a load or an imposed displacement: 0 before start, linear to 1 at end,
/// 1 after (s).
struct Ramp {
  double start = 0.0;
  double end = 0.0;
  [[nodiscard]] double at(double time) const noexcept {
    if (time >= end)
      return 1.0;
    if (time <= start)
      return 0.0;
    return (time - start) / (end - start);
  }
};

/// A material point held in x, y or both, at zero displacement or at an imposed one.
struct SupportPoint {
  MaterialPoint point;
  bool fix_x = false;
  bool fix_y = false;
  SupportMethod method = SupportMethod::exact;
  std::string origin; ///< "curve \"base\"" or "point \"anchor\"", for messages
  /// Where the point was at the start: the imposed displacement is measured from here.
  Point2 start = Point2::Zero();
  /// Imposed total displacement of the held components (m), reached along `ramp`.
  Point2 displacement = Point2::Zero();
  Ramp ramp;
};

/// Gravity or any uniform acceleration field acting on every element, m/s².
struct BodyLoad {
  Point2 acceleration = Point2::Zero();
  Ramp ramp;
};

/// A force on a material point, N (per metre of thickness in plane strain).
struct PointLoad {
  MaterialPoint point;
  Point2 force = Point2::Zero();
  Ramp ramp;
  /// A factor on the ramp's: the contact forces an excavation takes off the material left
  /// fall from 1 to 0 over its stage (TimeStepper::set_contact_release()); 1 for the rest.
  double scale = 1.0;
};

/// A traction (Pa, vector) or a pressure (Pa, positive pushing into the material) on a named
/// curve; applied to the material side of each piece (the left one where both sides are
/// material: a bonded line). Either may vary along the curve.
struct CurveLoad {
  int curve = -1;
  bool is_pressure = false;
  Point2 traction = Point2::Zero();
  double pressure = 0.0;
  Ramp ramp;
  /// Optional traction field added to `traction` (Pa), evaluated at the current position.
  std::function<Point2(const Point2&)> traction_at;
  /// Optional pressure field added to `pressure` (Pa), evaluated at the current position
  /// (e.g. water pressure growing with depth).
  std::function<double(const Point2&)> pressure_at;
};

/// The support points of named curve @p curve: the ends of every piece (and its mid-point
/// for order-1 covers, where the displacement along a piece is quadratic), on each material
/// side, so that the whole curve is held: with exact elimination the displacement is zero
/// along every piece, not only at points.
[[nodiscard]] std::vector<SupportPoint> curve_support_points(const Model& model,
                                                             int curve,
                                                             bool fix_x,
                                                             bool fix_y,
                                                             SupportMethod method,
                                                             const std::string& origin);

/// Constraint rows of the exact supports for a step ending at @p time (one per held
/// component and point; none for a point of excavated material, ModelElement::excavated): the step
/// displacement of the point is what remains of its imposed displacement, ramp(time) u_imposed - (x
/// - x_start), so that a held point never drifts.
[[nodiscard]] std::vector<LinearConstraint>
support_constraints(const Model& model, const std::vector<SupportPoint>& supports, double time);

/// Puts the held components of every exact support point where its support holds them at
/// @p time, start + ramp(time) u_imposed, after a step moved the point with the material.
/// A point whose row DofMap eliminated is there already, to rounding. A point whose row was
/// a combination of the rows before it to rounding (order-1 covers: more points on a held
/// curve than the cover functions have freedoms along it) moved by what the other rows left
/// of it, up to 1e-8 of the step; kept, that motion would add up from step to step, and in
/// the step in which the row counts as independent again its pivot, of the same small size,
/// would turn it into a jump of the unknowns (the ramp of examples/03 at order 1 jacked the
/// block off after 95 steps). Penalty supports are not moved: their springs hold them.
void hold_supported_points(std::vector<SupportPoint>& supports, double time);

/// A penalty support point on its element's raw unknowns (Shi eq. 2.27).
struct SupportSpring {
  Eigen::MatrixXd stiffness; ///< stiffness (Tx^T Tx and/or Ty^T Ty)
  /// The load pulling the point towards its imposed displacement at the time asked for:
  /// stiffness T^T (ramp(time) u_imposed - (x - x_start)) on the held components.
  Eigen::VectorXd load;
};
[[nodiscard]] SupportSpring
support_spring(const Model& model, const SupportPoint& support, double stiffness, double time);

/// The local load vector of element @p element at time @p time from its integrals, into
/// @p out: every body load (Shi eq. 2.14, density times acceleration) and its initial-stress
/// load -∫ B^T sigma0 (eq. 2.10).
void element_load(const Model& model,
                  int element,
                  const ElementIntegrals& integrals,
                  std::span<const BodyLoad> body_loads,
                  double time,
                  Eigen::VectorXd& out);

/// Adds a point or curve load at time @p time to the raw load vector @p f.
void add_point_load(const Model& model, const PointLoad& load, double time, Eigen::VectorXd& f);
void add_curve_load(const Model& model, const CurveLoad& load, double time, Eigen::VectorXd& f);

} // namespace nmm
