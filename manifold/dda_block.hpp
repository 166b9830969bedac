// SPDX-License-Identifier: MIT
// manifold/dda_block.hpp — a DDA block as one special cover (Shi 1997, chapters 1.3 and 2:
// DDA is the totally discontinuous case of the manifold method, one cover per block with
// weight 1): the six-unknown first-order function about the block's centroid, its element
// integrals by simplex integration over the block polygon (concave blocks and holes too), and
// the exact rotation of the geometry update.
#pragma once

#include "manifold/nmm_element.hpp"
#include "mesh/geometry.hpp"

#include <Eigen/Core>

#include <span>

namespace nmm {

/// Unknowns of a DDA block: d = (u0, v0, r0, ex, ey, gxy), the translation of the centroid,
/// the rotation about it and the constant strain.
inline constexpr int dda_block_dofs = 6;

/// The DDA displacement function about @p origin (Shi 1997 chapter 1.3: one cover of weight 1
/// per block with a first-order cover function; in DDA's own unknowns, the VEM-DDA paper's T*,
/// eq. 37):
///   u = T(x) d,  T = [1 0 -Y X 0 Y/2; 0 1 X 0 Y X/2],  (X, Y) = x - origin.
[[nodiscard]] Eigen::Matrix<double, 2, 6> dda_basis(const Point2& origin, const Point2& x);

/// ∫ T^T T over polygons (6 x 6) and ∫ T over polygons (2 x 6) for the DDA basis about
/// @p origin, from the moments of degree <= 2 (exact, simplex integration).
struct DdaMoments {
  double area = 0.0;
  Eigen::Matrix<double, 6, 6> mass = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 2, 6> mean = Eigen::Matrix<double, 2, 6>::Zero();
};
[[nodiscard]] DdaMoments dda_moments(const Point2& origin, std::span<const Polygon> polygons);

/// Kinematics of a DDA block about its centroid.
class DdaShape {
public:
  explicit DdaShape(const Point2& origin) : origin_(origin) {}
  [[nodiscard]] const Point2& origin() const noexcept { return origin_; }
  [[nodiscard]] Eigen::Matrix<double, 2, 6> interpolation_at(const Point2& x) const {
    return dda_basis(origin_, x);
  }
  /// The linear displacement T(x) d used in the equations.
  [[nodiscard]] Point2 displacement_at(const Point2& x, std::span<const double> d) const;
  /// Where the material point at @p x goes: the centroid translates by (u0, v0), the rest
  /// turns about it by exactly r0 and stretches by the strain (DDA's post-adjustment). The
  /// linear T(x) d turns a point by tan r0 and stretches the block by 1/cos r0: a block
  /// spinning at 1 rad/s with dt = 1e-3 s would grow by 1e-6 of its area every step.
  [[nodiscard]] Point2 moved(const Point2& x, std::span<const double> d) const;
  /// The constant strain (ex, ey, gxy).
  [[nodiscard]] LinearField3 strain(std::span<const double> d) const;

private:
  Point2 origin_;
};

/// Element integrals of a DDA block (Shi 1997 chapter 2 with one cover of weight 1).
class DdaIntegrals {
public:
  DdaIntegrals(const DdaShape& shape, std::span<const Polygon> polygons);
  [[nodiscard]] double area() const noexcept { return moments_.area; }
  /// ∫ B^T D B: the area times D on the strain unknowns.
  [[nodiscard]] Eigen::Matrix<double, 6, 6> stiffness(const Eigen::Matrix3d& d,
                                                      double thickness) const;
  /// ∫ T^T T times density and thickness.
  [[nodiscard]] Eigen::Matrix<double, 6, 6> mass(double density_thickness) const;
  /// ∫ T^T f for a constant force per volume.
  [[nodiscard]] Eigen::Matrix<double, 6, 1> body_force(const Point2& force, double thickness) const;
  /// -∫ B^T sigma0 for a linear stress field.
  [[nodiscard]] Eigen::Matrix<double, 6, 1> initial_stress_load(const LinearField3& stress,
                                                                double thickness) const;

private:
  DdaShape shape_;
  DdaMoments moments_;
  Eigen::Vector2d first_ = Eigen::Vector2d::Zero(); ///< ∫ (X, Y)
};

} // namespace nmm
