// SPDX-License-Identifier: MIT
// Simplex integration against Shi's published tables, closed forms and an independent
// quadrature (Gauss-Legendre on collapsed triangles and tetrahedra of a fan).
#include "manifold/regular_shapes.hpp"
#include "manifold/simplex_integration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

namespace nmm {
namespace {

// ------------------------------------------------------------- independent quadrature

struct GaussRule {
  std::vector<double> x; // nodes on [0, 1]
  std::vector<double> w; // weights summing to 1
};

// n-point Gauss-Legendre rule by Newton iteration on P_n (exact to degree 2n - 1).
GaussRule gauss_legendre(int n) {
  GaussRule rule;
  for (int i = 1; i <= n; ++i) {
    double t = std::cos(std::numbers::pi * (i - 0.25) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0;
      double p1 = t;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * t * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (t * p1 - p0) / (t * t - 1.0);
      const double step = p1 / derivative;
      t -= step;
      if (std::abs(step) < 1e-16)
        break;
    }
    rule.x.push_back(0.5 * (1.0 - t));
    rule.w.push_back(1.0 / ((1.0 - t * t) * derivative * derivative));
  }
  return rule;
}

// ∫ x^a y^b over the triangle (p0, p1, p2), unsigned, by the Duffy map
// (s, t) -> p0 + s (p1 - p0) + t (1 - s) (p2 - p0) with Jacobian |J| (1 - s).
// 12 points per direction integrate degree <= 22 exactly (the map adds one degree in s).
double triangle_quadrature(const Point2& p0, const Point2& p1, const Point2& p2, int a, int b) {
  static const GaussRule rule = gauss_legendre(12);
  const Point2 e1 = p1 - p0;
  const Point2 e2 = p2 - p0;
  const double jacobian = std::abs(e1.x() * e2.y() - e2.x() * e1.y());
  double sum = 0.0;
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    for (std::size_t j = 0; j < rule.x.size(); ++j) {
      const double s = rule.x[i];
      const double t = rule.x[j] * (1.0 - s);
      const Point2 p = p0 + s * e1 + t * e2;
      sum += rule.w[i] * rule.w[j] * (1.0 - s) * std::pow(p.x(), a) * std::pow(p.y(), b);
    }
  }
  return jacobian * sum;
}

// ∫ x^a y^b z^c over the tetrahedron (p0..p3), unsigned, by the collapsed map with
// Jacobian |J| (1 - s)^2 (1 - t); 10 points per direction cover degree <= 17.
double tetrahedron_quadrature(
    const Point3& p0, const Point3& p1, const Point3& p2, const Point3& p3, int a, int b, int c) {
  static const GaussRule rule = gauss_legendre(10);
  const Point3 e1 = p1 - p0;
  const Point3 e2 = p2 - p0;
  const Point3 e3 = p3 - p0;
  const double jacobian = std::abs(e1.dot(e2.cross(e3)));
  double sum = 0.0;
  for (std::size_t i = 0; i < rule.x.size(); ++i) {
    for (std::size_t j = 0; j < rule.x.size(); ++j) {
      for (std::size_t k = 0; k < rule.x.size(); ++k) {
        const double s = rule.x[i];
        const double t = rule.x[j] * (1.0 - s);
        const double u = rule.x[k] * (1.0 - s) * (1.0 - rule.x[j]);
        const Point3 p = p0 + s * e1 + t * e2 + u * e3;
        sum += rule.w[i] * rule.w[j] * rule.w[k] * (1.0 - s) * (1.0 - s) * (1.0 - rule.x[j]) *
               std::pow(p.x(), a) * std::pow(p.y(), b) * std::pow(p.z(), c);
      }
    }
  }
  return jacobian * sum;
}

// ------------------------------------------------------------------ test geometries

// A star-shaped, generally concave polygon about `center`: vertices at increasing angles
// with radii in [r_min, r_max]. A fan from the centre is a valid triangulation of it.
Loop random_star_polygon(
    std::mt19937& rng, const Point2& center, int n, double r_min, double r_max) {
  std::uniform_real_distribution<double> radius(r_min, r_max);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  Loop loop;
  for (int k = 0; k < n; ++k) {
    const double angle = 2.0 * std::numbers::pi * (k + 0.5 + jitter(rng)) / n;
    const double r = radius(rng);
    loop.push_back(center + r * Point2(std::cos(angle), std::sin(angle)));
  }
  return loop;
}

double star_quadrature(const Loop& loop, const Point2& center, int a, int b) {
  double sum = 0.0;
  for (std::size_t k = 0; k < loop.size(); ++k) {
    sum += triangle_quadrature(center, loop[k], loop[(k + 1) % loop.size()], a, b);
  }
  return sum;
}

double max_radius(std::span<const Point2> loop, const Point2& origin) {
  double r = 0.0;
  for (const Point2& p : loop)
    r = std::max(r, (p - origin).norm());
  return r;
}

// Tolerance scale for M(a, b): the moments of |x|^a |y|^b are bounded by area * R^(a+b),
// R the largest vertex distance from the origin. Relative to this scale, not to M(a, b)
// itself, because odd moments of symmetric shapes cancel to ~0.
double moment_scale(double area, double radius, int degree) {
  return std::abs(area) * std::pow(std::max(radius, 1.0e-300), degree);
}

// ----------------------------------------------------------------- Shi's tables (2D)

TEST(SimplexIntegration, RegularPolygonsReproduceShiAreasAndCentroids) {
  const double s3 = std::sqrt(3.0);
  const double s5 = std::sqrt(5.0);
  // Shi's table: triangle 1.299038, square 2.000000, pentagon 2.377641, hexagon 2.598076,
  // with the closed forms beside them; centroids at the centre of the circle.
  const struct {
    int n;
    double closed_form;
    double table;
  } rows[] = {{3, 0.75 * s3, 1.299038},
              {4, 2.0, 2.000000},
              {5, 0.625 * std::sqrt(10.0 + 2.0 * s5), 2.377641},
              {6, 1.5 * s3, 2.598076}};
  for (const auto& row : rows) {
    const Loop loop = regular_polygon(row.n);
    const Moments2 m = polygon_moments(loop, 1, Point2::Zero());
    // Vertices from sin/cos carry ~1 ulp each: 1e-14 relative covers the sum of n terms.
    EXPECT_NEAR(m.area(), row.closed_form, 1e-14 * row.closed_form) << row.n << "-gon";
    // The table prints 6 decimals: agreement to half a unit in the last place.
    EXPECT_NEAR(m.area(), row.table, 5e-7) << row.n << "-gon";
    EXPECT_NEAR(m.centroid().x(), 0.0, 1e-15) << row.n << "-gon";
    EXPECT_NEAR(m.centroid().y(), 0.0, 1e-15) << row.n << "-gon";
  }
}

TEST(SimplexIntegration, OrientedLoopIntegralChangesSignWithOrientation) {
  // Shi's vertex formula runs clockwise: the oriented (simplex) integral is negative.
  const Loop clockwise = regular_polygon(6);
  const Loop counter_clockwise(clockwise.rbegin(), clockwise.rend());
  const Moments2 negative = oriented_loop_moments(clockwise, 4, Point2(0.3, -0.2));
  const Moments2 positive = oriented_loop_moments(counter_clockwise, 4, Point2(0.3, -0.2));
  EXPECT_LT(negative.area(), 0.0);
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; a + b <= 4; ++b) {
      // The reversed loop fans from another first vertex: equal up to rounding of terms
      // of size moment_scale (radius 1.4 about this origin).
      EXPECT_NEAR(negative(a, b), -positive(a, b),
                  1e-14 * moment_scale(positive.area(), 1.4, a + b))
          << a << "," << b;
    }
  }
}

