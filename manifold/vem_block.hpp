// SPDX-License-Identifier: MIT
// manifold/vem_block.hpp — a VEM block (the VEM-DDA paper, Luo et al. 2021, sections 3-4):
// every vertex of the block is a cover with its own displacement (2 unknowns), the element is
// the whole block; the displacement is linear along each edge and virtual inside. Matrices
// come from the projection Pi_P on the linear fields (eq. 32-41) plus the trace-scaled
// stabilisation (eq. 46-58); body force and initial stress through the projection (eq.
// 60-63). Works for any simple polygon with holes, concave ones included (only boundary
// integrals and moments of the polygon are used).
#pragma once

#include "manifold/nmm_element.hpp"
#include "mesh/geometry.hpp"

#include <Eigen/Core>

#include <span>
#include <vector>

namespace nmm {

/// Kinematics of a VEM block at its current vertices.
class VemShape {
public:
  /// @param polygons  the block: its outer loop counter-clockwise, holes clockwise. Its
  ///                  vertices in that order (outer, then each hole) are the element's
  ///                  covers; local unknowns 2 i and 2 i + 1 are u and v of vertex i.
  explicit VemShape(std::span<const Polygon> polygons);

  [[nodiscard]] int n_vertices() const noexcept { return static_cast<int>(vertices_.size()); }
  [[nodiscard]] int n_dofs() const noexcept { return 2 * n_vertices(); }
  [[nodiscard]] const std::vector<Point2>& vertices() const noexcept { return vertices_; }
  /// The vertex after @p vertex along its loop (the block's edges are vertex -> next).
  [[nodiscard]] int next(int vertex) const noexcept {
    return next_[static_cast<std::size_t>(vertex)];
  }
  /// x*: the mean of the vertices, origin of the projection (eq. 32).
  [[nodiscard]] const Point2& origin() const noexcept { return origin_; }
  /// Area S of the block.
  [[nodiscard]] double area() const noexcept { return area_; }
  /// H (eq. 38): the DDA unknowns (u*, v*, r0, ex, ey, gxy) of Pi_P u from the vertex values.
  [[nodiscard]] const Eigen::MatrixXd& projector() const noexcept { return projector_; }

  /// The interpolation at @p x: on the boundary (within 1e-9 of the block's size of an edge)
  /// the linear interpolation between the edge's two vertices, which is exact; inside, the
  /// projection T*(x) H (the virtual field itself is not known there).
  [[nodiscard]] Eigen::Matrix<double, 2, Eigen::Dynamic> interpolation_at(const Point2& x) const;
  /// The interpolation at @p x on the line of the block's boundary edge @p a -> @p b, on
  /// the edge's two vertices: @p columns gets their u and v (local indices) and @p out the
  /// linear weights (1 - s, s), s = (x - a).(b - a) / |b - a|². On the edge that is
  /// interpolation_at(x), exactly; past its ends the edge's line (a contact's shear anchor
  /// that has slid past the end of its edge). A contact on the block so couples 4 of its 2n
  /// unknowns, the same 4 wherever its points move along the edge in a step.
  void interpolation_on_edge(const Point2& x,
                             const Point2& a,
                             const Point2& b,
                             Eigen::Matrix<double, 2, Eigen::Dynamic>& out,
                             std::vector<int>& columns) const;
  [[nodiscard]] Point2 displacement_at(const Point2& x, std::span<const double> d) const;
  /// The constant strain of Pi_P u (eq. 40): P_c d.
  [[nodiscard]] LinearField3 strain(std::span<const double> d) const;
  /// The rotation r0 of Pi_P u.
  [[nodiscard]] double rotation(std::span<const double> d) const;
  /// P_u (eq. 50): Pi_P u at the vertices, T*(x_i) H; 2n x 2n. It reproduces every linear
  /// field and is a projector (P_u² = P_u), so I - P_u vanishes exactly on linear fields.
  [[nodiscard]] Eigen::MatrixXd vertex_projection() const;
  /// S t P_c^T D P_c (eq. 48): the consistency part of the stiffness, for @p elasticity D
  /// and @p thickness t; 2n x 2n.
  [[nodiscard]] Eigen::MatrixXd consistency_stiffness(const Eigen::Matrix3d& elasticity,
                                                      double thickness) const;
  /// The stabilisation's vertex forces of the step displacement @p d:
  /// eta_E (I - P_u)^T (I - P_u) d (eq. 49), eta_E of eq. 52 with the elasticity matrix
  /// @p elasticity times @p thickness, as VemIntegrals::stiffness(); 2n values. The step
  /// adds them to the block's carried stabilisation force (docs/formulation.md, "VEM
  /// block").
  [[nodiscard]] Eigen::VectorXd stabilisation_force(const Eigen::Matrix3d& elasticity,
                                                    double thickness,
                                                    std::span<const double> d) const;

private:
  std::vector<Point2> vertices_;
  /// Next vertex along its loop, for each vertex.
  std::vector<int> next_;
  Point2 origin_ = Point2::Zero();
  double area_ = 0.0;
  double size_ = 0.0;
  Eigen::MatrixXd projector_; ///< 6 x 2n
};

/// Element integrals of a VEM block.
class VemIntegrals {
public:
  VemIntegrals(const VemShape& shape, std::span<const Polygon> polygons);
  [[nodiscard]] double area() const noexcept { return shape_.area(); }
  /// S P_c^T D P_c + eta_E (I - P_u)^T (I - P_u), eta_E equating the traces (eq. 48-53).
  [[nodiscard]] Eigen::MatrixXd stiffness(const Eigen::Matrix3d& d, double thickness) const;
  /// rho H^T P_m H + eta_M (I - P_u)^T (I - P_u) (eq. 54-57, without 2/dt²).
  [[nodiscard]] Eigen::MatrixXd mass(double density_thickness) const;
  /// H^T ∫ T*^T b (eq. 61-63).
  [[nodiscard]] Eigen::VectorXd body_force(const Point2& force, double thickness) const;
  /// -S P_c^T sigma0 (eq. 60), sigma0 the mean of the stress field over the block; for a
  /// field with a linear part (an `[in_situ]` stress growing with depth) -∫ eps(v) : sigma
  /// by parts instead: the boundary integral of v . sigma n exactly, the interior one of
  /// v . div sigma through the projection, as the body force.
  [[nodiscard]] Eigen::VectorXd initial_stress_load(const LinearField3& stress,
                                                    double thickness) const;
  /// The load of a carried stabilisation force @p carried (2n vertex forces): -(I - P_u)^T
  /// f, as the initial stress gives -S P_c^T sigma0 (eq. 60). (I - P_u)^T keeps the part
  /// that does no work on the linear fields of the current shape: the load has no resultant,
  /// no moment and does not load the constant strain.
  [[nodiscard]] Eigen::VectorXd stabilisation_load(const Eigen::VectorXd& carried) const;

private:
  /// initial_stress_load() of a stress field with a linear part.
  [[nodiscard]] Eigen::VectorXd linear_stress_load(const LinearField3& stress,
                                                   double thickness) const;

  const VemShape& shape_;
  /// I - P_u, (I - P_u)^T (I - P_u) and trace(P_u^T P_u) (eq. 49-50).
  Eigen::MatrixXd residual_;
  Eigen::MatrixXd stabilisation_;
  double projection_trace_ = 0.0;
  Eigen::Matrix<double, 6, 6> basis_mass_; ///< P_m (eq. 56)
  Eigen::Matrix<double, 2, 6> basis_mean_; ///< ∫ T*
  Eigen::Vector2d first_ = Eigen::Vector2d::Zero();
};

} // namespace nmm
