// SPDX-License-Identifier: MIT
// Reading a .geo or .msh into the physical mesh: its Physical Surfaces as material regions,
// its Physical Curves and Points, and the warnings for curves coarser than the cover mesh.
// The parts are in the other io/gmsh_*.cpp files (io/gmsh_internal.hpp).
#include "io/gmsh_reader.hpp"

#include "io/gmsh_internal.hpp"
#include "io/text.hpp"
#include "mesh/curve_resolution.hpp"
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace nmm {

namespace {

using detail::check_geometry_file;
using detail::check_tolerance;
using detail::coarse_curve_warnings;
using detail::entity_tags;
using detail::GmshFileKind;
using detail::ModelReader;
using detail::open_model;
using detail::physical_groups;
using detail::PhysicalGroup;
using detail::throw_no_physical_surface;

/// Diagonal (in the plane) of the bounding box of the surfaces of all Physical Surfaces.
double surfaces_diagonal(const std::vector<PhysicalGroup>& groups) {
  BoundingBox box;
  for (const PhysicalGroup& group : groups) {
    for (const int tag : group.entities) {
      double x0 = 0, y0 = 0, z0 = 0, x1 = 0, y1 = 0, z1 = 0;
      gmsh::model::getBoundingBox(2, tag, x0, y0, z0, x1, y1, z1);
      if (x1 >= x0 && y1 >= y0) {
        box.extend({x0, y0});
        box.extend({x1, y1});
      }
    }
  }
  return box.is_empty() ? 0.0 : box.size().norm();
}

PhysicalMesh read_open_model(const std::string& file, const GeometryReadOptions& options) {
  const std::vector<PhysicalGroup> surface_groups = physical_groups(2, "surface");
  if (surface_groups.empty())
    throw_no_physical_surface(file);
  const std::set<int> surfaces = entity_tags(2);
  for (const PhysicalGroup& group : surface_groups) {
    for (const int tag : group.entities) {
      if (surfaces.count(tag) == 0)
        throw InputError(file + ": Physical Surface \"" + group.name + "\" refers to surface " +
                         std::to_string(tag) + ", which does not exist; fix the group's list");
    }
  }
  const double diagonal = surfaces_diagonal(surface_groups);
  const bool automatic = !(options.curve_tolerance > 0.0);
  const double tolerance =
      automatic ? automatic_curve_tolerance(diagonal, options.cover_size) : options.curve_tolerance;
  // Coordinates written with z = 0 come back as exact zeros; allow only rounding noise.
  const double z_limit = 1.0e-9 * std::max(diagonal, 1.0);
  ModelReader reader(file, tolerance, automatic ? options.cover_size : 0.0, z_limit);

  PhysicalMesh physical;
  physical.source = file;
  for (const PhysicalGroup& group : surface_groups) {
    MaterialRegion& region = physical.regions.emplace_back();
    region.name = group.name;
    for (const int tag : group.entities)
      region.polygons.push_back(reader.surface(tag, group.name));
  }
  const std::vector<PhysicalGroup> curve_groups = physical_groups(1, "curve");
  for (const PhysicalGroup& group : curve_groups) {
    NamedCurve& named = physical.curves.emplace_back();
    named.name = group.name;
    const std::string context = "Physical Curve \"" + group.name + "\"";
    for (const int tag : group.entities) {
      for (const std::vector<Point2>& polyline : reader.curve(tag, context))
        named.polylines.push_back(polyline);
    }
  }
  for (const PhysicalGroup& group : physical_groups(0, "point")) {
    NamedPoint& named = physical.points.emplace_back();
    named.name = group.name;
    const std::string context = "Physical Point \"" + group.name + "\"";
    for (const int tag : group.entities)
      named.points.push_back(reader.point(tag, context));
  }
  validate_physical_mesh(physical);
  if (options.cover_size > 0.0)
    physical.warnings = coarse_curve_warnings(file, reader, physical, surface_groups, curve_groups,
                                              options.cover_size);
  return physical;
}

} // namespace

namespace detail {

void check_tolerance(const std::string& file, const GeometryReadOptions& options) {
  if (!(options.curve_tolerance >= 0.0) || !std::isfinite(options.curve_tolerance)) {
    throw InputError(file +
                     ": the curve tolerance must be a finite length >= 0 (0 = automatic: "
                     "1e-2 of the cover size, or 1e-3 of the material's bounding-box "
                     "diagonal when that is finer), got " +
                     number_text(options.curve_tolerance, 10));
  }
}

} // namespace detail

// ------------------------------------------------------------------------------------------

PhysicalMesh read_physical_mesh(const std::filesystem::path& file,
                                const GeometryReadOptions& options) {
  const std::string name = file.string();
  check_tolerance(name, options);
  const GmshFileKind kind = check_geometry_file(file);
  if (kind == GmshFileKind::msh && options.curve_tolerance > 0.0) {
    throw InputError(
        name + ": [cover_mesh] curve_tolerance = " + number_text(options.curve_tolerance, 10) +
        " m cannot apply to a .msh: its curves are its mesh's line elements, with "
        "no curve to sample again; remove curve_tolerance (the mesh's curves are "
        "used as they are), or give the .geo as geometry to sample its curves");
  }
  std::optional<GmshSession> own_session;
  if (!GmshSession::is_alive())
    own_session.emplace();
  open_model(file, kind, options);
  return read_open_model(name, options);
}

} // namespace nmm
