// SPDX-License-Identifier: MIT
// Curves coarser than the cover mesh: the warnings for Physical Curves and surface outlines
// whose sampled or meshed segments are longer than the cover size where they bend.
#include "io/gmsh_internal.hpp"
#include "io/text.hpp"
#include "mesh/curve_resolution.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace nmm::detail {

namespace {

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

} // namespace

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

} // namespace nmm::detail
