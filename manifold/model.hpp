// SPDX-License-Identifier: MIT
// manifold/model.hpp — the manifold model: covers with positions and unknowns, elements with
// polygons, materials and stresses, the boundary loops; moved step by step with the
// material (Shi 1997, chapter 8.1: what is transferred from one step to the next).
#pragma once

#include "manifold/element.hpp"
#include "manifold/linear_constraint.hpp"
#include "manifold/material.hpp"
#include "manifold/nmm_element.hpp"
#include "mesh/cover_system.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/state_archive.hpp"

#include <Eigen/Core>

#include <array>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace nmm {

/// A physical cover of the model: an NMM cover, a DDA block or a vertex of a VEM block.
struct ModelCover {
  ElementKind kind = ElementKind::nmm;
  /// The math node (NMM), -1 for the covers of blocks.
  int node = -1;
  int block = -1;
  /// See Cover::extension_element: -1 for a cover with unknowns of its own.
  int extension_element = -1;
  /// Current position: the cover's math node (the vertex of the triangle of every element of
  /// this cover, and the origin of its order-1 cover function), the centroid of a DDA block,
  /// the vertex of a VEM block.
  Point2 position = Point2::Zero();
  /// The cover's raw unknowns are first_dof .. first_dof + n_dofs - 1: 2 (order 0) or 6
  /// (order 1) for NMM covers, 6 for a DDA block (u0, v0, r0, ex, ey, gxy), 2 for a VEM
  /// vertex. The first two are always the displacement of the cover's position.
  int first_dof = 0;
  int n_dofs = 0;
};

/// An element of the model: a manifold element, a DDA block or a VEM block.
struct ModelElement {
  ElementKind kind = ElementKind::nmm;
  /// The math triangle (NMM), -1 for blocks.
  int triangle = -1;
  int material = -1;
  int block = -1;
  /// The covers: three in the triangle's node order (NMM), the block's one (DDA), the
  /// block's vertices in the order of its polygon's loops (VEM).
  std::vector<int> covers;
  /// Raw unknowns of the element, in the local order of its shape.
  std::vector<int> dofs;
  /// Current integration domain.
  std::vector<Polygon> polygons;
  /// Accumulated stress (the initial stress of the next step, Shi eq. 2.9-2.10), a linear
  /// field for order-1 covers, constant for order 0.
  LinearField3 stress;
  /// VEM blocks: the stabilisation's vertex forces accumulated over the steps (2 per vertex,
  /// local order), the stabilisation's counterpart of `stress`: the next step's load is
  /// -(I - P_u)^T of it (docs/formulation.md, "VEM block"). Empty for other elements and
  /// before the first step.
  Eigen::VectorXd stabilisation_force;
  double area = 0.0;
  /// Removed by a stage's `excavate` (docs/case-file.md, "[[stage]]"): no stiffness, mass or
  /// contact, its stress frozen; the fraction `release` of its loads (body forces and the
  /// initial-stress load of its stress) still acts on its covers, from 1 at the start of
  /// its stage to 0 at the end, so that the tractions it held on the rest are released
  /// over the stage's steps.
  bool excavated = false;
  double release = 0.0;
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
  /// Unknowns of each NMM cover.
  [[nodiscard]] int dofs_per_cover() const noexcept { return cover_dofs(order); }
  /// Raw unknowns: those of every cover, cover by cover.
  [[nodiscard]] int n_dofs() const noexcept { return n_dofs_; }
  /// Raw unknown j (0 .. covers[cover].n_dofs - 1) of a cover.
  [[nodiscard]] int dof(int cover, int j) const noexcept {
    return covers[static_cast<std::size_t>(cover)].first_dof + j;
  }
  /// The cover owning raw unknown @p dof.
  [[nodiscard]] int cover_of_dof(int dof) const;
  /// Gives every cover its first_dof and every element its dofs (after covers were added).
  void number_dofs();

  /// The NMM element's triangle: the positions of its three covers.
  [[nodiscard]] std::array<Point2, 3> triangle(int element) const;
  /// The element's kinematics at the current geometry (element.hpp).
  [[nodiscard]] ElementShape shape(int element) const;
  /// The NMM element's shape. @pre elements[element].kind == ElementKind::nmm.
  [[nodiscard]] NmmShape nmm_shape(int element) const;
  /// Raw unknowns of the element, in the local order of its shape.
  [[nodiscard]] std::span<const int> element_dofs(int element) const {
    return elements[static_cast<std::size_t>(element)].dofs;
  }
  /// The element's local unknowns taken from a raw vector.
  [[nodiscard]] Eigen::VectorXd element_values(int element, const Eigen::VectorXd& raw) const;
  /// The same into @p out (resized; no allocation when it has the size: per-step loops).
  void element_values(int element, const Eigen::VectorXd& raw, Eigen::VectorXd& out) const;
  /// The origin of the element's strain and stress fields: ElementShape::origin() without
  /// building the shape.
  [[nodiscard]] Point2 element_origin(int element) const;
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
  /// (docs/cover-mesher.md, "Tiny pieces"): order 0 u_c = U(x_c); order 1 the cover function
  /// U(x_c) + G_c . (x - x_c), G_c the root's three covers' gradients extrapolated affinely
  /// to x_c, which keeps every quadratic representable and moves the tiny cover with every
  /// flex of the order-1 dependence (dependency_relations()).
  [[nodiscard]] std::vector<LinearConstraint> extension_relations() const;

