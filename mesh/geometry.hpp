// SPDX-License-Identifier: MIT
// mesh/geometry.hpp — points, loops and polygons with holes in double precision.
#pragma once

#include <Eigen/Core>

#include <span>
#include <string>
#include <vector>

namespace nmm {

/// A point or vector in the plane, in metres.
using Point2 = Eigen::Vector2d;

/// A closed polygonal loop: vertices in order, the last one NOT repeated.
using Loop = std::vector<Point2>;

/// A polygon with holes. The orientation of the loops is free: every function that takes
/// a Polygon treats `outer` as material and each of `holes` as a void inside it.
struct Polygon {
  Loop outer;
  std::vector<Loop> holes;
};

/// Axis-aligned bounding box; empty (min > max) when default constructed.
struct BoundingBox {
  Point2 min{1.0, 1.0};
  Point2 max{-1.0, -1.0};

  [[nodiscard]] bool is_empty() const { return min.x() > max.x() || min.y() > max.y(); }
  /// Grows the box to contain @p p.
  void extend(const Point2& p);
  /// max - min; (0,0) for a single point, meaningless when empty.
  [[nodiscard]] Point2 size() const { return max - min; }
};

/// "(x, y)" with @p digits significant digits, for messages.
[[nodiscard]] std::string point_text(const Point2& p, int digits = 10);

/// Signed area of a loop by the shoelace formula (Shi 1997, simplex integration eq. 25):
/// positive when counter-clockwise. Computed about the first vertex so that a small loop
/// far from the origin keeps its accuracy.
[[nodiscard]] double signed_area(std::span<const Point2> loop);

/// True when the loop turns counter-clockwise (positive signed area).
[[nodiscard]] bool is_counter_clockwise(std::span<const Point2> loop);

/// Area of a polygon with holes: |outer| - sum |hole|, whatever the loop orientations.
[[nodiscard]] double area(const Polygon& polygon);

/// Neumaier's compensated summation: the sum of many terms to about one rounding error of
/// the result. Why: 1.5e5 element areas summed naively drift by 1e-12 relative, which would
/// hide a real tiling error of that size.
class CompensatedSum {
public:
  void add(double value) noexcept;
  CompensatedSum& operator+=(double value) noexcept {
    add(value);
    return *this;
  }
  [[nodiscard]] double value() const noexcept { return sum_ + compensation_; }

private:
  double sum_ = 0.0;
  double compensation_ = 0.0;
};

/// Smallest box holding every vertex of @p points.
[[nodiscard]] BoundingBox bounding_box(std::span<const Point2> points);

} // namespace nmm
