// SPDX-License-Identifier: MIT
// manifold/nmm_element.hpp — shape functions and element matrices of a manifold element
// with order-0 or order-1 cover functions (Shi 1997, chapters 2, 4.3-4.5 and 5), every area
// integral exact by simplex integration (chapter 7).
#pragma once

#include "mesh/geometry.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

namespace nmm {

/// Highest supported cover-function order (0: constant, Shi eq. 1.8; 1: linear, eq. 1.9).
inline constexpr int max_cover_order = 1;

/// Scalar basis functions per cover: 1 for order 0, 3 (1, x, y) for order 1.
[[nodiscard]] constexpr int cover_basis_size(int order) noexcept { return order == 0 ? 1 : 3; }

/// Unknowns per cover, 2 m, in Shi's order d1..d2m: (u, v) of each basis function in turn.
[[nodiscard]] constexpr int cover_dofs(int order) noexcept { return 2 * cover_basis_size(order); }

/// Most scalar shape functions and unknowns of an element (order 1: 3 covers x 3 functions).
inline constexpr int max_element_shapes = 9;
inline constexpr int max_element_dofs = 2 * max_element_shapes;

/// Element-sized matrices and vectors, sized at run time up to the maximum, never on the
/// heap: element work runs for every element every step (bench/step_bench.cpp).
using ElementMatrix = Eigen::Matrix<double,
                                    Eigen::Dynamic,
                                    Eigen::Dynamic,
                                    Eigen::ColMajor,
                                    max_element_dofs,
                                    max_element_dofs>;
using ElementVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, max_element_dofs, 1>;
using ElementDofs = Eigen::Matrix<int, Eigen::Dynamic, 1, Eigen::ColMajor, max_element_dofs, 1>;
using ShapeVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, Eigen::ColMajor, max_element_shapes, 1>;
using ShapeMatrix = Eigen::Matrix<double,
                                  Eigen::Dynamic,
                                  Eigen::Dynamic,
                                  Eigen::ColMajor,
                                  max_element_shapes,
                                  max_element_shapes>;
using InterpolationMatrix =
    Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::ColMajor, 2, max_element_dofs>;
using ShapeCoefficients =
    Eigen::Matrix<double, 6, Eigen::Dynamic, Eigen::ColMajor, 6, max_element_shapes>;
using GradientCoefficients =
    Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::ColMajor, 3, max_element_shapes>;

/// A linear field of three components (a stress or a strain) over an element:
/// component i = c(i,0) + c(i,1) (x - origin.x) + c(i,2) (y - origin.y), i = xx, yy, xy.
struct LinearField3 {
  Point2 origin = Point2::Zero();
  Eigen::Matrix3d coefficients = Eigen::Matrix3d::Zero();

  /// The three components at @p x.
  [[nodiscard]] Eigen::Vector3d at(const Point2& x) const {
    const Point2 d = x - origin;
    return coefficients.col(0) + coefficients.col(1) * d.x() + coefficients.col(2) * d.y();
  }
  /// The same field about another origin.
  [[nodiscard]] LinearField3 about(const Point2& new_origin) const;
};

/// Shape functions of one manifold element: phi_a = w_k s_{k,j}, a = m k + j, where w_k is
/// the k-th barycentric coordinate of the element's triangle (Shi eq. 4.7-4.11) and s_{k,j}
/// the j-th basis function of cover k about that cover's position, scaled by `scale`
/// (1, (x - x_k)/L, (y - y_k)/L). The unknowns are ordered a-major, u before v:
/// local dof 2a is u of phi_a, 2a + 1 is v of phi_a; so each cover's 2m dofs are contiguous.
///
/// The polynomials are held in local coordinates about the triangle's centroid so that an
/// element far from the origin keeps its accuracy.
class NmmShape {
public:
  /// @param vertices  the element's triangle, counter-clockwise: the current positions of
  ///                  its three covers (the element's own copy of its math triangle).
  /// @param order     cover-function order, 0 or 1.
  /// @param scale     length L scaling the order-1 basis (the math mesh size).
  NmmShape(const std::array<Point2, 3>& vertices, int order, double scale);

