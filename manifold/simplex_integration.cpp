// SPDX-License-Identifier: MIT
#include "manifold/simplex_integration.hpp"

#include "mesh/error.hpp"

#include <array>
#include <stdexcept>
#include <string>

namespace nmm {
namespace {

constexpr int max_degree = max_integration_degree;

// k! for k <= max_degree + 3 (the largest factorial in the 3D coefficient).
struct Factorials {
  std::array<double, max_degree + 4> value{};
  constexpr Factorials() {
    value[0] = 1.0;
    for (int k = 1; k < max_degree + 4; ++k)
      value[k] = value[k - 1] * k;
  }
};
constexpr Factorials factorials{};

// Binomial coefficients C(n, k) for n <= max_degree (Pascal's triangle, exact in double).
struct Binomials {
  std::array<std::array<double, max_degree + 1>, max_degree + 1> value{};
  constexpr Binomials() {
    for (int n = 0; n <= max_degree; ++n) {
      value[n][0] = 1.0;
      for (int k = 1; k <= n; ++k)
        value[n][k] = value[n - 1][k - 1] + (k < n ? value[n - 1][k] : 0.0);
    }
  }
};
constexpr Binomials binomials{};

// Always checked, also in Release: the work arrays below are sized by max_degree.
void check_degree(int degree) {
  if (degree < 0 || degree > max_degree) {
    throw std::out_of_range("simplex integration degree " + std::to_string(degree) +
                            " outside [0, " + std::to_string(max_degree) + "]");
  }
}

// Powers base^0 .. base^degree.
template <std::size_t N> void fill_powers(double base, int degree, std::array<double, N>& powers) {
  powers[0] = 1.0;
  for (int k = 1; k <= degree; ++k)
    powers[k] = powers[k - 1] * base;
}

constexpr int size2 = (max_degree + 1) * (max_degree + 2) / 2;

// True when @p origin lies in the bounding box of @p points grown by its own size on every
// side: close enough to fan from directly (see oriented_loop_moments).
template <typename Point> bool is_near(std::span<const Point> points, const Point& origin) {
  Point low = points.front();
  Point high = points.front();
  for (const Point& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const Point margin = high - low;
  return ((origin - low).array() >= -margin.array()).all() &&
         ((high - origin).array() >= -margin.array()).all();
}

// Adds J * H(a, b) for the triangle (0, p, q) to `sum`, where by Shi's eq. 14 with P0 at
// the origin
//   ∫∫_(0 p q) x^a y^b = J a! b! / (a+b+2)! * H(a, b),
//   H(a, b) = Σ_{i<=a, k<=b} C(i+k, i) C(a-i+b-k, a-i) px^i py^k qx^(a-i) qy^(b-k),
// and J = px qy - qx py. The double sum is the coefficient of s^a t^b in
// 1 / ((1 - s px - t py)(1 - s qx - t qy)), which gives the O(1)-per-entry recurrences
//   G(a, b) = px G(a-1, b) + py G(a, b-1),        G(0, 0) = 1,
//   H(a, b) = G(a, b) + qx H(a-1, b) + qy H(a, b-1).
void add_triangle_terms(const Point2& p, const Point2& q, int degree, double* sum) {
  const double jacobian = p.x() * q.y() - q.x() * p.y();
  if (jacobian == 0.0)
    return;
  // Only entries of degree < n are read while degree n is written: no zero fill needed
  // (this function is the hot loop of every element matrix).
  std::array<double, size2> g; // NOLINT(cppcoreguidelines-pro-type-member-init)
  std::array<double, size2> h; // NOLINT(cppcoreguidelines-pro-type-member-init)
  g[0] = 1.0;
  h[0] = 1.0;
  sum[0] += jacobian;
  for (int n = 1; n <= degree; ++n) {
    const int block = n * (n + 1) / 2;
    const int previous = (n - 1) * n / 2;
    for (int b = 0; b <= n; ++b) {
      const int a = n - b;
      // (a-1, b) sits at previous + b, (a, b-1) at previous + b - 1.
      double gv = 0.0;
      double hv = 0.0;
      if (a > 0) {
        gv += p.x() * g[previous + b];
        hv += q.x() * h[previous + b];
      }
      if (b > 0) {
        gv += p.y() * g[previous + b - 1];
        hv += q.y() * h[previous + b - 1];
      }
      hv += gv;
      g[block + b] = gv;
      h[block + b] = hv;
      sum[block + b] += jacobian * hv;
    }
  }
}

// Multiplies the accumulated J * H(a, b) by a! b! / (a+b+2)!.
void apply_coefficients2(int degree, double* values) {
  for (int n = 0; n <= degree; ++n) {
    for (int b = 0; b <= n; ++b) {
      const int a = n - b;
      values[Moments2::index(a, b)] *=
          factorials.value[a] * factorials.value[b] / factorials.value[n + 2];
    }
  }
}

} // namespace

// ---------------------------------------------------------------------------- Moments2

Moments2::Moments2(int degree, const Point2& origin)
    : degree_(degree), origin_(origin), values_(static_cast<std::size_t>(size_for(degree))) {
  check_degree(degree);
}

Point2 Moments2::centroid() const {
  NMM_ASSERT(degree_ >= 1, "centroid needs first moments");
  NMM_ASSERT(area() != 0.0, "centroid of a region of zero area");
  return origin_ + Point2((*this)(1, 0), (*this)(0, 1)) / area();
}

Moments2 Moments2::shifted_to(const Point2& new_origin) const {
  Moments2 result(degree_, new_origin);
  const Point2 d = origin_ - new_origin;
  if (d.isZero(0.0)) {
    result.values_ = values_;
    return result;
  }
  std::array<double, max_degree + 1> dx{};
  std::array<double, max_degree + 1> dy{};
  fill_powers(d.x(), degree_, dx);
  fill_powers(d.y(), degree_, dy);
  for (int a = 0; a <= degree_; ++a) {
    for (int b = 0; a + b <= degree_; ++b) {
      double value = 0.0;
      for (int i = 0; i <= a; ++i) {
        const double x_factor = binomials.value[a][i] * dx[a - i];
        for (int j = 0; j <= b; ++j) {
          value += x_factor * binomials.value[b][j] * dy[b - j] * (*this)(i, j);
        }
      }
      result(a, b) = value;
    }
  }
  return result;
}

Moments2& Moments2::operator+=(const Moments2& other) {
  NMM_ASSERT(degree_ == other.degree_ && origin_ == other.origin_,
             "adding moments of different degree or origin");
  for (std::size_t k = 0; k < values_.size(); ++k)
    values_[k] += other.values_[k];
  return *this;
}

Moments2& Moments2::operator-=(const Moments2& other) {
  NMM_ASSERT(degree_ == other.degree_ && origin_ == other.origin_,
             "subtracting moments of different degree or origin");
  for (std::size_t k = 0; k < values_.size(); ++k)
    values_[k] -= other.values_[k];
  return *this;
}

Moments2& Moments2::operator*=(double factor) {
  for (double& v : values_)
    v *= factor;
  return *this;
}

Moments2 oriented_loop_moments(std::span<const Point2> loop, int degree, const Point2& origin) {
  check_degree(degree);
  if (loop.size() < 3)
    return Moments2(degree, origin);
  // Shi sums simplices P0 Pk Pk+1 with P0 = (0, 0) (eq. 25); any P0 gives the same result
  // in exact arithmetic. In floating point the fan point sets the size of the summed terms:
  // fanning from the requested origin when it lies near the loop needs no shift at all;
  // for an origin far away we fan from the first vertex (small coordinates, two edges drop
  // out) and shift binomially, where the term d^a d^b * area dominates and nothing cancels.
  const Point2 reference = is_near(loop, origin) ? origin : loop.front();
  Moments2 local(degree, reference);
  double* sum = &local(0, 0);
  for (std::size_t k = 0; k < loop.size(); ++k) {
    const Point2& next = loop[k + 1 < loop.size() ? k + 1 : 0];
    add_triangle_terms(loop[k] - reference, next - reference, degree, sum);
  }
  apply_coefficients2(degree, sum);
  return local.shifted_to(origin);
}

Moments2 polygon_moments(std::span<const Point2> loop, int degree, const Point2& origin) {
  Moments2 result = oriented_loop_moments(loop, degree, origin);
  if (result.area() < 0.0)
    result *= -1.0;
  return result;
}

Moments2 polygon_moments(const Polygon& polygon, int degree, const Point2& origin) {
  Moments2 result = polygon_moments(polygon.outer, degree, origin);
  for (const Loop& hole : polygon.holes)
    result -= polygon_moments(hole, degree, origin);
  return result;
}

Point2 centroid(std::span<const Polygon> polygons) {
  const Point2 origin = polygons.front().outer.front();
  Moments2 moments(1, origin);
  for (const Polygon& polygon : polygons)
    moments += polygon_moments(polygon, 1, origin);
  return moments.centroid();
}

// ---------------------------------------------------------------------------- Moments3

namespace {

// Adds J * H(a, b, c) for the tetrahedron (0, A, B, C), the 3D analogue of
// add_triangle_terms: by Shi's eq. 14 with n = 3 and P0 at the origin,
//   ∫∫∫ x^a y^b z^c = J a! b! c! / (a+b+c+3)! * H(a, b, c),
// H the coefficient of s^a t^b u^c in Π_{V in A,B,C} 1 / (1 - s Vx - t Vy - u Vz), and
// J = det[A; B; C]. Three chained recurrences, one per vertex.
void add_tetrahedron_terms(const Point3& pa,
                           const Point3& pb,
                           const Point3& pc,
                           int degree,
                           std::vector<double>& ga,
                           std::vector<double>& gab,
                           std::vector<double>& h,
                           double* sum) {
  const double jacobian = pa.dot(pb.cross(pc));
  if (jacobian == 0.0)
    return;
  ga[0] = gab[0] = h[0] = 1.0;
  sum[0] += jacobian;
  for (int n = 1; n <= degree; ++n) {
    for (int a = n; a >= 0; --a) {
      for (int b = n - a; b >= 0; --b) {
        const int c = n - a - b;
        const int here = Moments3::index(a, b, c);
        double va = 0.0;
        double vab = 0.0;
        double vh = 0.0;
        if (a > 0) {
          const int i = Moments3::index(a - 1, b, c);
          va += pa.x() * ga[i];
          vab += pb.x() * gab[i];
          vh += pc.x() * h[i];
        }
        if (b > 0) {
          const int i = Moments3::index(a, b - 1, c);
          va += pa.y() * ga[i];
          vab += pb.y() * gab[i];
          vh += pc.y() * h[i];
        }
        if (c > 0) {
          const int i = Moments3::index(a, b, c - 1);
          va += pa.z() * ga[i];
          vab += pb.z() * gab[i];
          vh += pc.z() * h[i];
        }
        vab += va;
        vh += vab;
        ga[here] = va;
        gab[here] = vab;
        h[here] = vh;
        sum[here] += jacobian * vh;
      }
    }
  }
}

} // namespace

Moments3::Moments3(int degree, const Point3& origin)
    : degree_(degree), origin_(origin), values_(static_cast<std::size_t>(size_for(degree))) {
  check_degree(degree);
}

Point3 Moments3::centroid() const {
  NMM_ASSERT(degree_ >= 1, "centroid needs first moments");
  NMM_ASSERT(volume() != 0.0, "centroid of a solid of zero volume");
  return origin_ + Point3((*this)(1, 0, 0), (*this)(0, 1, 0), (*this)(0, 0, 1)) / volume();
}

Moments3 Moments3::shifted_to(const Point3& new_origin) const {
  Moments3 result(degree_, new_origin);
  const Point3 d = origin_ - new_origin;
  if (d.isZero(0.0)) {
    result.values_ = values_;
    return result;
  }
  std::array<double, max_degree + 1> dx{};
  std::array<double, max_degree + 1> dy{};
  std::array<double, max_degree + 1> dz{};
  fill_powers(d.x(), degree_, dx);
  fill_powers(d.y(), degree_, dy);
  fill_powers(d.z(), degree_, dz);
  for (int a = 0; a <= degree_; ++a) {
    for (int b = 0; a + b <= degree_; ++b) {
      for (int c = 0; a + b + c <= degree_; ++c) {
        double value = 0.0;
        for (int i = 0; i <= a; ++i) {
          const double fx = binomials.value[a][i] * dx[a - i];
          for (int j = 0; j <= b; ++j) {
            const double fxy = fx * binomials.value[b][j] * dy[b - j];
            for (int k = 0; k <= c; ++k) {
              value += fxy * binomials.value[c][k] * dz[c - k] * (*this)(i, j, k);
            }
          }
        }
        result(a, b, c) = value;
      }
    }
  }
  return result;
}

Moments3 polyhedron_moments(const Polyhedron& polyhedron, int degree, const Point3& origin) {
  check_degree(degree);
  if (polyhedron.vertices.empty())
    return Moments3(degree, origin);
  // P0 at the requested origin when it is near the solid, else at a vertex and shifted
  // (eq. 29 takes (0, 0, 0); the reasoning is that of oriented_loop_moments).
  const Point3 reference = is_near(std::span<const Point3>(polyhedron.vertices), origin)
                               ? origin
                               : polyhedron.vertices.front();
  Moments3 local(degree, reference);
  const auto size = static_cast<std::size_t>(Moments3::size_for(degree));
  std::vector<double> ga(size);
  std::vector<double> gab(size);
  std::vector<double> h(size);
  double* sum = &local(0, 0, 0);
  const auto n_vertices = static_cast<int>(polyhedron.vertices.size());
  for (const std::vector<int>& face : polyhedron.faces) {
    for (int v : face) {
      NMM_ASSERT(v >= 0 && v < n_vertices, "polyhedron face names a missing vertex");
    }
    if (face.size() < 3)
      continue;
    const Point3 first = polyhedron.vertices[face[0]] - reference;
    for (std::size_t k = 1; k + 1 < face.size(); ++k) {
      add_tetrahedron_terms(first, polyhedron.vertices[face[k]] - reference,
                            polyhedron.vertices[face[k + 1]] - reference, degree, ga, gab, h, sum);
    }
  }
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; a + b <= degree; ++b) {
      for (int c = 0; a + b + c <= degree; ++c) {
        local(a, b, c) *= factorials.value[a] * factorials.value[b] * factorials.value[c] /
                          factorials.value[a + b + c + 3];
      }
    }
  }
  return local.shifted_to(origin);
}

} // namespace nmm
