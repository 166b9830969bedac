// SPDX-License-Identifier: MIT
#include "mesh/physical_mesh.hpp"

#include "mesh/error.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace nmm {

namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalPolygon = CGAL::Polygon_2<Epick>;

template <class Items> int find_by_name(const Items& items, const std::string& name) {
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].name == name)
      return static_cast<int>(i);
  }
  return -1;
}

template <class Items> std::string names_of(const Items& items) {
  std::string result;
  for (const auto& item : items) {
    if (!result.empty())
      result += ", ";
    result += '"' + item.name + '"';
  }
  return result.empty() ? std::string("(none)") : result;
}

[[noreturn]] void fail(const PhysicalMesh& physical, const std::string& message) {
  throw InputError(physical.source.empty() ? message : physical.source + ": " + message);
}

bool is_finite(const Point2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

/// Removes consecutive duplicates (also last == first), so that gmsh loops that repeat the
/// closing vertex or sample a curve end twice are accepted.
void remove_repeated_vertices(Loop& loop) {
  loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
  while (loop.size() > 1 && loop.front() == loop.back())
    loop.pop_back();
}

CgalPolygon to_cgal(const Loop& loop) {
  CgalPolygon polygon;
  for (const Point2& p : loop)
    polygon.push_back(Epick::Point_2(p.x(), p.y()));
  return polygon;
}

void check_loop(const PhysicalMesh& physical,
                const std::string& region,
                Loop& loop,
                const char* what) {
  for (const Point2& p : loop) {
    if (!is_finite(p))
      fail(physical, "material region \"" + region + "\": " + what +
                         " has a non-finite coordinate; check the geometry file");
  }
  remove_repeated_vertices(loop);
  if (loop.size() < 3) {
    fail(physical, "material region \"" + region + "\": " + what + " near " +
                       (loop.empty() ? std::string("?") : point_text(loop.front())) +
                       " has fewer than 3 distinct vertices; a Physical Surface needs a closed "
                       "curve loop");
  }
  const CgalPolygon polygon = to_cgal(loop);
  if (!polygon.is_simple()) {
    fail(physical, "material region \"" + region + "\": " + what + " near " +
                       point_text(loop.front()) +
                       " crosses or touches itself; redraw the surface so that its boundary "
                       "is a simple closed loop");
  }
  if (polygon.orientation() == CGAL::COLLINEAR || signed_area(loop) == 0.0) {
    fail(physical, "material region \"" + region + "\": " + what + " near " +
                       point_text(loop.front()) + " has zero area");
  }
}

} // namespace

int PhysicalMesh::find_region(const std::string& name) const { return find_by_name(regions, name); }
int PhysicalMesh::find_curve(const std::string& name) const { return find_by_name(curves, name); }
int PhysicalMesh::find_point(const std::string& name) const { return find_by_name(points, name); }
std::string PhysicalMesh::region_names() const { return names_of(regions); }
std::string PhysicalMesh::curve_names() const { return names_of(curves); }
std::string PhysicalMesh::point_names() const { return names_of(points); }

BoundingBox material_bounding_box(const PhysicalMesh& physical) {
  BoundingBox box;
  for (const MaterialRegion& region : physical.regions) {
    for (const Polygon& polygon : region.polygons) {
      for (const Point2& p : polygon.outer)
        box.extend(p);
    }
  }
  return box;
}

double material_area(const PhysicalMesh& physical) {
  CompensatedSum total;
  for (const MaterialRegion& region : physical.regions) {
    for (const Polygon& polygon : region.polygons)
      total += area(polygon);
  }
  return total.value();
}

void validate_physical_mesh(PhysicalMesh& physical) {
  if (physical.regions.empty()) {
    fail(physical, "the geometry has no Physical Surface; name each material region with "
                   "Physical Surface(\"rock\") = {...} so the case file can refer to it");
  }
  for (MaterialRegion& region : physical.regions) {
    if (region.polygons.empty())
      fail(physical, "Physical Surface \"" + region.name + "\" holds no surface");
    for (Polygon& polygon : region.polygons) {
      check_loop(physical, region.name, polygon.outer, "the outer boundary");
      if (!is_counter_clockwise(polygon.outer))
        std::reverse(polygon.outer.begin(), polygon.outer.end());
      const CgalPolygon outer = to_cgal(polygon.outer);
      for (Loop& hole : polygon.holes) {
        check_loop(physical, region.name, hole, "a hole boundary");
        if (is_counter_clockwise(hole))
          std::reverse(hole.begin(), hole.end());
        // A hole must lie inside its outer loop; touching at a vertex is allowed (the
        // arrangement handles it), crossing is not. Checking every vertex is exact and
        // catches holes drawn outside the surface.
        for (const Point2& p : hole) {
          if (outer.bounded_side(Epick::Point_2(p.x(), p.y())) == CGAL::ON_UNBOUNDED_SIDE) {
            fail(physical, "material region \"" + region.name + "\": the hole through " +
                               point_text(p) + " is not inside the surface's outer boundary");
          }
        }
      }
    }
  }
  for (NamedCurve& curve : physical.curves) {
    double length = 0.0;
    for (std::vector<Point2>& line : curve.polylines) {
      for (const Point2& p : line) {
        if (!is_finite(p))
          fail(physical, "Physical Curve \"" + curve.name + "\" has a non-finite coordinate");
      }
      line.erase(std::unique(line.begin(), line.end()), line.end());
      for (std::size_t k = 1; k < line.size(); ++k)
        length += (line[k] - line[k - 1]).norm();
    }
    std::erase_if(curve.polylines, [](const std::vector<Point2>& l) { return l.size() < 2; });
    if (curve.polylines.empty() || length == 0.0) {
      fail(physical, "Physical Curve \"" + curve.name +
                         "\" has no curve of non-zero length; add curves to the group or "
                         "remove it");
    }
  }
  for (const NamedPoint& group : physical.points) {
    if (group.points.empty())
      fail(physical, "Physical Point \"" + group.name + "\" holds no point");
    for (const Point2& p : group.points) {
      if (!is_finite(p))
        fail(physical, "Physical Point \"" + group.name + "\" has a non-finite coordinate");
    }
  }
}

} // namespace nmm
