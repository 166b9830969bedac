// SPDX-License-Identifier: MIT
#include "io/gmsh_reader.hpp"

#include "io/gmsh_internal.hpp"
#include "io/text.hpp"
#include "mesh/curve_resolution.hpp"
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include <Eigen/Core>
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

namespace nmm {

namespace {

using detail::check_geometry_file;
using detail::check_tolerance;
using detail::element_corners;
using detail::entity_tags;
using detail::GmshFileKind;
using detail::NodeTable;
using detail::open_model;
using detail::physical_groups;
using detail::PhysicalGroup;
using detail::planar;
using detail::Point3;
using detail::run_gmsh;
using detail::tag_list;
using detail::throw_no_physical_surface;

using detail::ModelReader;

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

// ----------------------------------------------------------------------------------------
// Curves coarser than the cover mesh

/// A segment as its two end points in a fixed order, to find the same segment elsewhere.
std::array<double, 4> segment_key(const Point2& a, const Point2& b) {
  const bool forward = std::make_pair(a.x(), a.y()) < std::make_pair(b.x(), b.y());
  const Point2& p = forward ? a : b;
  const Point2& q = forward ? b : a;
  return {p.x(), p.y(), q.x(), q.y()};
}

/// The coarse segments of @p polyline (closed when its ends meet) not in @p skip.
void add_coarse_segments(std::vector<CoarseSegment>& found,
                         std::vector<Point2> polyline,
                         double cover_size,
                         const std::set<std::array<double, 4>>& skip = {}) {
  const bool closed = polyline.size() > 2 && polyline.front() == polyline.back();
  if (closed)
    polyline.pop_back();
  for (const CoarseSegment& segment : coarse_segments(polyline, closed, cover_size)) {
    if (skip.count(segment_key(segment.a, segment.b)) == 0)
      found.push_back(segment);
  }
}

/// The warning for the coarse segments @p found of @p what (a Physical Curve, or the outline
/// of a Physical Surface): how coarse, where, and what to do.
std::string coarse_curve_warning(const std::string& what,
                                 const std::vector<CoarseSegment>& found,
                                 double cover_size,
                                 bool from_mesh) {
  const CoarseSegment& longest = *std::max_element(
      found.begin(), found.end(), [](const auto& a, const auto& b) { return a.length < b.length; });
  // A circle through the longest chord: chords of the cover size deviate by this much.
  const double tolerance =
      longest.deviation * cover_size * cover_size / (longest.length * longest.length);
  const std::string h = number_text(cover_size);
  return what + " is coarser than the cover mesh: " + std::to_string(found.size()) +
         (found.size() == 1 ? " segment" : " segments") +
         " where it bends are longer than [cover_mesh] size = " + h + " m, the longest " +
         number_text(longest.length, 3) + " m near " +
         point_text(0.5 * (longest.a + longest.b), 6) + ", about " +
         number_text(longest.deviation, 2) +
         " m off the curve it stands for, and the covers follow these chords; " +
         (from_mesh ? "mesh the curve finer in gmsh (a mesh size of at most " + h +
                          " m along it, e.g. gmsh -2 -clmax " + h +
                          "), or give the .geo as geometry: nmm samples its curves for the "
                          "cover mesh"
                    : "lower [cover_mesh] curve_tolerance to at most " + number_text(tolerance, 2) +
                          " m, or remove it (the automatic tolerance follows the cover size)") +
         " (a polygon meant as drawn may stay)";
}

/// One warning per Physical Curve, and per Physical Surface for its outline curves that no
/// Physical Curve names, whose sampled or meshed curves are coarser than the cover mesh.
std::vector<std::string> coarse_curve_warnings(const std::string& file,
                                               ModelReader& reader,
                                               const PhysicalMesh& physical,
                                               const std::vector<PhysicalGroup>& surface_groups,
                                               const std::vector<PhysicalGroup>& curve_groups,
                                               double cover_size) {
  const bool from_mesh = lower(std::filesystem::path(file).extension().string()) == ".msh";
  std::vector<std::string> warnings;
  std::set<int> named_curves;
  std::set<std::array<double, 4>> named_segments;
  for (std::size_t g = 0; g < curve_groups.size(); ++g) {
    std::vector<CoarseSegment> found;
    for (const int tag : curve_groups[g].entities) {
      named_curves.insert(tag);
      if (!reader.is_sampled(tag))
        continue;
      for (const std::vector<Point2>& polyline : reader.curve(tag, curve_groups[g].name)) {
        for (std::size_t i = 0; i + 1 < polyline.size(); ++i)
          named_segments.insert(segment_key(polyline[i], polyline[i + 1]));
        add_coarse_segments(found, polyline, cover_size);
      }
    }
    if (!found.empty())
      warnings.push_back(coarse_curve_warning("Physical Curve \"" + curve_groups[g].name + "\"",
                                              found, cover_size, from_mesh));
  }
  for (std::size_t g = 0; g < surface_groups.size(); ++g) {
    std::vector<CoarseSegment> found;
    const MaterialRegion& region = physical.regions[g];
    for (std::size_t k = 0; k < surface_groups[g].entities.size(); ++k) {
      const int tag = surface_groups[g].entities[k];
      std::string type;
      gmsh::model::getType(2, tag, type);
      if (type == "Discrete surface") {
        // A meshed surface's outline is its elements' boundary: every segment a mesh edge.
        const Polygon& polygon = region.polygons[k];
        add_coarse_segments(found, polygon.outer, cover_size, named_segments);
        for (const Loop& hole : polygon.holes)
          add_coarse_segments(found, hole, cover_size, named_segments);
        continue;
      }
      for (const int curve : reader.outline(tag)) {
        if (named_curves.count(curve) > 0 || !reader.is_sampled(curve))
          continue;
        for (const std::vector<Point2>& polyline : reader.curve(curve, region.name))
          add_coarse_segments(found, polyline, cover_size);
      }
    }
    if (!found.empty())
      warnings.push_back(coarse_curve_warning(
          "the outline of Physical Surface \"" + region.name + "\"", found, cover_size, from_mesh));
  }
  return warnings;
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
