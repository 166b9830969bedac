// SPDX-License-Identifier: MIT
// io/gmsh_reader.hpp — gmsh geometry (.geo, .msh) to the physical mesh and the "gmsh"
// mathematical mesh (DESIGN.md, "Contracts users see / Geometry").
#pragma once

#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"

#include <filesystem>
#include <string>

namespace nmm {

/// The gmsh library, initialised for the lifetime of this object (RAII around
/// gmsh::initialize / gmsh::finalize).
///
/// The session reads no gmsh configuration files, prints nothing to the terminal and
/// captures gmsh's messages, so that the functions below can put gmsh's own error text (for
/// a .geo syntax error: its file and line) into an InputError. It also sets gmsh's
/// "General.AbortOnError" to 0: in gmsh 4.8 an exception thrown out of the .geo parser
/// leaves the parser unusable for the rest of the process, so errors are read from the log
/// instead. The process locale, which gmsh::initialize changes, is restored on destruction.
///
/// gmsh has one global state, so only one session may be alive at a time, and it must be
/// used from one thread. read_physical_mesh() and make_gmsh_math_mesh() open a session of
/// their own when none is alive; holding one across several calls saves the start-up cost.
/// Those functions replace the session's current gmsh model.
class GmshSession {
public:
  /// @throws std::logic_error when another session is alive (a programmer error).
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  GmshSession(GmshSession&&) = delete;
  GmshSession& operator=(GmshSession&&) = delete;

