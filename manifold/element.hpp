// SPDX-License-Identifier: MIT
// manifold/element.hpp — the one interface behind which the three kinds of element live
// (DESIGN.md "special covers"): NMM elements (three covers, barycentric weights), DDA blocks
// (one cover, weight 1) and VEM blocks (a cover per vertex, the element is the block).
// Assembly, contact, supports and loads, output and step control see only this: the
// element's unknowns, the displacement at a point, the strain and rotation, where a point
// moves, and the element integrals. The kind is looked at here and nowhere else.
#pragma once

#include "manifold/dda_block.hpp"
#include "manifold/nmm_element.hpp"
#include "manifold/vem_block.hpp"

#include <Eigen/Core>

#include <cstdint>
#include <span>
#include <variant>
#include <vector>

namespace nmm {

/// What kind of cover an element is built on (the `kind` cell array of the output).
enum class ElementKind : std::uint8_t { nmm = 0, dda = 1, vem = 2 };

/// (u, v)(x) = T(x) d_e for the element's local unknowns d_e.
using PointInterpolation = Eigen::Matrix<double, 2, Eigen::Dynamic>;

/// The kinematics of one element at the current geometry.
class ElementShape {
public:
  explicit ElementShape(NmmShape shape) : shape_(std::move(shape)) {}
  explicit ElementShape(DdaShape shape) : shape_(shape) {}
  explicit ElementShape(VemShape shape) : shape_(std::move(shape)) {}

  [[nodiscard]] ElementKind kind() const noexcept {
    return static_cast<ElementKind>(shape_.index());
  }
  /// Number of local unknowns.
  [[nodiscard]] int n_dofs() const;
  /// The point about which strain and stress fields are held: the triangle's centroid
  /// (NMM), the block's centroid (DDA), the mean of the vertices (VEM).
  [[nodiscard]] Point2 origin() const;
  [[nodiscard]] PointInterpolation interpolation_at(const Point2& x) const;
  /// The same into @p out (no allocation when it has the size: contact loops).
  void interpolation_at(const Point2& x, PointInterpolation& out) const;
  /// T(x) for a point @p x on the line of the element's boundary edge @p a -> @p b, on the
  /// unknowns it involves: @p columns gets their local indices and @p out the matching
  /// columns. An NMM element or a DDA block: interpolation_at(x) on all its unknowns. A VEM
  /// block: the edge's two vertices (VemShape::interpolation_on_edge), so that a contact on a
  /// 188-vertex foundation block couples 4 of its 376 unknowns, the same all through a step.
  void interpolation_on_edge(const Point2& x,
                             const Point2& a,
                             const Point2& b,
                             PointInterpolation& out,
                             std::vector<int>& columns) const;
  [[nodiscard]] Point2 displacement_at(const Point2& x, std::span<const double> d) const;
  /// Where the material point at @p x goes with the step displacement @p d: x + T(x) d,
  /// except for DDA blocks, which turn by their rotation exactly (dda_block.hpp).
  [[nodiscard]] Point2 moved(const Point2& x, std::span<const double> d) const;
  /// Strain field of @p d (constant for order 0, DDA and VEM; linear for order 1).
  [[nodiscard]] LinearField3 strain(std::span<const double> d) const;
  /// Rigid rotation of @p d at origin(): (dv/dx - du/dy) / 2.
  [[nodiscard]] double rotation(std::span<const double> d) const;
  /// The NMM shape, or null for a block.
  [[nodiscard]] const NmmShape* nmm() const noexcept { return std::get_if<NmmShape>(&shape_); }
  /// The VEM block's shape, or null for other elements.
  [[nodiscard]] const VemShape* vem() const noexcept { return std::get_if<VemShape>(&shape_); }

private:
  friend class ElementIntegrals;
  std::variant<NmmShape, DdaShape, VemShape> shape_;
};

/// An element's mass matrix: NMM's acts on u and v alike (a scalar matrix on the shape
/// functions, kept as such: a quarter of the memory); DDA's and VEM's couple u and v.
struct ElementMass {
  bool scalar = false;
  Eigen::MatrixXd matrix;

  /// local += factor M.
  void add_to(Eigen::MatrixXd& local, double factor) const;
  /// M v into @p out.
  void times(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;
  /// v^T M v / 2.
  [[nodiscard]] double energy(const Eigen::VectorXd& v) const;
};

/// Area integrals of one element, exact by simplex integration, whichever its kind.
class ElementIntegrals {
public:
  /// @param shape     must outlive this object.
  /// @param polygons  the element's integration domain at the same geometry as @p shape.
  ElementIntegrals(const ElementShape& shape, std::span<const Polygon> polygons);

  [[nodiscard]] double area() const;
  /// Stiffness times @p thickness, into @p out (resized; no allocation when it has the size).
  void stiffness(const Eigen::Matrix3d& d, double thickness, Eigen::MatrixXd& out) const;
  /// Mass times density and thickness, into @p out.
  void mass(double density_thickness, ElementMass& out) const;
  /// Body force of a constant force per volume, plus the initial-stress load of @p stress
  /// when it is not zero, into @p out.
  void loads(const Point2& force,
             const LinearField3& stress,
             double thickness,
             Eigen::VectorXd& out) const;
  /// Adds the load of a VEM block's carried stabilisation force @p carried (2n vertex
  /// forces; VemIntegrals::stabilisation_load()) to @p out. Nothing for an empty @p carried
  /// or another kind of element.
  void add_stabilisation_load(const Eigen::VectorXd& carried, Eigen::VectorXd& out) const;

private:
  std::variant<NmmElementIntegrals, DdaIntegrals, VemIntegrals> integrals_;
};

} // namespace nmm
