// SPDX-License-Identifier: MIT
#include "manifold/material.hpp"
#include "manifold/nmm_element.hpp"

#include "../../support/gauss_quadrature.hpp"
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

namespace nmm {
namespace {

// Far from the origin on purpose: the local coordinates must keep the accuracy.
const std::array<Point2, 3> triangle{Point2(1000.3, 2000.1), Point2(1001.9, 2000.4),
                                     Point2(1000.8, 2001.7)};

Polygon whole_triangle() { return {{triangle[0], triangle[1], triangle[2]}, {}}; }

/// A concave pentagon inside the triangle: a cut element.
Polygon cut_piece() {
  const Point2 c = (triangle[0] + triangle[1] + triangle[2]) / 3.0;
  auto mix = [&](int k, double t) {
    return Point2(c + t * (triangle[static_cast<std::size_t>(k)] - c));
  };
  return {{mix(0, 0.9), mix(1, 0.8), Point2(c + 0.1 * (triangle[1] - c)), mix(2, 0.95),
           Point2(c + 0.3 * (triangle[0] - c) + 0.2 * (triangle[2] - c))},
          {}};
}

ElasticMaterial rock() {
  ElasticMaterial m;
  m.name = "rock";
  m.young = 5.0e9;
  m.poisson = 0.25;
  m.density = 2600.0;
  return m;
}

/// Area of the triangle, and P1 FEM stiffness / mass in closed form (Shi eq. 4.7, 5.x).
double triangle_area() {
  const Point2 a = triangle[1] - triangle[0];
  const Point2 b = triangle[2] - triangle[0];
  return 0.5 * (a.x() * b.y() - a.y() * b.x());
}

Eigen::MatrixXd p1_stiffness(const Eigen::Matrix3d& d) {
  const double twice = 2.0 * triangle_area();
  Eigen::Matrix<double, 3, 6> b = Eigen::Matrix<double, 3, 6>::Zero();
  for (int k = 0; k < 3; ++k) {
    const Point2& p = triangle[static_cast<std::size_t>((k + 1) % 3)];
    const Point2& q = triangle[static_cast<std::size_t>((k + 2) % 3)];
    const double bx = (p.y() - q.y()) / twice;
    const double by = (q.x() - p.x()) / twice;
    b(0, 2 * k) = bx;
    b(1, 2 * k + 1) = by;
    b(2, 2 * k) = by;
    b(2, 2 * k + 1) = bx;
  }
  return triangle_area() * b.transpose() * d * b;
}

TEST(NmmShape, OrderZeroWeightsArePartitionOfUnityAndInterpolateVertices) {
  const NmmShape shape(triangle, 0, 1.0);
  ASSERT_EQ(shape.n_dofs(), 6);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    const Point2 x = triangle[0] + unit(random) * (triangle[1] - triangle[0]) +
                     0.3 * unit(random) * (triangle[2] - triangle[0]);
    EXPECT_NEAR(shape.values_at(x).sum(), 1.0, 1e-13);
  }
  for (int k = 0; k < 3; ++k) {
    const Eigen::VectorXd at_vertex = shape.values_at(triangle[static_cast<std::size_t>(k)]);
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(at_vertex(j), j == k ? 1.0 : 0.0, 1e-12);
  }
}

TEST(NmmShape, RigidBodyMotionGivesZeroStrainForBothOrders) {
  // Translation (0.3, -0.2) plus an infinitesimal rotation 1e-3 about (1000, 2000): linear,
  // so order 0 represents it by nodal values and order 1 by cover functions equal to it.
  const double theta = 1e-3;
  auto field = [&](const Point2& x) {
    return Point2(0.3 - theta * (x.y() - 2000.0), -0.2 + theta * (x.x() - 1000.0));
  };
  for (const int order : {0, 1}) {
    const double scale = 0.7;
    const NmmShape shape(triangle, order, scale);
    std::vector<double> d(static_cast<std::size_t>(shape.n_dofs()), 0.0);
    const int m = cover_basis_size(order);
    for (int k = 0; k < 3; ++k) {
      const Point2 u = field(triangle[static_cast<std::size_t>(k)]);
      const std::size_t base = static_cast<std::size_t>(2 * m * k);
      d[base] = u.x();
      d[base + 1] = u.y();
      if (order == 1) { // gradient times scale: du/dy = -theta, dv/dx = theta
        d[base + 3] = theta * scale;
        d[base + 4] = -theta * scale;
      }
    }
    const LinearField3 strain = shape.strain(d);
    EXPECT_LT(strain.coefficients.cwiseAbs().maxCoeff(), 1e-15) << "order " << order;
    const Point2 x(1000.9, 2000.6);
    EXPECT_NEAR((shape.displacement_at(x, d) - field(x)).norm(), 0.0, 1e-14);
  }
}

TEST(NmmShape, OrderOneReproducesEveryQuadratic) {
  // q(x) = x^T A x + b.x + c, represented exactly by the cover functions
  // l_k(x) = q(x_k) + (grad q(x_k) + grad q(c0)) / 2 . (x - x_k) for any common point c0
  // (docs/formulation.md, "Order-1 covers": the P1 interpolation error cancels).
  Eigen::Matrix2d a;
  a << 0.7, -0.2, -0.2, 1.3;
  const Point2 b(0.4, -1.1);
  const Point2 x0(1000.0, 2000.0);
  auto q = [&](const Point2& x) { return (x - x0).dot(a * (x - x0)) + b.dot(x - x0) + 0.5; };
  auto grad = [&](const Point2& x) { return Point2(2.0 * a * (x - x0) + b); };
  const Point2 c0(1003.0, 1999.0);
  const double scale = 1.3;
  const NmmShape shape(triangle, 1, scale);
  std::vector<double> d(18, 0.0);
  for (int k = 0; k < 3; ++k) {
    const Point2& xk = triangle[static_cast<std::size_t>(k)];
    const Point2 g = 0.5 * (grad(xk) + grad(c0)) * scale;
    const std::size_t base = static_cast<std::size_t>(6 * k);
    d[base] = q(xk);     // u of the constant basis
    d[base + 2] = g.x(); // u of (x - xk)/L
    d[base + 4] = g.y(); // u of (y - yk)/L
  }
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int i = 0; i < 20; ++i) {
    const double s = unit(random);
    const double t = unit(random) * (1.0 - s);
    const Point2 x =
        triangle[0] + s * (triangle[1] - triangle[0]) + t * (triangle[2] - triangle[0]);
    EXPECT_NEAR(shape.displacement_at(x, d).x(), q(x), 1e-11);
    EXPECT_NEAR(shape.displacement_at(x, d).y(), 0.0, 1e-15);
  }
}

