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

} // namespace

namespace detail {

std::vector<Chain> chain_edges(const std::vector<std::array<std::size_t, 2>>& edges) {
  std::unordered_map<std::size_t, std::vector<std::size_t>> incident;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    incident[edges[e][0]].push_back(e);
    incident[edges[e][1]].push_back(e);
  }
  std::vector<bool> used(edges.size(), false);
  auto walk = [&](std::size_t edge, std::size_t start) {
    Chain chain;
    chain.first_node = start;
    std::size_t node = start;
    while (true) {
      used[edge] = true;
      const bool forward = edges[edge][0] == node;
      chain.edges.emplace_back(edge, forward);
      node = forward ? edges[edge][1] : edges[edge][0];
      if (node == start) {
        chain.closed = true;
        break;
      }
      // Where several edges meet (two loops touching), prefer the one that follows the
      // current edge in the input: gmsh lists a surface's boundary loop by loop.
      std::optional<std::size_t> next;
      for (const std::size_t candidate : incident[node]) {
        if (used[candidate])
          continue;
        if (!next || (*next < edge && candidate > edge))
          next = candidate;
      }
      if (!next)
        break;
      edge = *next;
    }
    chain.last_node = node;
    return chain;
  };
  std::vector<Chain> chains;
  // Open paths first, started at an end (a node of odd degree), never in their middle.
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (used[e])
      continue;
    for (const std::size_t end : edges[e]) {
      if (incident[end].size() % 2 == 1) {
        chains.push_back(walk(e, end));
        break;
      }
    }
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!used[e])
      chains.push_back(walk(e, edges[e][0]));
  }
  return chains;
}

Polygon ModelReader::surface(int tag, const std::string& group) {
  std::string type;
  gmsh::model::getType(2, tag, type);
  const std::string context =
      "Physical Surface \"" + group + "\" (gmsh surface " + std::to_string(tag) + ")";
  std::vector<Loop> loops =
      type == "Discrete surface" ? discrete_loops(tag, context) : curve_loops(tag, context);
  if (loops.empty())
    throw InputError(file_ + ": " + context +
                     " has no boundary curves; define it from a closed Curve Loop");
  // The loop enclosing the others has the largest area; validate_physical_mesh() checks
  // that the holes do lie inside it.
  const auto outer = std::max_element(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    return std::abs(signed_area(a)) < std::abs(signed_area(b));
  });
  Polygon polygon;
  polygon.outer = std::move(*outer);
  loops.erase(outer);
  polygon.holes = std::move(loops);
  return polygon;
}

