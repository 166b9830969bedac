// SPDX-License-Identifier: MIT
// mesh/curve_resolution.hpp — how finely a curve must be sampled for the cover mesh, and
// where a polyline that stands for a curve is coarser than the cover mesh.
#pragma once

#include "mesh/geometry.hpp"

#include <vector>

namespace nmm {

/// The automatic chord deviation of sampled curves, as a fraction of the cover size: the
/// covers of triangles of edge h then see the curve to 1e-2 h.
inline constexpr double curve_deviation_per_cover_size = 1e-2;

/// The automatic chord deviation (m) of curves sampled to polylines: the finer of 1e-3 of
/// @p diagonal (the material's bounding-box diagonal) and curve_deviation_per_cover_size ×
/// @p cover_size; the first alone when @p cover_size is 0 (not known). A circle of radius R
/// sampled to a deviation d has chords of sqrt(8 R d): a 6 m tunnel at a cover size of
/// 0.5 m has d = 5 mm and chords of at most 0.35 m (a 64-gon).
[[nodiscard]] double automatic_curve_tolerance(double diagonal, double cover_size);

/// The largest turn (radians) at a vertex of a polyline that is taken for a bend of a
/// sampled curve; a larger turn is a corner. A regular octagon turns by 45° at each vertex
/// (a curve sampled coarsely), a hexagon by 60° (a polygon).
inline constexpr double largest_bend_turn = 50.0 * 3.14159265358979323846 / 180.0;

/// One segment of a polyline that stands for a curve but is coarser than the cover mesh.
struct CoarseSegment {
  Point2 a;
  Point2 b;
  /// |b - a| (m).
  double length = 0.0;
  /// Estimated distance (m) between the segment and the curve it stands for: the sagitta of
  /// a circle that turns by the smaller of the turns at the segment's ends, length × turn / 8.
  double deviation = 0.0;
};

/// The segments of @p polyline (closed: its last vertex joins the first) that lie on a bend
/// and are coarser than triangles of edge @p cover_size: longer than @p cover_size, with an
/// estimated deviation above curve_deviation_per_cover_size × @p cover_size (both bounds of
/// the automatic sampling broken). A segment lies on a bend when the polyline turns at each
/// of its ends that has a neighbour the same way, by at most largest_bend_turn (the end of
/// an open polyline has none: a quarter circle of two chords is a bend). So straight runs,
/// corners of polygons, a straight segment next to a rounded corner (it does not turn at its
/// other end) and a polyline of one segment are never coarse.
[[nodiscard]] std::vector<CoarseSegment>
coarse_segments(const std::vector<Point2>& polyline, bool closed, double cover_size);

} // namespace nmm
