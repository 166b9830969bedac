// SPDX-License-Identifier: MIT
// mesh/cover_mesher.hpp — cut the math mesh by the physical mesh into physical covers,
// manifold elements, blocks and boundary loops (Shi 1997, chapters 1.1, 1.4, 4.1-4.2).
#pragma once

#include "mesh/cover_system.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"

#include <span>
#include <vector>

namespace nmm {

/// Tuning for build_cover_system().
struct CoverMesherOptions {
  /// A cover whose support is smaller than this fraction of its math star's area gets no
  /// unknowns of its own but an extension element (Cover::extension_element).
  /// Why: a joint or boundary passing close to a node leaves a sliver cover whose stiffness
  /// and mass scale with its area; at 1e-9 of the star the condition number grows by 1e9.
  /// 1e-3 bounds that growth to 1e3 while the slivers it treats are too thin to matter.
  double min_cover_area_ratio = 1.0e-3;
  /// Material regions (PhysicalMesh::regions indices) whose blocks are special covers
  /// (`model = "dda"` or `"vem"`): they get blocks and boundary loops but no math-mesh
  /// elements; joints ending inside them are ignored there with a warning, and every
  /// boundary between them and another region is a contact boundary, not a bond.
  std::vector<int> block_regions;
};

/// Moves the nodes of @p math that lie inside the material within rounding of a boundary
/// between material and void (1e-12 of the edge's size) onto it or just outside, by a few
/// units in the last place. Why: a mesh generator places boundary nodes of a slanted edge by
/// rounding, and a node a hair inside leaves a sliver of material that no triangle covers:
/// the boundary there would have no elements, and a load or contact on it would act on
/// nothing. Edges walked both ways by region loops (interfaces) are left alone.
/// @return the number of nodes moved.
int fit_math_mesh_to_boundary(MathMesh& math, const PhysicalMesh& physical);

/// Builds atoms, physical covers, manifold elements, blocks and boundary loops
/// (DESIGN.md, "Concepts"; the rules for degenerate input are in docs/cover-mesher.md).
///
/// Topology is decided exactly: one CGAL arrangement (exact kernel) of all physical
/// segments gives the material on each side of every line, the blocks and the boundary
/// loops; each math triangle touched by a physical segment is cut in a local arrangement
/// of its edges and those segments. Triangles touched by none become whole elements.
/// Coordinates are rounded to double only in the result, the same exact point always to
/// the same double, so vertices shared by elements and loops are bit-identical.
///
/// @param math      counter-clockwise triangles covering every material region.
/// @param physical  validated (validate_physical_mesh()).
/// @param joints    indices of the named curves that are joints (`[joints.NAME]`): they cut
///                  the material wherever they lie inside it. Other named curves only mark
///                  places (loads, supports, monitors) and never cut.
/// @post every element has three distinct covers, one per triangle node, of its block;
///       element areas sum to the material area (up to rounding of the vertices).
/// @throws InputError naming physical.source and the regions when material regions
///         overlap, or when the math mesh does not cover the material.
[[nodiscard]] CoverSystem build_cover_system(const MathMesh& math,
                                             const PhysicalMesh& physical,
                                             std::span<const int> joints,
                                             const CoverMesherOptions& options = {});

} // namespace nmm