std::vector<Loop> ModelReader::curve_loops(int tag, const std::string& context) {
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary({{2, tag}}, boundary, false, true, false);
  // A curve listed twice (a slit traversed both ways) lies inside the surface: not part of
  // its outline. Curves embedded with "In Surface" are not listed at all.
  std::map<int, int> count;
  for (const auto& dim_tag : boundary)
    ++count[std::abs(dim_tag.second)];
  std::vector<std::vector<Point2>> pieces;
  std::vector<int> piece_curve;
  for (const auto& dim_tag : boundary) {
    const int curve_tag = std::abs(dim_tag.second);
    if (count[curve_tag] != 1)
      continue;
    outlines_[tag].push_back(curve_tag);
    for (const std::vector<Point2>& polyline : curve(curve_tag, context)) {
      std::vector<Point2>& piece = pieces.emplace_back(polyline);
      if (dim_tag.second < 0)
        std::reverse(piece.begin(), piece.end());
      piece_curve.push_back(curve_tag);
    }
  }
  // End points are exact gmsh point coordinates, so equal coordinates mean a shared point.
  std::map<std::pair<double, double>, std::size_t> node_of;
  std::vector<Point2> node_point;
  auto node = [&](const Point2& p) {
    const auto [it, inserted] = node_of.try_emplace({p.x(), p.y()}, node_point.size());
    if (inserted)
      node_point.push_back(p);
    return it->second;
  };
  std::vector<std::array<std::size_t, 2>> edges;
  for (const std::vector<Point2>& piece : pieces)
    edges.push_back({node(piece.front()), node(piece.back())});

  std::vector<Loop> loops;
  std::vector<std::string> loose_ends;
  std::vector<int> open_curves;
  for (const Chain& chain : chain_edges(edges)) {
    if (!chain.closed) {
      loose_ends.push_back(point_text(node_point[chain.first_node]));
      loose_ends.push_back(point_text(node_point[chain.last_node]));
      for (const auto& step : chain.edges)
        open_curves.push_back(piece_curve[step.first]);
      continue;
    }
    Loop& loop = loops.emplace_back();
    for (const auto& [edge, forward] : chain.edges) {
      const std::vector<Point2>& piece = pieces[edge];
      // Every piece but the last point, which is the next piece's first.
      if (forward)
        loop.insert(loop.end(), piece.begin(), piece.end() - 1);
      else
        loop.insert(loop.end(), piece.rbegin(), piece.rend() - 1);
    }
  }
  if (!open_curves.empty()) {
    std::string ends;
    for (std::size_t i = 0; i < loose_ends.size() && i < 6; ++i)
      ends += (i > 0 ? (i + 1 == loose_ends.size() ? " and " : ", ") : "") + loose_ends[i];
    throw InputError(file_ + ": " + context + ": the boundary does not close: curves " +
                     tag_list(open_curves) + " leave loose ends at " + ends +
                     "; make consecutive curves of each Curve Loop share their end Point "
                     "(Coherence in the built-in kernel, BooleanFragments in OpenCASCADE)");
  }
  return loops;
}

std::vector<Loop> ModelReader::discrete_loops(int tag, const std::string& context) {
  const std::vector<std::vector<std::size_t>> elements = element_corners(2, tag);
  if (elements.empty()) {
    throw InputError(file_ + ": " + context +
                     " comes from a mesh but has no 2D elements; mesh it (gmsh -2) before "
                     "saving the .msh");
  }
  // Boundary edges of the surface mesh are those used by one element only; kept in the
  // order of first use so that loops come out the same on every run.
  struct EdgeUse {
    std::array<std::size_t, 2> directed;
    std::size_t first_use;
    int count;
  };
  std::map<std::pair<std::size_t, std::size_t>, EdgeUse> uses;
  std::size_t order = 0;
  for (const std::vector<std::size_t>& element : elements) {
    for (std::size_t i = 0; i < element.size(); ++i) {
      const std::size_t a = element[i];
      const std::size_t b = element[(i + 1) % element.size()];
      const auto found =
          uses.try_emplace({std::min(a, b), std::max(a, b)}, EdgeUse{{a, b}, order++, 0}).first;
      ++found->second.count;
    }
  }
  std::vector<EdgeUse> boundary;
  for (const auto& use : uses) {
    if (use.second.count == 1)
      boundary.push_back(use.second);
  }
  std::sort(boundary.begin(), boundary.end(),
            [](const EdgeUse& a, const EdgeUse& b) { return a.first_use < b.first_use; });
  std::vector<std::array<std::size_t, 2>> edges;
  for (const EdgeUse& use : boundary)
    edges.push_back(use.directed);
  std::vector<Loop> loops;
  for (const Chain& chain : chain_edges(edges)) {
    if (!chain.closed)
      throw InputError(file_ + ": " + context + ": the boundary of its mesh does not close near " +
                       point_text(planar(nodes_.at(chain.first_node))) +
                       "; save the mesh again from gmsh");
    Loop& loop = loops.emplace_back();
    for (const auto& [edge, forward] : chain.edges)
      loop.push_back(in_plane(nodes_.at(edges[edge][forward ? 0 : 1]), context));
  }
  return loops;
}

} // namespace detail

namespace {

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