  /// True while a GmshSession object exists in the process.
  [[nodiscard]] static bool is_alive() noexcept;

private:
  std::string saved_locale_;
};

/// Tuning for read_physical_mesh().
struct GeometryReadOptions {
  /// Largest distance (m) allowed between a curved gmsh curve and the polyline that
  /// replaces it (the chord deviation). 0 means automatic: automatic_curve_tolerance() of
  /// the diagonal of the bounding box of all Physical Surfaces and `cover_size` (1e-2 of the
  /// cover size, or 1e-3 of the diagonal when that is finer), with chords no longer than
  /// `cover_size`. Straight lines are never subdivided. Curves read from a mesh (.msh) are
  /// its line elements: there is no curve to sample, so a value > 0 is refused for a .msh.
  double curve_tolerance = 0.0;
  /// Edge length (m) of the cover mesh's triangles; 0: not known (no chord length bound, no
  /// check). When > 0, every curve that nmm samples (a curved curve of a .geo) or that comes
  /// from a mesh (.msh) and has segments coarser than this (coarse_segments()) is named in
  /// PhysicalMesh::warnings (without the file name, which is PhysicalMesh::source), with
  /// what to do.
  double cover_size = 0.0;
  /// Longest wall time (s) reading a `.geo` may take; 0: no limit. With a time or memory
  /// limit, a `.geo` is read first in a child process (fork) that is stopped at the limit,
  /// so that a file that loops forever (an endless `For`, a recursive `Macro`) or grows
  /// without bound (millions of points) cannot hang nmm; then it is read in this process.
  /// `.msh` files are data, read only once.
  double time_limit = 0.0;
  /// Most memory (bytes) reading a `.geo` may add to the process (RLIMIT_AS of the child:
  /// its address space at the fork plus this); 0: no limit.
  double memory_limit = 0.0;
};

/// Reads the physical groups of a gmsh file into the physical mesh (DESIGN.md, "Geometry").
///
/// Accepted files: `.geo` (built-in or OpenCASCADE kernel) and `.msh` (format 2 or 4).
/// - Physical Surface -> one MaterialRegion named after the group; a group without a name
///   is called "surface_<tag>" (its physical tag). Each gmsh surface of the group becomes
///   one Polygon: its boundary curves are sampled and chained into closed loops by their
///   end points; the loop of largest area (the one enclosing the others) is `outer`, the
///   others are `holes`. Curves embedded in a surface are not part of its boundary.
/// - Physical Curve -> one NamedCurve ("curve_<tag>" when unnamed), one polyline per gmsh
///   curve in the curve's parametric direction. A curve need not be embedded in the surface
///   it lies in (joints are drawn as plain curves).
/// - Physical Point -> one NamedPoint ("point_<tag>" when unnamed).
///
/// Sampling: a straight line is exactly its two end points; any other curve is subdivided
/// adaptively until its chord deviation (checked at three interior parameters per chord) is
/// at most the tolerance. End points are the exact coordinates of the gmsh points, and each
/// gmsh curve is sampled once: a curve shared by two surfaces, or by a surface and a
/// Physical Curve, has bit-identical vertices everywhere it appears. Discrete entities (all
/// entities of a .msh file) use their mesh: a surface's loops are the boundary edges of its
/// mesh elements, a curve's polyline its line elements chained in order.
///
/// The result has passed validate_physical_mesh() (outer loops counter-clockwise, holes
/// clockwise); `source` is @p file as given. The geometry must lie in the plane z = 0.
///
/// @throws InputError naming the file and, where it applies, the line (gmsh's own message
///         for .geo syntax errors) or the physical group, when: a curve tolerance > 0 is
///         given for a .msh (naming `[cover_mesh] curve_tolerance`); reading a .geo exceeds
///         GeometryReadOptions::time_limit or memory_limit; the file is missing,
///         unreadable or not .geo/.msh; gmsh reports an error; there is no Physical Surface;
///         a surface's boundary does not close; a curve cannot be sampled within the
///         tolerance; the tolerance is negative or not finite; or validation fails.
[[nodiscard]] PhysicalMesh read_physical_mesh(const std::filesystem::path& file,
                                              const GeometryReadOptions& options = {});

/// The `kind = "gmsh"` mathematical mesh: a triangulation of the Physical Surfaces of
/// @p file, nodes numbered 0..n-1 (all used), triangles counter-clockwise.
///
/// For a `.geo` file, the physical mesh is read exactly as read_physical_mesh(@p file,
/// @p options) and gmsh triangulates those polygons (not the original curves): every
/// polygon vertex is a mesh node and every polygon edge is covered by mesh edges, so the
/// triangles cover the material exactly, also along sampled curves, and conform to the
/// boundaries and to the curves shared between surfaces. Curves that are not surface
/// boundaries (joints) are not embedded. The element size is uniform: Mesh.MeshSizeMax =
/// @p size, no minimum, size factor 1; the mesh sizes, fields and mesh options of the .geo
/// are ignored (they refer to the original entities; the overload below can grade the mesh
/// by them). Near densely sampled curves the triangles are smaller than @p size.
///
/// For a `.msh` file, the file's own 2D elements of the Physical Surfaces are used (quads
/// are split into two triangles, high-order nodes dropped); @p size is then only checked.
///
/// @param size          maximum element edge length (m).
/// @param max_triangles refuse meshes estimated (area / (sqrt(3)/4 size^2)) before meshing,
///                      or found after, to have more triangles than this.
/// @throws InputError as read_physical_mesh(), and when @p size is not a positive finite
///         number or the mesh would be too large (the message says to raise
///         `[cover_mesh] size` or `[cover_mesh] max_triangles`), or when gmsh fails to mesh.
[[nodiscard]] MathMesh make_gmsh_math_mesh(const std::filesystem::path& file,
                                           double size,
                                           double max_triangles = default_max_math_triangles,
                                           const GeometryReadOptions& options = {});

/// As above, for a geometry whose physical mesh @p physical was read already
/// (read_physical_mesh() of the same file): a `.geo` is triangulated from @p physical; a
/// `.msh` is read for its own elements.
///
/// With @p sizes_from_geometry (`[cover_mesh] geometry_sizes`) a `.geo`'s own mesh sizes
/// grade the triangles: gmsh meshes the file's model as the file asks (characteristic
/// lengths of its points, its Fields and Background Field, its Mesh.MeshSize* options),
/// with Mesh.MeshSizeMax at most @p size; the local edge length of that mesh (at each node
/// the mean length of its edges, at most @p size) is then the background size field of the
/// triangulation of @p physical. @p size stays the largest edge. Without it (and for a
/// `.msh`, whose elements are used as they are) the .geo is not read again.
/// @throws InputError also when the file's own mesh has more triangles than
///         @p max_triangles (its sizes in mm?), naming the file and what to change.
[[nodiscard]] MathMesh make_gmsh_math_mesh(const std::filesystem::path& file,
                                           const PhysicalMesh& physical,
                                           double size,
                                           double max_triangles = default_max_math_triangles,
                                           bool sizes_from_geometry = false);

} // namespace nmm