  [[nodiscard]] int order() const noexcept { return order_; }
  /// Number of scalar shape functions, 3 m.
  [[nodiscard]] int n_shapes() const noexcept { return static_cast<int>(values_.cols()); }
  /// Number of element unknowns, 6 m.
  [[nodiscard]] int n_dofs() const noexcept { return 2 * n_shapes(); }
  [[nodiscard]] const Point2& origin() const noexcept { return origin_; }

  /// Shape function values at @p x (length n_shapes()).
  [[nodiscard]] ShapeVector values_at(const Point2& x) const;
  /// The 2 x n_dofs() interpolation matrix T(x) of Shi eq. 2.2: (u, v) = T(x) d.
  [[nodiscard]] InterpolationMatrix interpolation_at(const Point2& x) const;
  /// The strain field exx, eyy, gxy of the local unknowns @p dofs (Shi eq. 2.3-2.5); linear
  /// for order 1, constant for order 0.
  [[nodiscard]] LinearField3 strain(std::span<const double> dofs) const;
  /// The displacement at @p x of the local unknowns @p dofs.
  [[nodiscard]] Point2 displacement_at(const Point2& x, std::span<const double> dofs) const;

  /// Coefficients (monomials 1, X, Y, X², XY, Y² in local coordinates) of every shape
  /// function, one column each.
  [[nodiscard]] const ShapeCoefficients& values() const { return values_; }
  /// Coefficients (1, X, Y) of the x and y derivatives.
  [[nodiscard]] const GradientCoefficients& dx() const { return dx_; }
  [[nodiscard]] const GradientCoefficients& dy() const { return dy_; }

private:
  int order_ = 0;
  Point2 origin_ = Point2::Zero();
  ShapeCoefficients values_;
  GradientCoefficients dx_;
  GradientCoefficients dy_;
};

/// Area integrals of one element: stiffness, mass, body force and initial-stress load, from
/// the moments of its polygons up to degree 2 (order 0) or 4 (order 1), exact.
class NmmElementIntegrals {
public:
  /// @param polygons  the integration domain (the element's atoms), in the same coordinates
  ///                  as the shape's vertices.
  NmmElementIntegrals(const NmmShape& shape, std::span<const Polygon> polygons);

  /// Material area of the element (m²).
  [[nodiscard]] double area() const noexcept { return area_; }

  /// Stiffness ∫ B^T D B (Shi eq. 2.8), times @p thickness.
  [[nodiscard]] ElementMatrix stiffness(const Eigen::Matrix3d& d, double thickness) const;
  /// Consistent mass ∫ T^T T (Shi eq. 2.22 without 2M/Δ²), times @p density_thickness.
  [[nodiscard]] ElementMatrix mass(double density_thickness) const;
  /// The scalar part of the mass (one displacement component), n_shapes() square: the
  /// mass is this matrix on u and the same on v.
  [[nodiscard]] ShapeMatrix scalar_mass(double density_thickness) const;
  /// Body-force load ∫ T^T f (Shi eq. 2.14) for a constant force per volume @p force (N/m³)
  /// times @p thickness.
  [[nodiscard]] ElementVector body_force(const Point2& force, double thickness) const;
  /// Initial-stress load -∫ B^T sigma0 (Shi eq. 2.10) for a linear stress field, times
  /// @p thickness.
  [[nodiscard]] ElementVector initial_stress_load(const LinearField3& stress,
                                                  double thickness) const;

private:
  const NmmShape& shape_;
  double area_ = 0.0;
  Eigen::Matrix<double, 6, 1> first_;  ///< ∫ monomial_i, degree <= 2
  Eigen::Matrix<double, 6, 6> second_; ///< ∫ monomial_i monomial_j, degree <= 2 each
  Eigen::Matrix3d linear_;             ///< ∫ monomial_i monomial_j, degree <= 1 each
};

} // namespace nmm
