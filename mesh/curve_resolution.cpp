// SPDX-License-Identifier: MIT
#include "mesh/curve_resolution.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>

namespace nmm {

double automatic_curve_tolerance(double diagonal, double cover_size) {
  const double from_model = 1.0e-3 * diagonal;
  if (!(cover_size > 0.0))
    return from_model;
  return std::min(from_model, curve_deviation_per_cover_size * cover_size);
}

namespace {

/// Signed turn (radians, counter-clockwise positive) from direction @p in to @p out.
double turn(const Point2& in, const Point2& out) {
  const double cross = in.x() * out.y() - in.y() * out.x();
  return std::atan2(cross, in.dot(out));
}

} // namespace

std::vector<CoarseSegment>
coarse_segments(const std::vector<Point2>& polyline, bool closed, double cover_size) {
  std::vector<CoarseSegment> coarse;
  const std::size_t n = polyline.size();
  if (n < 2 || !(cover_size > 0.0))
    return coarse;
  const std::size_t n_segments = closed ? n : n - 1;
  const auto point = [&](std::size_t i) -> const Point2& { return polyline[i % n]; };
  // The turn at vertex i, where segment i - 1 meets segment i; none at an open end.
  const auto turn_at = [&](std::size_t i) -> std::optional<double> {
    if (!closed && (i == 0 || i == n - 1))
      return std::nullopt;
    const Point2& previous = point(i + n - 1);
    return turn(point(i) - previous, point(i + 1) - point(i));
  };
  for (std::size_t s = 0; s < n_segments; ++s) {
    const Point2& a = point(s);
    const Point2& b = point(s + 1);
    const double length = (b - a).norm();
    if (!(length > cover_size))
      continue;
    const std::optional<double> first = turn_at(s);
    const std::optional<double> second = turn_at(s + 1);
    if (!first && !second)
      continue;
    double smallest = 0.0;
    if (first && second) {
      if (*first * *second <= 0.0)
        continue; // a straight end, or an inflection
      smallest = std::min(std::abs(*first), std::abs(*second));
    } else {
      smallest = std::abs(first ? *first : *second);
    }
    if (std::max(std::abs(first.value_or(0.0)), std::abs(second.value_or(0.0))) > largest_bend_turn)
      continue; // a corner
    const double deviation = length * smallest / 8.0;
    if (deviation > curve_deviation_per_cover_size * cover_size)
      coarse.push_back({a, b, length, deviation});
  }
  return coarse;
}

} // namespace nmm
