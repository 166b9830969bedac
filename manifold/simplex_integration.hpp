// SPDX-License-Identifier: MIT
// manifold/simplex_integration.hpp — exact monomial integrals over polygons and polyhedra
// from their boundary vertices only (Shi 1997, chapter 7 and the second paper,
// "Simplex Integration for Manifold Method and DDA", eq. 11-14 and 25-32).
#pragma once

#include "mesh/geometry.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <span>
#include <vector>

namespace nmm {

/// Highest total degree the integrators accept. The coefficients a! b! / (a+b+2)! stay far
/// from under/overflow well beyond this; the cap only guards against a runaway argument.
inline constexpr int max_integration_degree = 24;

namespace detail {
/// Storage of a set of moments: inline up to degree 8 in 2D (45 values), on the heap beyond.
/// Why: element matrices need degree <= 4 and are rebuilt for every element every step; a
/// heap allocation per moment set was a measurable part of a step (bench/step_bench.cpp).
class MomentValues {
public:
  MomentValues() = default;
  explicit MomentValues(std::size_t n) : size_(n) {
    if (n > inline_capacity)
      heap_.assign(n, 0.0);
    else
      std::fill_n(inline_.begin(), n, 0.0);
  }
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  [[nodiscard]] double* data() noexcept {
    return size_ > inline_capacity ? heap_.data() : inline_.data();
  }
  [[nodiscard]] const double* data() const noexcept {
    return size_ > inline_capacity ? heap_.data() : inline_.data();
  }
  double& operator[](std::size_t k) noexcept { return data()[k]; }
  double operator[](std::size_t k) const noexcept { return data()[k]; }
  double* begin() noexcept { return data(); }
  double* end() noexcept { return data() + size_; }

private:
  static constexpr std::size_t inline_capacity = 45;
  std::size_t size_ = 0;
  std::array<double, inline_capacity> inline_{};
  std::vector<double> heap_;
};
} // namespace detail

/// The moments M(a, b) = ∫∫ (x - x0)^a (y - y0)^b dx dy of a plane region for all
/// a + b <= degree, about the origin (x0, y0).
class Moments2 {
public:
  Moments2() = default;
  /// All moments zero. @pre 0 <= degree <= max_integration_degree.
  Moments2(int degree, const Point2& origin);

  [[nodiscard]] int degree() const noexcept { return degree_; }
  [[nodiscard]] const Point2& origin() const noexcept { return origin_; }

  /// M(a, b). @pre a, b >= 0 and a + b <= degree().
  [[nodiscard]] double operator()(int a, int b) const { return values_[index(a, b)]; }
  double& operator()(int a, int b) { return values_[index(a, b)]; }

  /// M(0, 0).
  [[nodiscard]] double area() const { return values_[0]; }
  /// The centroid in absolute coordinates. @pre degree() >= 1 and area() != 0.
  [[nodiscard]] Point2 centroid() const;

  /// The same integrals about another origin, by the binomial expansion of
  /// (x - x1)^a = ((x - x0) + (x0 - x1))^a. Exact in exact arithmetic.
  [[nodiscard]] Moments2 shifted_to(const Point2& new_origin) const;

  Moments2& operator+=(const Moments2& other);
  Moments2& operator-=(const Moments2& other);
  Moments2& operator*=(double factor);

  /// Flat index of (a, b): degree n = a + b is stored in block n, ordered by b.
  [[nodiscard]] static int index(int a, int b) noexcept {
    const int n = a + b;
    return n * (n + 1) / 2 + b;
  }
  /// Number of monomials of total degree <= @p degree.
  [[nodiscard]] static int size_for(int degree) noexcept { return (degree + 1) * (degree + 2) / 2; }

private:
  int degree_ = -1;
  Point2 origin_ = Point2::Zero();
  detail::MomentValues values_;
};

/// Oriented integrals over one closed loop (Shi's simplex sum, eq. 25-28 generalised to any
/// degree by eq. 14): positive for a counter-clockwise loop, negative for a clockwise one.
/// A self-touching or self-overlapping loop gives the sum of its winding-weighted parts.
/// @pre 0 <= degree <= max_integration_degree.
[[nodiscard]] Moments2
oriented_loop_moments(std::span<const Point2> loop, int degree, const Point2& origin);

/// Integrals over a simple polygon with holes, whatever the orientation of each loop:
/// the outer loop counts positive, every hole negative.
[[nodiscard]] Moments2 polygon_moments(const Polygon& polygon, int degree, const Point2& origin);

/// Same as above for a polygon without holes.
[[nodiscard]] Moments2
polygon_moments(std::span<const Point2> loop, int degree, const Point2& origin);

/// The centroid of @p polygons (a block: its polygons' areas together), from their first
/// moments about the first polygon's first vertex (accurate far from 0).
/// @pre at least one polygon, and a nonzero area.
[[nodiscard]] Point2 centroid(std::span<const Polygon> polygons);

/// A point or vector in space (for the 3D simplex integration).
using Point3 = Eigen::Vector3d;

/// The moments M(a, b, c) = ∫∫∫ (x - x0)^a (y - y0)^b (z - z0)^c dV of a solid for all
/// a + b + c <= degree, about the origin (x0, y0, z0).
class Moments3 {
public:
  Moments3() = default;
  /// All moments zero. @pre 0 <= degree <= max_integration_degree.
  Moments3(int degree, const Point3& origin);

  [[nodiscard]] int degree() const noexcept { return degree_; }
  [[nodiscard]] const Point3& origin() const noexcept { return origin_; }
  [[nodiscard]] double operator()(int a, int b, int c) const { return values_[index(a, b, c)]; }
  double& operator()(int a, int b, int c) { return values_[index(a, b, c)]; }
  [[nodiscard]] double volume() const { return values_[0]; }
  /// The centroid in absolute coordinates. @pre degree() >= 1 and volume() != 0.
  [[nodiscard]] Point3 centroid() const;
  /// The same integrals about another origin (trinomial expansion).
  [[nodiscard]] Moments3 shifted_to(const Point3& new_origin) const;

  /// Flat index of (a, b, c): block n = a + b + c, then (b, c) as in Moments2.
  [[nodiscard]] static int index(int a, int b, int c) noexcept {
    const int n = a + b + c;
    const int m = b + c;
    return n * (n + 1) * (n + 2) / 6 + m * (m + 1) / 2 + c;
  }
  [[nodiscard]] static int size_for(int degree) noexcept {
    return (degree + 1) * (degree + 2) * (degree + 3) / 6;
  }

private:
  int degree_ = -1;
  Point3 origin_ = Point3::Zero();
  detail::MomentValues values_;
};

/// A closed polyhedron: planar polygonal faces given as vertex index loops, each turning
/// counter-clockwise when seen from outside (outward normal by the right-hand rule).
struct Polyhedron {
  std::vector<Point3> vertices;
  std::vector<std::vector<int>> faces;
};

/// Volume integrals over a closed polyhedron (Shi, second paper, eq. 29-32 generalised by
/// eq. 14): every face is fanned from its first vertex and every fan triangle closed into
/// a tetrahedron with a reference point near the solid. Faces may be concave polygons.
/// @pre 0 <= degree <= max_integration_degree; faces oriented outward and closing the
///      surface (an inward-oriented surface gives the negated moments).
[[nodiscard]] Moments3
polyhedron_moments(const Polyhedron& polyhedron, int degree, const Point3& origin);

} // namespace nmm