TEST(NmmElementIntegrals, OrderZeroWholeTriangleIsTheP1FiniteElement) {
  const ElasticMaterial material = rock();
  const Eigen::Matrix3d d = elasticity_matrix(material);
  const NmmShape shape(triangle, 0, 1.0);
  const std::vector<Polygon> polygons{whole_triangle()};
  const NmmElementIntegrals integrals(shape, polygons);
  EXPECT_NEAR(integrals.area(), triangle_area(), 1e-12 * triangle_area());
  const Eigen::MatrixXd k = integrals.stiffness(d, 1.0);
  const Eigen::MatrixXd reference = p1_stiffness(d);
  EXPECT_LT((k - reference).norm(), 1e-12 * reference.norm());
  // Consistent mass of a P1 triangle: rho A / 12 [2 1 1; 1 2 1; 1 1 2] per component.
  const Eigen::MatrixXd m = integrals.mass(material.density);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double expected = material.density * triangle_area() / 12.0 * (i == j ? 2.0 : 1.0);
      EXPECT_NEAR(m(2 * i, 2 * j), expected, 1e-12 * expected);
      EXPECT_NEAR(m(2 * i + 1, 2 * j + 1), expected, 1e-12 * expected);
      EXPECT_EQ(m(2 * i, 2 * j + 1), 0.0);
    }
  }
  // Gravity: a third of the weight on each node.
  const Eigen::VectorXd f = integrals.body_force(Point2(0.0, -9.81 * material.density), 1.0);
  for (int node = 0; node < 3; ++node) {
    EXPECT_NEAR(f(2 * node), 0.0, 1e-12);
    EXPECT_NEAR(f(2 * node + 1), -9.81 * material.density * triangle_area() / 3.0, 1e-9);
  }
}

