// SPDX-License-Identifier: MIT
// Unit tests of the DDA and VEM block elements (manifold/dda_block, manifold/vem_block)
// against closed forms, on a concave polygon with a hole far from the origin.
#include "manifold/element.hpp"
#include "manifold/material.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>

namespace nmm {
namespace {

/// An L-shaped block (area 3 m²) with a square hole of 0.25 m² (area 2.75 m²), far from 0.
std::vector<Polygon> concave_block() {
  const Point2 o(1000.0, -500.0);
  Polygon p;
  p.outer = {
      o, o + Point2(2, 0), o + Point2(2, 1), o + Point2(1, 1), o + Point2(1, 2), o + Point2(0, 2)};
  p.holes = {{o + Point2(0.25, 0.25), o + Point2(0.25, 0.75), o + Point2(0.75, 0.75),
              o + Point2(0.75, 0.25)}};
  return {p};
}

/// Vertex values of the linear field u = a + G (x - x_ref).
Eigen::VectorXd linear_values(const VemShape& shape, const Point2& a, const Eigen::Matrix2d& g) {
  Eigen::VectorXd d(shape.n_dofs());
  const Point2 ref(1000.0, -500.0);
  for (int i = 0; i < shape.n_vertices(); ++i)
    d.segment<2>(2 * i) = a + g * (shape.vertices()[static_cast<std::size_t>(i)] - ref);
  return d;
}

TEST(VemBlock, ProjectorReproducesLinearFieldsOnAConcaveBlockWithAHole) {
  // Pi_P u = u for every linear u (eq. 32-35): at the vertices and inside. Tolerance 1e-10:
  // rounding of coordinates of 1e3 m in the boundary sums.
  const std::vector<Polygon> block = concave_block();
  const VemShape shape(block);
  EXPECT_EQ(shape.n_vertices(), 10);
  EXPECT_NEAR(shape.area(), 2.75, 1e-12);
  Eigen::Matrix2d g;
  g << 1e-3, -2e-3, 3e-3, 4e-4;
  const Point2 a(0.1, -0.2);
  const Eigen::VectorXd d = linear_values(shape, a, g);
  const std::span<const double> values(d.data(), static_cast<std::size_t>(d.size()));
  for (const Point2& x : {Point2(1000.5, -499.0), Point2(1001.5, -499.8), Point2(1000.1, -498.5)}) {
    const Point2 exact = a + g * (x - Point2(1000.0, -500.0));
    EXPECT_LT((shape.displacement_at(x, values) - exact).norm(), 1e-10) << x.transpose();
  }
  const LinearField3 strain = shape.strain(values);
  EXPECT_NEAR(strain.coefficients(0, 0), g(0, 0), 1e-12);
  EXPECT_NEAR(strain.coefficients(1, 0), g(1, 1), 1e-12);
  EXPECT_NEAR(strain.coefficients(2, 0), g(0, 1) + g(1, 0), 1e-12);
  EXPECT_NEAR(shape.rotation(values), 0.5 * (g(1, 0) - g(0, 1)), 1e-12);
}

TEST(VemBlock, InterpolationOnAnEdgeInvolvesOnlyItsTwoVertices) {
  // On an edge the VEM displacement is the linear interpolation of the edge's two vertices
  // (exact), so interpolation_on_edge() gives those four columns, with the values of the
  // full interpolation_at(x) (compared bit for bit: the same arithmetic), the same four at
  // the edge's ends (a point moving along the edge keeps its unknowns), and the edge's line
  // past them (weights 1 - s and s, s = 1.5: -0.5 and 1.5).
  const std::vector<Polygon> block = concave_block();
  const VemShape shape(block);
  const ElementShape element(shape);
  const Point2 o(1000.0, -500.0);
  const auto& v = shape.vertices();
  struct Case {
    int from; ///< the edge's first vertex (outer loop 0-5, hole 6-9)
    int to;
    double s;
  };
  for (const Case& c : {Case{0, 1, 0.25}, Case{3, 4, 0.5}, Case{6, 7, 0.75}, Case{9, 6, 0.5},
                        Case{1, 2, 0.0}, Case{1, 2, 1.0}, Case{4, 5, 1.5}}) {
    const Point2& a = v[static_cast<std::size_t>(c.from)];
    const Point2& b = v[static_cast<std::size_t>(c.to)];
    const Point2 x = a + c.s * (b - a);
    PointInterpolation sparse;
    std::vector<int> columns;
    element.interpolation_on_edge(x, a, b, sparse, columns);
    EXPECT_EQ(columns, (std::vector<int>{2 * c.from, 2 * c.from + 1, 2 * c.to, 2 * c.to + 1}))
        << c.from << "-" << c.to << " at " << c.s;
    ASSERT_EQ(sparse.cols(), 4);
    PointInterpolation scattered = PointInterpolation::Zero(2, shape.n_dofs());
    for (std::size_t j = 0; j < columns.size(); ++j)
      scattered.col(columns[j]) = sparse.col(static_cast<Eigen::Index>(j));
    if (c.s <= 1.0) {
      EXPECT_EQ(scattered, shape.interpolation_at(x)) << c.from << "-" << c.to << " at " << c.s;
    } else {
      EXPECT_NEAR(sparse(0, 0), 1.0 - c.s, 1e-15);
      EXPECT_NEAR(sparse(1, 3), c.s, 1e-15);
    }
  }
  // A DDA block's interpolation involves all six unknowns everywhere.
  const ElementShape dda(DdaShape(o + Point2(1.0, 1.0)));
  PointInterpolation t;
  std::vector<int> columns;
  dda.interpolation_on_edge(o, o, o + Point2(2.0, 0.0), t, columns);
  EXPECT_EQ(columns, (std::vector<int>{0, 1, 2, 3, 4, 5}));
  EXPECT_EQ(t, dda.interpolation_at(o));
}

TEST(VemBlock, StiffnessPassesThePatchTestAndHasOnlyRigidKernel) {
  // For a linear field with constant stress sigma, K d equals the boundary tractions sigma n
  // lumped to the vertices by the linear edge functions (the consistency term is exact and
  // the stabilisation vanishes on linear fields); K has exactly three zero eigenvalues (the
  // rigid motions). Tolerances: 1e-9 of the force scale, rounding.
  const std::vector<Polygon> block = concave_block();
  const VemShape shape(block);
  const VemIntegrals integrals(shape, block);
  ElasticMaterial m;
  m.young = 1e9;
  m.poisson = 0.3;
  m.plane = PlaneCondition::stress;
  const Eigen::Matrix3d dm = elasticity_matrix(m);
  const Eigen::MatrixXd k = integrals.stiffness(dm, 1.0);
  Eigen::Matrix2d g;
  g << 1e-3, 2e-4, -3e-4, -5e-4;
  const Eigen::VectorXd d = linear_values(shape, Point2(0.3, 0.1), g);
  const Eigen::Vector3d sigma = dm * Eigen::Vector3d(g(0, 0), g(1, 1), g(0, 1) + g(1, 0));
  Eigen::Matrix2d s;
  s << sigma(0), sigma(2), sigma(2), sigma(1);
  // Boundary tractions: each edge a -> b (material on the left) has l n = (dy, -dx).
  Eigen::VectorXd f = Eigen::VectorXd::Zero(shape.n_dofs());
  const auto add_loop = [&](const Loop& loop, int first) {
    const int n = static_cast<int>(loop.size());
    for (int i = 0; i < n; ++i) {
      const Point2& a = loop[static_cast<std::size_t>(i)];
      const Point2& b = loop[static_cast<std::size_t>((i + 1) % n)];
      const Point2 force = s * Point2(b.y() - a.y(), a.x() - b.x());
      f.segment<2>(2 * (first + i)) += 0.5 * force;
      f.segment<2>(2 * (first + (i + 1) % n)) += 0.5 * force;
    }
  };
  add_loop(block[0].outer, 0);
  add_loop(block[0].holes[0], 6);
  const double scale = f.cwiseAbs().maxCoeff();
  EXPECT_LT((k * d - f).cwiseAbs().maxCoeff(), 1e-9 * scale);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(k);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  const double largest = lambda.maxCoeff();
  int zero = 0;
  for (Eigen::Index i = 0; i < lambda.size(); ++i)
    zero += std::abs(lambda(i)) < 1e-10 * largest;
  EXPECT_EQ(zero, 3);
  EXPECT_GT(lambda.minCoeff(), -1e-10 * largest);
}

TEST(VemBlock, MassAndBodyForceGiveTheBlocksMassAndWeight) {
  // A translation's kinetic energy is rho S v²/2 (the stabilisation vanishes on it) and the
  // body force sums to S b: 1e-10 relative, rounding.
  const std::vector<Polygon> block = concave_block();
  const VemShape shape(block);
  const VemIntegrals integrals(shape, block);
  const double rho = 2500.0;
  const Eigen::MatrixXd mass = integrals.mass(rho);
  const Eigen::VectorXd ones_x = linear_values(shape, Point2(1, 0), Eigen::Matrix2d::Zero());
  EXPECT_NEAR(ones_x.dot(mass * ones_x), rho * 2.75, 1e-10 * rho * 2.75);
  const Eigen::VectorXd f = integrals.body_force(Point2(0.0, -9.81 * rho), 1.0);
  double fx = 0.0;
  double fy = 0.0;
  for (int i = 0; i < shape.n_vertices(); ++i) {
    fx += f(2 * i);
    fy += f(2 * i + 1);
  }
  EXPECT_NEAR(fx, 0.0, 1e-9);
  EXPECT_NEAR(fy, -9.81 * rho * 2.75, 1e-10 * 9.81 * rho * 2.75);
}

TEST(DdaBlock, MassOfARectangleIsItsMassAndPolarMoment) {
  // A 2 x 1 rectangle about its centroid: translation rho a b, rotation rho a b (a² + b²)/12
  // (Shi 1997 chapter 2.5 with one cover of weight 1); 1e-12 relative.
  const Point2 c(300.0, 200.0);
  Polygon rectangle;
  rectangle.outer = {c + Point2(-1, -0.5), c + Point2(1, -0.5), c + Point2(1, 0.5),
                     c + Point2(-1, 0.5)};
  const std::vector<Polygon> block{rectangle};
  const DdaShape shape(c);
  const DdaIntegrals integrals(shape, block);
  const Eigen::Matrix<double, 6, 6> m = integrals.mass(1.0);
  EXPECT_NEAR(m(0, 0), 2.0, 1e-12);
  EXPECT_NEAR(m(1, 1), 2.0, 1e-12);
  EXPECT_NEAR(m(2, 2), 2.0 * 5.0 / 12.0, 1e-12);
  EXPECT_NEAR(m(0, 2), 0.0, 1e-12);
  // Exact rotation: a quarter turn moves a corner to the next one's place, distances kept.
  const double d[6] = {0.0, 0.0, 3.14159265358979323846 / 2.0, 0.0, 0.0, 0.0};
  const Point2 corner = rectangle.outer[1];
  const Point2 moved = shape.moved(corner, d);
  EXPECT_LT((moved - (c + Point2(0.5, 1.0))).norm(), 1e-12);
}

} // namespace
} // namespace nmm
