// SPDX-License-Identifier: MIT
// tests/support/gauss_quadrature.hpp — an integration rule independent of the simplex
// integration under test: a fan of triangles with the 7-point, degree-5 Gauss rule.
#pragma once

#include "mesh/geometry.hpp"

#include <cstddef>

namespace nmm::testing {

/// Integral of f over @p polygon's outer loop, a fan of triangles from the vertex @p apex
/// (the loop must be star-shaped from it, e.g. convex), each by the 7-point Gauss rule:
/// exact for polynomials up to degree 5 on each triangle.
template <class F> double gauss_fan(const Polygon& polygon, std::size_t apex, F f) {
  static const double w[7] = {0.225,
                              0.132394152788506,
                              0.132394152788506,
                              0.132394152788506,
                              0.125939180544827,
                              0.125939180544827,
                              0.125939180544827};
  static const double l[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                                 {0.059715871789770, 0.470142064105115, 0.470142064105115},
                                 {0.470142064105115, 0.059715871789770, 0.470142064105115},
                                 {0.470142064105115, 0.470142064105115, 0.059715871789770},
                                 {0.797426985353087, 0.101286507323456, 0.101286507323456},
                                 {0.101286507323456, 0.797426985353087, 0.101286507323456},
                                 {0.101286507323456, 0.101286507323456, 0.797426985353087}};
  const Loop& loop = polygon.outer;
  const std::size_t n = loop.size();
  const Point2& a = loop[apex];
  double total = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t j = (i + 1) % n;
    if (i == apex || j == apex)
      continue;
    const Point2& b = loop[i];
    const Point2& c = loop[j];
    const double area = 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
    for (int g = 0; g < 7; ++g)
      total += area * w[g] * f(Point2(l[g][0] * a + l[g][1] * b + l[g][2] * c));
  }
  return total;
}

} // namespace nmm::testing
