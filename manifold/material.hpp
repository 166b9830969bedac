// SPDX-License-Identifier: MIT
// manifold/material.hpp — linear elastic material of a region (Shi 1997, eq. 2.1).
#pragma once

#include <Eigen/Core>

#include <string>

namespace nmm {

/// Plane strain (thick bodies: dams, slopes, tunnels; per metre of thickness) or plane
/// stress (thin plates; integrated over `thickness`).
enum class PlaneCondition { strain, stress };

/// The elastic constants and density of one material region, SI units.
struct ElasticMaterial {
  std::string name;
  double young = 0.0;   ///< Pa, > 0
  double poisson = 0.0; ///< -1 < nu < 0.5
  double density = 0.0; ///< kg/m³, >= 0 (0 only in static analyses without gravity)
  PlaneCondition plane = PlaneCondition::strain;
  double thickness = 1.0; ///< m; plane stress only (plane strain is per metre)
  /// Stress at the start of the analysis (sxx, syy, sxy), Pa, e.g. an in-situ stress: at the
  /// height initial_stress_surface, and everywhere when initial_stress_gradient is zero.
  Eigen::Vector3d initial_stress = Eigen::Vector3d::Zero();
  /// Growth of the initial stress per metre of depth below initial_stress_surface, Pa/m
  /// (sxx, syy, sxy; compression negative): the case file's `[in_situ]` field,
  /// sigma(y) = initial_stress + initial_stress_gradient (initial_stress_surface - y).
  /// Zero (the default): the initial stress is uniform.
  Eigen::Vector3d initial_stress_gradient = Eigen::Vector3d::Zero();
  /// The height (a y coordinate, m) at which the initial stress is `initial_stress`.
  double initial_stress_surface = 0.0;
  /// NMM and VEM blocks: turn each block's geometry and velocities by the step's rotation
  /// exactly (Model::turn_exactly), as DDA blocks always do, instead of moving the covers or
  /// vertices by their linear displacement (which keeps a contact's penetration in the
  /// equations that of the moved geometry, but makes a spinning block grow). Off by default.
  bool exact_rotation = false;

  /// The initial stress at the height @p y, Pa (exactly `initial_stress` when it is uniform).
  [[nodiscard]] Eigen::Vector3d initial_stress_at(double y) const {
    if (initial_stress_gradient.isZero())
      return initial_stress;
    return initial_stress + initial_stress_gradient * (initial_stress_surface - y);
  }

  /// The factor every area integral is multiplied by: thickness for plane stress, 1 m for
  /// plane strain.
  [[nodiscard]] double thickness_factor() const noexcept {
    return plane == PlaneCondition::stress ? thickness : 1.0;
  }
};

/// The 3x3 matrix D with (sxx, syy, sxy) = D (exx, eyy, gxy): Shi's eq. 2.1 for plane
/// stress; for plane strain E/((1+nu)(1-2nu)) [[1-nu, nu, 0], [nu, 1-nu, 0], [0, 0, (1-2nu)/2]].
/// @pre validate_material() passed.
[[nodiscard]] Eigen::Matrix3d elasticity_matrix(const ElasticMaterial& material);

/// Checks E > 0, -1 < nu < 0.5 (also for plane stress: nu = 0.5 would make the plate
/// incompressible and the penalty-contact conditioning meaningless), density >= 0,
/// thickness > 0, all finite. @throws InputError naming the material.
void validate_material(const ElasticMaterial& material);

} // namespace nmm
