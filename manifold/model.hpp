// SPDX-License-Identifier: MIT
// manifold/model.hpp — the manifold model: covers with positions and unknowns, elements with
// polygons, materials and stresses, the boundary loops; moved step by step with the
// material (Shi 1997, chapter 8.1: what is transferred from one step to the next).
#pragma once

#include "manifold/linear_constraint.hpp"
#include "manifold/material.hpp"
#include "manifold/nmm_element.hpp"
#include "mesh/cover_system.hpp"
#include "mesh/math_mesh.hpp"

#include <Eigen/Core>

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace nmm {

/// A physical cover of the model.
struct ModelCover {
  int node = -1;
  int block = -1;
  /// See Cover::extension_element: -1 for a cover with unknowns of its own.
  int extension_element = -1;
  /// Current position of the cover's math node: the vertex of the triangle of every element
  /// of this cover, and the origin of its order-1 cover function.
  Point2 position = Point2::Zero();
};

/// A manifold element of the model.
struct ModelElement {
  int triangle = -1;
  int material = -1;
  int block = -1;
  std::array<int, 3> covers{-1, -1, -1};
  /// Current integration domain.
  std::vector<Polygon> polygons;
  /// Accumulated stress (the initial stress of the next step, Shi eq. 2.9-2.10), a linear
  /// field for order-1 covers, constant for order 0.
  LinearField3 stress;
  double area = 0.0;
};

/// A material point followed through the analysis (monitors, point loads).
struct MaterialPoint {
  int element = -1;
  Point2 position = Point2::Zero();
};

/// Everything the time stepper changes from step to step.
class Model {
public:
  /// Cover-function order (0 or 1).
  int order = 0;
  /// Length scaling order-1 cover functions (the math mesh size), m.
  double scale = 1.0;
  /// Materials by region index (PhysicalMesh::regions).
  std::vector<ElasticMaterial> materials;
  std::vector<ModelCover> covers;
  std::vector<ModelElement> elements;
  std::vector<Block> blocks;
  /// Boundary loops at current positions (contact).
  std::vector<BoundaryLoop> loops;
  /// Pieces of each named curve at current positions (supports and loads on curves).
  std::vector<std::vector<CurvePiece>> curve_pieces;

  [[nodiscard]] int n_covers() const noexcept { return static_cast<int>(covers.size()); }
  [[nodiscard]] int n_elements() const noexcept { return static_cast<int>(elements.size()); }
  /// Unknowns per cover.
  [[nodiscard]] int dofs_per_cover() const noexcept { return cover_dofs(order); }
  /// Raw unknowns: dofs_per_cover() for every cover, cover by cover.
  [[nodiscard]] int n_dofs() const noexcept { return n_covers() * dofs_per_cover(); }
  /// Raw unknown j (0 .. dofs_per_cover() - 1) of cover c.
  [[nodiscard]] int dof(int cover, int j) const noexcept { return cover * dofs_per_cover() + j; }

  /// The element's triangle: the positions of its three covers.
  [[nodiscard]] std::array<Point2, 3> triangle(int element) const;
  [[nodiscard]] NmmShape shape(int element) const;
  /// Raw unknowns of the element, in the local order of its shape.
  [[nodiscard]] ElementDofs element_dofs(int element) const;
  /// The element's local unknowns taken from a raw vector.
  [[nodiscard]] ElementVector element_values(int element, const Eigen::VectorXd& raw) const;
  /// Displacement at @p x of the element's field for the raw unknowns @p raw.
  [[nodiscard]] Point2 displacement(int element, const Point2& x, const Eigen::VectorXd& raw) const;
  /// Material of an element.
  [[nodiscard]] const ElasticMaterial& material_of(int element) const {
    return materials[static_cast<std::size_t>(
        elements[static_cast<std::size_t>(element)].material)];
  }

  /// The element whose material contains @p x (current positions): containing polygon,
  /// else the nearest element within @p tolerance; -1 when none.
  [[nodiscard]] int find_element(const Point2& x, double tolerance) const;

  /// Constraints giving every tiny cover the extension of its extension element's field
  /// (docs/formulation.md, "Tiny covers"): order 0 u_c = U(x_c); order 1 the cover function
  /// U(x_c) + (grad U(x_c) + grad U(c0)) / 2 . (x - x_c) with one c0 per block, which keeps
  /// every quadratic representable.
  [[nodiscard]] std::vector<LinearConstraint> extension_relations() const;

  /// For order 1: unknowns fixed to zero to remove the linear dependence of the cover
  /// functions (docs/formulation.md, "Order-1 covers"). Each block's dependencies are the
  /// flexes of the framework whose joints are its covers and whose bars are the sides of its
  /// elements' triangles; as many unknowns as there are flexes are fixed, chosen by
  /// column-pivoted QR, so the space of displacement fields is unchanged. Empty for order 0.
  [[nodiscard]] std::vector<LinearConstraint> dependency_relations() const;

  /// Adds D eps(d) of the step to every element's stress and rotates the stress with the
  /// element's rigid rotation of the step (objective update). Call before move().
  void accumulate_stress(const Eigen::VectorXd& raw);

  /// Moves covers, element polygons, loops, curve pieces and @p points with the step
  /// displacement (Shi 1997, chapter 8.1: the geometry of the next step).
  void move(const Eigen::VectorXd& raw, std::vector<MaterialPoint>& points);
};

/// Options of make_model().
struct ModelOptions {
  int order = 0;
  /// Length scaling of order-1 cover functions; 0: the mean edge of the math mesh.
  double scale = 0.0;
};

/// Builds the model of the NMM regions of a cover system.
/// @param materials  one per region of the physical mesh (index = region).
[[nodiscard]] Model make_model(const CoverSystem& covers,
                               const MathMesh& math,
                               std::vector<ElasticMaterial> materials,
                               const ModelOptions& options);

} // namespace nmm