TEST(NmmElementIntegrals, StiffnessIsSymmetricWithExactlyTheRigidNullSpace) {
  const Eigen::Matrix3d d = elasticity_matrix(rock());
  for (const int order : {0, 1}) {
    const NmmShape shape(triangle, order, 0.9);
    const std::vector<Polygon> polygons{cut_piece()};
    const Eigen::MatrixXd k = NmmElementIntegrals(shape, polygons).stiffness(d, 1.0);
    EXPECT_LT((k - k.transpose()).norm(), 1e-14 * k.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
    const double largest = eigen.eigenvalues().maxCoeff();
    int zero = 0;
    for (Eigen::Index i = 0; i < eigen.eigenvalues().size(); ++i) {
      EXPECT_GT(eigen.eigenvalues()(i), -1e-12 * largest);
      zero += eigen.eigenvalues()(i) < 1e-10 * largest;
    }
    // Order 0: the 3 rigid motions. Order 1: 18 unknowns for a quadratic field (12
    // functions), so 6 dependent combinations, plus the 3 rigid motions.
    EXPECT_EQ(zero, order == 0 ? 3 : 9) << "order " << order;
  }
}

TEST(ElasticityMatrix, MatchesTheClosedFormsOfPlaneStrainAndPlaneStress) {
  // The D of every element test and of the FEM-equivalence reference comes from
  // elasticity_matrix(): checked here against the textbook forms, written out (1e-15
  // relative: a few roundings of O(1) factors).
  const double e = 3.0e10;
  const double nu = 0.3;
  ElasticMaterial m;
  m.young = e;
  m.poisson = nu;
  m.plane = PlaneCondition::strain;
  const double f = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
  Eigen::Matrix3d strain;
  strain << f * (1.0 - nu), f * nu, 0.0, f * nu, f * (1.0 - nu), 0.0, 0.0, 0.0,
      f * (1.0 - 2.0 * nu) / 2.0;
  EXPECT_LT((elasticity_matrix(m) - strain).norm(), 1e-15 * strain.norm());
  m.plane = PlaneCondition::stress;
  const double g = e / (1.0 - nu * nu);
  Eigen::Matrix3d stress;
  stress << g, g * nu, 0.0, g * nu, g, 0.0, 0.0, 0.0, g * (1.0 - nu) / 2.0;
  EXPECT_LT((elasticity_matrix(m) - stress).norm(), 1e-15 * stress.norm());
}

/// Independent quadrature: the (star-shaped from its last vertex) polygon as a fan of
/// triangles, each by the 7-point degree-5 Gauss rule.
double quadrature(const Polygon& polygon, const std::function<double(const Point2&)>& f) {
  return testing::gauss_fan(polygon, polygon.outer.size() - 1, f);
}

TEST(NmmElementIntegrals, CutElementMatchesIndependentQuadrature) {
  // Tolerance 1e-10 relative: the 7-point rule is exact to degree 5 (the mass integrand of
  // order 1 is degree 4); the rest is rounding of O(1e3) coordinates.
  const Polygon piece = cut_piece();
  for (const int order : {0, 1}) {
    const NmmShape shape(triangle, order, 0.9);
    const std::vector<Polygon> polygons{piece};
    const NmmElementIntegrals integrals(shape, polygons);
    const Eigen::MatrixXd m = integrals.mass(1.0);
    for (int a = 0; a < shape.n_shapes(); ++a) {
      for (int b = 0; b < shape.n_shapes(); ++b) {
        const double expected = quadrature(piece, [&](const Point2& x) {
          const Eigen::VectorXd phi = shape.values_at(x);
          return phi(a) * phi(b);
        });
        EXPECT_NEAR(m(2 * a, 2 * b), expected, 1e-10 * std::abs(m(0, 0)));
      }
    }
    // Initial stress load of a linear stress field against quadrature of -B^T sigma.
    LinearField3 stress;
    stress.origin = Point2(1000.0, 2000.0);
    stress.coefficients << 1.0e6, 2.0e5, -1.0e5, -3.0e6, 0.0, 4.0e5, 5.0e5, -2.0e5, 1.0e5;
    const Eigen::VectorXd f = integrals.initial_stress_load(stress, 1.0);
    for (int a = 0; a < shape.n_shapes(); ++a) {
      const double fu = -quadrature(piece, [&](const Point2& x) {
        const Eigen::Vector3d s = stress.at(x);
        const Eigen::Vector3d m3 =
            Eigen::Vector3d(1.0, (x - shape.origin()).x(), (x - shape.origin()).y());
        return shape.dx().col(a).dot(m3) * s(0) + shape.dy().col(a).dot(m3) * s(2);
      });
      EXPECT_NEAR(f(2 * a), fu, 1e-10 * 3.0e6 * integrals.area());
    }
  }
}

TEST(NmmElementIntegrals, ConstantStressLoadBalancesOnAWholeTriangle) {
  // A constant stress in a free element: the load is in equilibrium (zero net force).
  const NmmShape shape(triangle, 0, 1.0);
  const std::vector<Polygon> polygons{whole_triangle()};
  LinearField3 stress;
  stress.coefficients.col(0) << 1.0e6, -2.0e6, 3.0e5;
  const Eigen::VectorXd f = NmmElementIntegrals(shape, polygons).initial_stress_load(stress, 1.0);
  EXPECT_NEAR(f(0) + f(2) + f(4), 0.0, 1e-6);
  EXPECT_NEAR(f(1) + f(3) + f(5), 0.0, 1e-6);
}

} // namespace
} // namespace nmm