TEST(SimplexIntegration, RectangleMatchesClosedFormToDegreeTwelve) {
  // ∫_x0^x1 ∫_y0^y1 x^a y^b = (x1^(a+1) - x0^(a+1)) (y1^(b+1) - y0^(b+1)) / ((a+1)(b+1)).
  const double x0 = -0.7;
  const double x1 = 1.3;
  const double y0 = 0.4;
  const double y1 = 2.1;
  const Loop loop{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
  const int degree = 12;
  const Moments2 m = polygon_moments(loop, degree, Point2::Zero());
  const double radius = max_radius(loop, Point2::Zero());
  for (int a = 0; a <= degree; ++a) {
    for (int b = 0; a + b <= degree; ++b) {
      const double exact = (std::pow(x1, a + 1) - std::pow(x0, a + 1)) / (a + 1) *
                           (std::pow(y1, b + 1) - std::pow(y0, b + 1)) / (b + 1);
      EXPECT_NEAR(m(a, b), exact, 1e-14 * moment_scale(m.area(), radius, a + b)) << a << "," << b;
    }
  }
}

// ------------------------------------------------ random concave polygons against Gauss

TEST(SimplexIntegration, RandomConcavePolygonsMatchGaussQuadratureToDegreeEight) {
  std::mt19937 rng(20261122);
  std::uniform_real_distribution<double> offset(-2.0, 2.0);
  std::uniform_int_distribution<int> vertices(5, 24);
  const int degree = 8;
  for (int trial = 0; trial < 40; ++trial) {
    const Point2 center(offset(rng), offset(rng));
    Loop loop = random_star_polygon(rng, center, vertices(rng), 0.2, 1.0);
    if (trial % 2 == 1)
      std::reverse(loop.begin(), loop.end()); // both orientations
    const Point2 origin(offset(rng), offset(rng));
    const Moments2 m = polygon_moments(loop, degree, origin);
    const double radius = max_radius(loop, origin);
    // Reference in coordinates relative to `origin`.
    Loop shifted;
    for (const Point2& p : loop)
      shifted.push_back(p - origin);
    for (int a = 0; a <= degree; ++a) {
      for (int b = 0; a + b <= degree; ++b) {
        const double reference = star_quadrature(shifted, center - origin, a, b);
        // Both sides are sums of O(n) terms of size ~scale; 1e-13 leaves room for their
        // rounding (~n * 1e-16) while catching any wrong coefficient by orders of magnitude.
        EXPECT_NEAR(m(a, b), reference, 1e-13 * moment_scale(m.area(), radius, a + b))
            << "trial " << trial << " moment " << a << "," << b;
      }
    }
  }
}

TEST(SimplexIntegration, CentroidOfABlocksPolygonsFarFromTheOrigin) {
  // centroid(): an L of 3 m² (centroid (5/6, 5/6) from its corner) and, as a second polygon
  // of the same block, a 1 m square with a 0.5 m square hole (centroid its centre), 1e6 m
  // from the origin. Together: (3 (5/6, 5/6) + 0.75 (3.5, 0.5)) / 3.75 from the corner. The
  // moments are taken about the first vertex, so the error is that of coordinates of 1e6 m:
  // 1e-9 m.
  const Point2 o(1e6, -1e6);
  Polygon l_shape;
  l_shape.outer = {
      o, o + Point2(2, 0), o + Point2(2, 1), o + Point2(1, 1), o + Point2(1, 2), o + Point2(0, 2)};
  Polygon frame;
  frame.outer = {o + Point2(3, 0), o + Point2(4, 0), o + Point2(4, 1), o + Point2(3, 1)};
  frame.holes = {{o + Point2(3.25, 0.25), o + Point2(3.25, 0.75), o + Point2(3.75, 0.75),
                  o + Point2(3.75, 0.25)}};
  const std::vector<Polygon> one{l_shape};
  EXPECT_LT((centroid(one) - (o + Point2(5.0, 5.0) / 6.0)).norm(), 1e-9);
  const std::vector<Polygon> both{l_shape, frame};
  const Point2 expected = o + (3.0 * Point2(5.0, 5.0) / 6.0 + 0.75 * Point2(3.5, 0.5)) / 3.75;
  EXPECT_LT((centroid(both) - expected).norm(), 1e-9);
}

TEST(SimplexIntegration, PolygonWithHolesIsOuterMinusHoles) {
  std::mt19937 rng(7);
  const int degree = 8;
  for (int trial = 0; trial < 10; ++trial) {
    const Point2 center(0.5, -0.25);
    Polygon polygon;
    polygon.outer = random_star_polygon(rng, center, 17, 0.7, 1.0);
    // Two holes inside the inner radius of the outer loop, each with its own orientation.
    polygon.holes.push_back(random_star_polygon(rng, center + Point2(0.3, 0.0), 9, 0.05, 0.2));
    Loop second = random_star_polygon(rng, center + Point2(-0.3, 0.1), 7, 0.05, 0.2);
    std::reverse(second.begin(), second.end());
    polygon.holes.push_back(second);
    if (trial % 2 == 0)
      std::reverse(polygon.outer.begin(), polygon.outer.end());

    const Moments2 m = polygon_moments(polygon, degree, Point2::Zero());
    EXPECT_NEAR(m.area(), area(polygon), 1e-14);
    const double radius = max_radius(polygon.outer, Point2::Zero());
    for (int a = 0; a <= degree; ++a) {
      for (int b = 0; a + b <= degree; ++b) {
        const double reference =
            star_quadrature(polygon.outer, center, a, b) -
            star_quadrature(polygon.holes[0], center + Point2(0.3, 0.0), a, b) -
            star_quadrature(polygon.holes[1], center + Point2(-0.3, 0.1), a, b);
        EXPECT_NEAR(m(a, b), reference, 1e-13 * moment_scale(m.area(), radius, a + b))
            << "trial " << trial << " moment " << a << "," << b;
      }
    }
  }
}

TEST(SimplexIntegration, TinyPolygonFarFromOriginKeepsRelativeAccuracy) {
  // A 1e-3 polygon at (1e6, 1e6): absolute-coordinate formulas would lose ~18 digits to
  // cancellation. Reference: Gauss quadrature in local coordinates, expanded binomially
  // ((x0 + u)^a = Σ C(a,i) x0^(a-i) u^i), whose dominant term x0^a y0^b * area carries the
  // value; the 1e-10 relative target is the issue's.
  std::mt19937 rng(11);
  const Point2 far(1.0e6, 1.0e6);
  const int degree = 6;
  for (int trial = 0; trial < 10; ++trial) {
    const Loop exact_local = random_star_polygon(rng, Point2::Zero(), 11, 2e-4, 5e-4);
    Loop loop;
    Loop local; // what the stored vertices really are relative to `far` (exact subtraction)
    for (const Point2& p : exact_local) {
      loop.push_back(far + p);
      local.push_back(loop.back() - far);
    }
    const Moments2 m = polygon_moments(loop, degree, Point2::Zero());
    for (int a = 0; a <= degree; ++a) {
      for (int b = 0; a + b <= degree; ++b) {
        double reference = 0.0;
        for (int i = 0; i <= a; ++i) {
          for (int j = 0; j <= b; ++j) {
            const double binomial =
                std::tgamma(a + 1.0) / (std::tgamma(i + 1.0) * std::tgamma(a - i + 1.0)) *
                std::tgamma(b + 1.0) / (std::tgamma(j + 1.0) * std::tgamma(b - j + 1.0));
            reference += binomial * std::pow(far.x(), a - i) * std::pow(far.y(), b - j) *
                         star_quadrature(local, Point2::Zero(), i, j);
          }
        }
        EXPECT_NEAR(m(a, b) / reference, 1.0, 1e-10) << "trial " << trial << " " << a << "," << b;
      }
    }
    // About a point of its own (a representable one: the centroid itself is only known to
    // the 1e-10 ulp of 1e6) the same polygon is an ordinary small polygon: 1e-13 scaled.
    const Point2 near = loop[3] + Point2(-1e-4, 2e-4);
    const Moments2 central = polygon_moments(loop, degree, near);
    Loop relative;
    for (const Point2& p : loop)
      relative.push_back(p - near); // exact: nearby doubles
    const Point2 center = far - near;
    for (int a = 0; a <= degree; ++a) {
      for (int b = 0; a + b <= degree; ++b) {
        EXPECT_NEAR(central(a, b), star_quadrature(relative, center, a, b),
                    1e-13 * moment_scale(central.area(), 1e-3, a + b))
            << "trial " << trial << " " << a << "," << b;
      }
    }
  }
}

TEST(SimplexIntegration, ShiftedMomentsEqualDirectIntegration) {
  std::mt19937 rng(3);
  const Loop loop = random_star_polygon(rng, Point2(1.0, 2.0), 13, 0.3, 1.0);
  const Moments2 about_a = polygon_moments(loop, 8, Point2(-1.0, 0.5));
  const Moments2 about_b = polygon_moments(loop, 8, Point2(2.0, 1.5));
  const Moments2 moved = about_a.shifted_to(Point2(2.0, 1.5));
  // The shift sums terms C d^(a-i) M_A(i, j) of size area * (R_A + |d|)^(a+b): its rounding
  // is relative to that, not to the (smaller) moments about the new origin.
  const double radius = max_radius(loop, Point2(-1.0, 0.5)) + (Point2(3.0, 1.0)).norm();
  for (int a = 0; a <= 8; ++a) {
    for (int b = 0; a + b <= 8; ++b) {
      EXPECT_NEAR(moved(a, b), about_b(a, b), 1e-13 * moment_scale(about_b.area(), radius, a + b));
    }
  }
}

TEST(SimplexIntegration, DegenerateLoopsHaveZeroMoments) {
  const Loop segment{{0, 0}, {1, 1}};
  const Moments2 m = polygon_moments(segment, 3, Point2::Zero());
  for (int a = 0; a <= 3; ++a) {
    for (int b = 0; a + b <= 3; ++b)
      EXPECT_EQ(m(a, b), 0.0);
  }
  const Loop collinear{{0, 0}, {1, 1}, {2, 2}};
  EXPECT_EQ(polygon_moments(collinear, 2, Point2::Zero()).area(), 0.0);
}

// ------------------------------------------------------------- Shi's tables (3D)

TEST(SimplexIntegration, RegularSolidsReproduceShiVolumes) {
  const double s3 = std::sqrt(3.0);
  const double s5 = std::sqrt(5.0);
  const struct {
    RegularSolid kind;
    double closed_form;
    double table;
    std::size_t faces;
  } rows[] = {
      {RegularSolid::tetrahedron, 8.0 / 27.0 * s3, 0.51320, 4},
      {RegularSolid::cube, 8.0 / (3.0 * s3), 1.53960, 6},
      {RegularSolid::dodecahedron, 2.0 / 3.0 / s3 * std::sqrt(10.0 * (3.0 + s5)), 2.78516, 12}};
  for (const auto& row : rows) {
    const Polyhedron solid = regular_solid(row.kind);
    ASSERT_EQ(solid.faces.size(), row.faces);
    const Moments3 m = polyhedron_moments(solid, 4, Point3::Zero());
    EXPECT_NEAR(m.volume(), row.closed_form, 1e-14 * row.closed_form);
    // Shi's table prints 5 decimals.
    EXPECT_NEAR(m.volume(), row.table, 5e-6);
    EXPECT_NEAR(m.centroid().norm(), 0.0, 1e-15);
    for (const Point3& v : solid.vertices)
      EXPECT_NEAR(v.norm(), 1.0, 1e-15);
  }
}

TEST(SimplexIntegration, CubeMatchesClosedFormToDegreeFour) {
  // Cube [-s, s]^3 about the point (0.2, -0.1, 0.3):
  // ∫ (x-ox)^a ... = Π ((s-o)^(a+1) - (-s-o)^(a+1)) / (a+1).
  const Polyhedron cube = regular_solid(RegularSolid::cube);
  const double s = 1.0 / std::sqrt(3.0);
  const Point3 o(0.2, -0.1, 0.3);
  const Moments3 m = polyhedron_moments(cube, 4, o);
  auto line = [&](double center, int power) {
    return (std::pow(s - center, power + 1) - std::pow(-s - center, power + 1)) / (power + 1);
  };
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; a + b <= 4; ++b) {
      for (int c = 0; a + b + c <= 4; ++c) {
        const double exact = line(o.x(), a) * line(o.y(), b) * line(o.z(), c);
        EXPECT_NEAR(m(a, b, c), exact, 1e-14) << a << b << c;
      }
    }
  }
}

