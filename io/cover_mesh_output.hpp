// SPDX-License-Identifier: MIT
// io/cover_mesh_output.hpp — the cover mesher's result as VTK files for ParaView: the
// manifold elements (mesh.vtu), the math mesh (math_mesh.vtu) and the boundary loops with
// their joints (boundary.vtp). DESIGN.md "Command line" (`nmm mesh`); docs/output.md.
#pragma once

#include "io/vtk_writer.hpp"
#include "mesh/cover_system.hpp"
#include "mesh/math_mesh.hpp"

#include <filesystem>
#include <span>

namespace nmm {

/// The manifold elements of @p covers, one cell per element polygon (an element with several
/// atoms gives several cells), each polygon with its own points: for element e, polygon p,
/// first the outer loop's vertices, then each hole's, in the order of Element::polygons.
/// Cell data (Int32 unless noted): `element`, `triangle` (math triangle), `covers` (the 3
/// physical covers), `material`, `block`, `n_atoms` (polygons of the element), `area`
/// (Float64, the element's area in m²). Step writers add their fields to the result.
[[nodiscard]] PolygonMeshData make_cover_mesh_data(const CoverSystem& covers);

/// Writes make_cover_mesh_data(@p covers) to @p file (`mesh.vtu` of `nmm mesh`).
/// @throws InputError naming the file or directory when it cannot be written.
void write_cover_mesh_vtu(const std::filesystem::path& file, const CoverSystem& covers);

/// The math triangles of @p mesh (VTK_TRIANGLE), points = math nodes. Cell data `triangle`,
/// point data `node` and, when @p covers is given, `n_covers`: the number of physical covers
/// of each node (CoverSystem::node_covers; 0 outside the material, 2 or more where joints
/// cut its star). @pre covers == nullptr or covers->node_covers has one entry per node.
[[nodiscard]] PolygonMeshData make_math_mesh_data(const MathMesh& mesh,
                                                  const CoverSystem* covers = nullptr);

/// Writes make_math_mesh_data() to @p file (`math_mesh.vtu` of `nmm mesh`).
/// @throws InputError naming the file or directory when it cannot be written.
void write_math_mesh_vtu(const std::filesystem::path& file,
                         const MathMesh& mesh,
                         const CoverSystem* covers = nullptr);

/// Boundary loops (CoverSystem::loops as meshed, or Model::loops where they are now) as
/// polylines: each loop is cut into maximal runs of edges on the same joint, one polyline per
/// run (a loop on one joint throughout is one closed polyline). Cell data (Int32): `block`,
/// `joint` (PhysicalMesh::curves index of the joint, -1 on a free boundary), `loop` (index
/// in @p loops).
[[nodiscard]] PolylineData make_boundary_data(std::span<const BoundaryLoop> loops);

/// Writes make_boundary_data(@p covers.loops) to @p file (e.g. `boundary.vtp`): the joints and
/// free boundaries drawn as lines in ParaView.
/// @throws InputError naming the file or directory when it cannot be written.
void write_boundary_vtp(const std::filesystem::path& file, const CoverSystem& covers);

} // namespace nmm
