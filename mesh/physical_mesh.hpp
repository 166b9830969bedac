// SPDX-License-Identifier: MIT
// mesh/physical_mesh.hpp — what the user cannot choose: material regions, joints, named
// curves and points (Shi 1997, chapter 1.1: the physical mesh). Built by io/ from gmsh
// physical groups, consumed by the cover mesher.
#pragma once

#include "mesh/geometry.hpp"

#include <string>
#include <vector>

namespace nmm {

/// One Physical Surface: a material region made of one or more polygons with holes.
struct MaterialRegion {
  /// The physical group name, which is also the material name in the case file.
  std::string name;
  /// One polygon per gmsh surface of the group. Loop orientation is free (normalised by
  /// validate_physical_mesh()); loops are closed implicitly (last vertex not repeated).
  std::vector<Polygon> polygons;
};

/// One Physical Curve (or Physical Point) of the geometry, sampled to polylines.
struct NamedCurve {
  std::string name;
  /// Each gmsh curve of the group as a polyline (at least 2 points), in gmsh's parametric
  /// direction, sampled so that the chord deviation is below the reader's tolerance.
  std::vector<std::vector<Point2>> polylines;
};

/// One Physical Point group.
struct NamedPoint {
  std::string name;
  std::vector<Point2> points;
};

/// The physical mesh of DESIGN.md: every line the covers must respect, plus the named
/// curves and points that boundary conditions, loads and monitors refer to.
///
/// Which named curves are joints is decided by the case file (`[joints.NAME]`), not by the
/// geometry: the cover mesher receives the joint set names separately. A curve shared by two
/// regions that is not a joint is a bonded interface (splits elements by material only).
struct PhysicalMesh {
  /// The geometry file, for error messages ("slope.geo").
  std::string source;
  std::vector<MaterialRegion> regions;
  std::vector<NamedCurve> curves;
  std::vector<NamedPoint> points;
  /// Remarks of the reader that do not stop a run, each saying what to do (a curve sampled
  /// coarser than the cover mesh, for instance).
  std::vector<std::string> warnings;

  [[nodiscard]] int n_regions() const noexcept { return static_cast<int>(regions.size()); }

  /// Index of the region, curve or point group called @p name, or -1.
  [[nodiscard]] int find_region(const std::string& name) const;
  [[nodiscard]] int find_curve(const std::string& name) const;
  [[nodiscard]] int find_point(const std::string& name) const;

  /// Comma-separated names of all regions / curves / points, for "did you mean" messages.
  [[nodiscard]] std::string region_names() const;
  [[nodiscard]] std::string curve_names() const;
  [[nodiscard]] std::string point_names() const;
};

/// Bounding box of all material regions (named curves and points outside do not count).
[[nodiscard]] BoundingBox material_bounding_box(const PhysicalMesh& physical);

/// Total material area (sum over regions of outer minus holes).
[[nodiscard]] double material_area(const PhysicalMesh& physical);

/// Checks and normalises the physical mesh in place: every coordinate finite; every loop has
/// at least 3 distinct vertices, positive area and does not touch or cross itself (exact
/// predicates); holes lie inside their outer loop; outer loops become counter-clockwise and
/// holes clockwise; consecutive duplicate vertices are removed; every named curve has at
/// least one polyline of non-zero length.
/// Overlaps between different regions are detected later by the cover mesher, which sees
/// every region boundary in one exact arrangement.
/// @throws InputError naming physical.source, the physical group and a vertex near the
///         problem, and saying what to fix.
void validate_physical_mesh(PhysicalMesh& physical);

} // namespace nmm