// A star-shaped polyhedron: the octahedron's faces split in four, vertices pushed to
// random radii about `center`. Every face with the centre is a positive tetrahedron.
Polyhedron random_star_polyhedron(std::mt19937& rng, const Point3& center) {
  std::vector<Point3> directions{{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                 {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
  std::vector<std::array<int, 3>> triangles{{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                                            {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  std::vector<std::array<int, 3>> finer;
  auto midpoint = [&](int i, int j) {
    directions.push_back((directions[i] + directions[j]).normalized());
    return static_cast<int>(directions.size()) - 1;
  };
  for (const auto& t : triangles) {
    const int ab = midpoint(t[0], t[1]);
    const int bc = midpoint(t[1], t[2]);
    const int ca = midpoint(t[2], t[0]);
    finer.push_back({t[0], ab, ca});
    finer.push_back({ab, t[1], bc});
    finer.push_back({ca, bc, t[2]});
    finer.push_back({ab, bc, ca});
  }
  // Edge midpoints were added once per triangle: identical points, harmless for volume
  // integrals (the surface is still closed as a chain of oriented triangles).
  std::uniform_real_distribution<double> radius(0.4, 1.0);
  Polyhedron solid;
  for (const Point3& d : directions)
    solid.vertices.push_back(center + radius(rng) * d);
  for (const auto& t : finer)
    solid.faces.push_back({t[0], t[1], t[2]});
  return solid;
}

TEST(SimplexIntegration, RandomStarPolyhedraMatchGaussQuadratureToDegreeFour) {
  std::mt19937 rng(99);
  for (int trial = 0; trial < 5; ++trial) {
    const Point3 center(0.3 * trial, -0.2, 0.1 * trial);
    Polyhedron solid = random_star_polyhedron(rng, center);
    // Duplicated midpoints must coincide for the surface to close: give them one radius.
    for (std::size_t i = 0; i < solid.vertices.size(); ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (((solid.vertices[i] - center).normalized() - (solid.vertices[j] - center).normalized())
                .norm() < 1e-12) {
          solid.vertices[i] = solid.vertices[j];
        }
      }
    }
    const Point3 origin(0.1, 0.2, -0.3);
    const Moments3 m = polyhedron_moments(solid, 4, origin);
    double radius = 0.0;
    for (const Point3& v : solid.vertices)
      radius = std::max(radius, (v - origin).norm());
    for (int a = 0; a <= 4; ++a) {
      for (int b = 0; a + b <= 4; ++b) {
        for (int c = 0; a + b + c <= 4; ++c) {
          double reference = 0.0;
          for (const auto& f : solid.faces) {
            reference += tetrahedron_quadrature(center - origin, solid.vertices[f[0]] - origin,
                                                solid.vertices[f[1]] - origin,
                                                solid.vertices[f[2]] - origin, a, b, c);
          }
          EXPECT_NEAR(m(a, b, c), reference,
                      1e-13 * std::abs(m.volume()) * std::pow(radius, a + b + c))
              << "trial " << trial << " " << a << b << c;
        }
      }
    }
  }
}

TEST(SimplexIntegration, ConcavePrismWithPolygonalFacesMatchesQuadrature) {
  // A prism over a concave star polygon: its two caps are concave 15-gons, not triangles.
  std::mt19937 rng(5);
  const Point2 center(0.2, 0.1);
  const Loop base = random_star_polygon(rng, center, 15, 0.3, 1.0); // counter-clockwise
  const double z0 = -0.4;
  const double z1 = 0.9;
  Polyhedron prism;
  const int n = static_cast<int>(base.size());
  for (const Point2& p : base)
    prism.vertices.emplace_back(p.x(), p.y(), z0);
  for (const Point2& p : base)
    prism.vertices.emplace_back(p.x(), p.y(), z1);
  std::vector<int> bottom;
  std::vector<int> top;
  for (int k = n - 1; k >= 0; --k)
    bottom.push_back(k); // seen from below: clockwise in xy
  for (int k = 0; k < n; ++k)
    top.push_back(n + k);
  prism.faces.push_back(bottom);
  prism.faces.push_back(top);
  for (int k = 0; k < n; ++k) {
    const int next = (k + 1) % n;
    prism.faces.push_back({k, next, n + next, n + k});
  }
  const Moments3 m = polyhedron_moments(prism, 4, Point3::Zero());
  for (int a = 0; a <= 4; ++a) {
    for (int b = 0; a + b <= 4; ++b) {
      for (int c = 0; a + b + c <= 4; ++c) {
        const double reference = star_quadrature(base, center, a, b) *
                                 (std::pow(z1, c + 1) - std::pow(z0, c + 1)) / (c + 1);
        EXPECT_NEAR(m(a, b, c), reference, 1e-13 * std::abs(m.volume()) * std::pow(1.5, a + b + c))
            << a << b << c;
      }
    }
  }
}

} // namespace
} // namespace nmm