  /// Excavates @p removed (ModelElement::excavated, release 1): an NMM cover left with less
  /// than @p min_cover_area_ratio of its elements' triangles in material takes the extension
  /// of the nearest well-posed element of its block, as the cover mesher's tiny covers do
  /// (docs/cover-mesher.md, "Tiny pieces"), and so does one whose extension element is
  /// removed; a cover left with none has its unknowns fixed (excavated_cover_relations()).
  void excavate(const std::vector<int>& removed, double min_cover_area_ratio);

  /// 1 for each block all of whose elements are excavated, else 0.
  [[nodiscard]] std::vector<char> excavated_blocks() const;

  /// Every unknown of a cover all of whose elements are excavated, fixed to zero (nothing
  /// holds or moves it any more). Empty when nothing is excavated.
  [[nodiscard]] std::vector<LinearConstraint> excavated_cover_relations() const;

  /// For order 1: unknowns fixed to zero to remove the linear dependence of the cover
  /// functions (docs/formulation.md, "Order-1 covers"). Each block's dependencies are the
  /// flexes of the framework whose joints are its covers and whose bars are the sides of its
  /// elements' triangles; as many unknowns as there are flexes are fixed, chosen by
  /// column-pivoted QR, so the space of displacement fields is unchanged. Empty for order 0.
  /// Excavated elements do not count.
  [[nodiscard]] std::vector<LinearConstraint> dependency_relations() const;

  /// Adds D eps(d) of the step to every element's stress and rotates the stress with the
  /// element's rigid rotation of the step (objective update); the same for a VEM block's
  /// stabilisation force: every vertex force turned by the rotation, plus
  /// eta_E (I - P_u)^T (I - P_u) d. Excavated elements keep theirs. Call before move().
  void accumulate_stress(const Eigen::VectorXd& raw);

  /// The exact rotation of the VEM and NMM blocks whose material has `exact_rotation`
  /// (docs/formulation.md, "VEM block: exact rotation", "NMM blocks: exact rotation").
  /// An NMM block (any of whose elements has such a material) turns by the mass-weighted
  /// mean rotation r of its elements about its centre of mass, each cover function getting
  /// the affine (R(r) - I - r J)(x - c), its velocity turned with it (exact_rotation.cpp).
  /// Each such VEM block's step turns it by
  /// r0 (its projected rotation, VemShape::rotation) about its centroid c only to first
  /// order, r0 J (x - c); this adds the rest, (R(r0) - I - r0 J)(x_i - c), to each vertex's
  /// step displacement in @p raw, and turns each vertex velocity relative to the centroid's
  /// by R(r0) in @p velocity, so that a rigid spin's velocities turn with the block. The added
  /// field is affine, which the block's interpolation reproduces exactly, so moving every
  /// point of the block by the new @p raw turns it exactly. Call after accumulate_stress()
  /// (the stress turns by r0 there) and before move(); no change without such blocks.
  void turn_exactly(Eigen::VectorXd& raw, Eigen::VectorXd& velocity) const;

  /// Moves covers, element polygons, loops, curve pieces and @p points with the step
  /// displacement (Shi 1997, chapter 8.1: the geometry of the next step).
  void move(const Eigen::VectorXd& raw, std::vector<MaterialPoint>& points);

  /// The largest displacement of a cover's position or a block's vertex in @p raw (m): what
  /// the step control limits (Shi 1997, chapter 8.5).
  [[nodiscard]] double largest_displacement(const Eigen::VectorXd& raw) const;

  /// Sets the unknowns of @p cover in @p raw to the rigid motion v(x) = v0 + omega J (x - c)
  /// (a velocity or a displacement field; J turns by 90 degrees).
  void set_rigid_motion(
      int cover, const Point2& v0, double omega, const Point2& c, Eigen::VectorXd& raw) const;

  /// Writes what the steps change (cover positions, element polygons, areas, stresses and
  /// carried stabilisation forces, boundary loops, curve pieces) for a restart checkpoint.
  void save_state(StateWriter& out) const;
  /// Reads what save_state() wrote into a model built from the same case.
  /// @throws InputError (StateReader) when a count differs: a checkpoint of another model.
  void load_state(StateReader& in);

private:
  int n_dofs_ = 0;
};

/// Options of make_model().
struct ModelOptions {
  int order = 0;
  /// Length scaling of order-1 cover functions; 0: the mean edge of the math mesh.
  double scale = 0.0;
  /// Kind of every material region (index = region): the blocks of `dda` and `vem` regions
  /// (CoverMesherOptions::block_regions) become special covers. Empty: every region NMM.
  std::vector<ElementKind> region_kinds;
};

/// Builds the model of a cover system: NMM elements on the covers of NMM regions, one DDA or
/// VEM element per block of the special regions (their covers after the NMM covers).
/// @param materials  one per region of the physical mesh (index = region).
/// @throws InputError for a block that cannot be an element (fewer than three vertices or
///         no area), naming its material and a point of it.
[[nodiscard]] Model make_model(const CoverSystem& covers,
                               const MathMesh& math,
                               std::vector<ElasticMaterial> materials,
                               const ModelOptions& options);

} // namespace nmm
