// SPDX-License-Identifier: MIT
#include "mesh/geometry.hpp"

#include <cmath>
#include <sstream>

namespace nmm {

std::string point_text(const Point2& p, int digits) {
  std::ostringstream out;
  out.precision(digits);
  out << '(' << p.x() << ", " << p.y() << ')';
  return out.str();
}

void BoundingBox::extend(const Point2& p) {
  if (is_empty()) {
    min = p;
    max = p;
    return;
  }
  min = min.cwiseMin(p);
  max = max.cwiseMax(p);
}

void CompensatedSum::add(double value) noexcept {
  const double t = sum_ + value;
  if (std::abs(sum_) >= std::abs(value))
    compensation_ += (sum_ - t) + value;
  else
    compensation_ += (value - t) + sum_;
  sum_ = t;
}

double signed_area(std::span<const Point2> loop) {
  if (loop.size() < 3)
    return 0.0;
  // Fan from the first vertex: cross products of small relative vectors do not cancel
  // catastrophically the way absolute coordinates far from the origin would.
  const Point2& base = loop.front();
  double twice_area = 0.0;
  for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
    const Point2 p = loop[k] - base;
    const Point2 q = loop[k + 1] - base;
    twice_area += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice_area;
}

bool is_counter_clockwise(std::span<const Point2> loop) { return signed_area(loop) > 0.0; }

double area(const Polygon& polygon) {
  double result = std::abs(signed_area(polygon.outer));
  for (const Loop& hole : polygon.holes)
    result -= std::abs(signed_area(hole));
  return result;
}

BoundingBox bounding_box(std::span<const Point2> points) {
  BoundingBox box;
  for (const Point2& p : points)
    box.extend(p);
  return box;
}

} // namespace nmm
