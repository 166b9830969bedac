// SPDX-License-Identifier: MIT
#include "manifold/nmm_element.hpp"

#include "manifold/simplex_integration.hpp"
#include "mesh/error.hpp"

namespace nmm {

namespace {

using Linear = Eigen::Vector3d;                // c0 + c1 X + c2 Y
using Quadratic = Eigen::Matrix<double, 6, 1>; // 1, X, Y, X², XY, Y²

/// Exponents of the monomials in Moments2::index order, degree <= 2.
constexpr std::array<std::array<int, 2>, 6> exponents{
    {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}}};

Quadratic multiply(const Linear& p, const Linear& q) {
  Quadratic r;
  r << p(0) * q(0), p(0) * q(1) + p(1) * q(0), p(0) * q(2) + p(2) * q(0), p(1) * q(1),
      p(1) * q(2) + p(2) * q(1), p(2) * q(2);
  return r;
}

Eigen::Matrix<double, 6, 1> monomials(const Point2& local) {
  Eigen::Matrix<double, 6, 1> m;
  m << 1.0, local.x(), local.y(), local.x() * local.x(), local.x() * local.y(),
      local.y() * local.y();
  return m;
}

} // namespace

LinearField3 LinearField3::about(const Point2& new_origin) const {
  LinearField3 result;
  result.origin = new_origin;
  result.coefficients = coefficients;
  const Point2 shift = new_origin - origin;
  result.coefficients.col(0) += coefficients.col(1) * shift.x() + coefficients.col(2) * shift.y();
  return result;
}

NmmShape::NmmShape(const std::array<Point2, 3>& vertices, int order, double scale) : order_(order) {
  NMM_ASSERT(order >= 0 && order <= max_cover_order, "unsupported cover order");
  NMM_ASSERT(scale > 0.0, "cover basis scale must be positive");
  origin_ = (vertices[0] + vertices[1] + vertices[2]) / 3.0;
  std::array<Point2, 3> q;
  for (std::size_t k = 0; k < 3; ++k)
    q[k] = vertices[k] - origin_;
  const double twice_area =
      (q[1] - q[0]).x() * (q[2] - q[0]).y() - (q[1] - q[0]).y() * (q[2] - q[0]).x();
  NMM_ASSERT(twice_area > 0.0, "element triangle must be counter-clockwise and non-degenerate");
  const int m = cover_basis_size(order);
  values_.setZero(6, 3 * m);
  dx_.setZero(3, 3 * m);
  dy_.setZero(3, 3 * m);
  for (std::size_t k = 0; k < 3; ++k) {
    // Barycentric weight of vertex k (Shi eq. 4.7-4.8): the signed area of the triangle
    // (X, q_{k+1}, q_{k+2}) over the element's, expanded in X and Y.
    const Point2& a = q[(k + 1) % 3];
    const Point2& b = q[(k + 2) % 3];
    const Linear weight =
        Linear(a.x() * b.y() - a.y() * b.x(), a.y() - b.y(), b.x() - a.x()) / twice_area;
    std::array<Linear, 3> basis{Linear(1.0, 0.0, 0.0), Linear(-q[k].x() / scale, 1.0 / scale, 0.0),
                                Linear(-q[k].y() / scale, 0.0, 1.0 / scale)};
    for (int j = 0; j < m; ++j) {
      const Quadratic phi = multiply(weight, basis[static_cast<std::size_t>(j)]);
      const int column = m * static_cast<int>(k) + j;
      values_.col(column) = phi;
      dx_.col(column) << phi(1), 2.0 * phi(3), phi(4);
      dy_.col(column) << phi(2), phi(4), 2.0 * phi(5);
    }
  }
}

ShapeVector NmmShape::values_at(const Point2& x) const {
  return values_.transpose() * monomials(x - origin_);
}

InterpolationMatrix NmmShape::interpolation_at(const Point2& x) const {
  const ShapeVector phi = values_at(x);
  InterpolationMatrix t = InterpolationMatrix::Zero(2, n_dofs());
  for (int a = 0; a < n_shapes(); ++a) {
    t(0, 2 * a) = phi(a);
    t(1, 2 * a + 1) = phi(a);
  }
  return t;
}

Point2 NmmShape::displacement_at(const Point2& x, std::span<const double> dofs) const {
  NMM_ASSERT(static_cast<int>(dofs.size()) == n_dofs(), "wrong number of element unknowns");
  const ShapeVector phi = values_at(x);
  Point2 u = Point2::Zero();
  for (int a = 0; a < n_shapes(); ++a) {
    u.x() += phi(a) * dofs[static_cast<std::size_t>(2 * a)];
    u.y() += phi(a) * dofs[static_cast<std::size_t>(2 * a + 1)];
  }
  return u;
}

LinearField3 NmmShape::strain(std::span<const double> dofs) const {
  NMM_ASSERT(static_cast<int>(dofs.size()) == n_dofs(), "wrong number of element unknowns");
  LinearField3 field;
  field.origin = origin_;
  for (int a = 0; a < n_shapes(); ++a) {
    const double u = dofs[static_cast<std::size_t>(2 * a)];
    const double v = dofs[static_cast<std::size_t>(2 * a + 1)];
    field.coefficients.row(0) += dx_.col(a).transpose() * u;
    field.coefficients.row(1) += dy_.col(a).transpose() * v;
    field.coefficients.row(2) += dy_.col(a).transpose() * u + dx_.col(a).transpose() * v;
  }
  return field;
}

NmmElementIntegrals::NmmElementIntegrals(const NmmShape& shape, std::span<const Polygon> polygons)
    : shape_(shape) {
  // Degree of the mass integrand: shape functions are of degree order + 1.
  const int degree = 2 * (shape.order() + 1);
  Moments2 moments(degree, shape.origin());
  for (const Polygon& polygon : polygons)
    moments += polygon_moments(polygon, degree, shape.origin());
  area_ = moments.area();
  first_.setZero();
  second_.setZero();
  for (std::size_t i = 0; i < 6; ++i) {
    if (exponents[i][0] + exponents[i][1] <= degree)
      first_(static_cast<Eigen::Index>(i)) = moments(exponents[i][0], exponents[i][1]);
    for (std::size_t j = 0; j < 6; ++j) {
      const int a = exponents[i][0] + exponents[j][0];
      const int b = exponents[i][1] + exponents[j][1];
      if (a + b <= degree)
        second_(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = moments(a, b);
    }
  }
  linear_ = second_.topLeftCorner<3, 3>();
}

ElementMatrix NmmElementIntegrals::stiffness(const Eigen::Matrix3d& d, double thickness) const {
  const auto& dx = shape_.dx();
  const auto& dy = shape_.dy();
  const ShapeMatrix gxx = dx.transpose() * linear_ * dx;
  const ShapeMatrix gxy = dx.transpose() * linear_ * dy; // ∫ phi_a,x phi_b,y
  const ShapeMatrix gyy = dy.transpose() * linear_ * dy;
  const ShapeMatrix gyx = gxy.transpose();
  const int n = shape_.n_shapes();
  ElementMatrix k(2 * n, 2 * n);
  // B_a^u = (phi_a,x, 0, phi_a,y), B_a^v = (0, phi_a,y, phi_a,x): the 2x2 blocks of B^T D B.
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      k(2 * a, 2 * b) =
          d(0, 0) * gxx(a, b) + d(0, 2) * gxy(a, b) + d(2, 0) * gyx(a, b) + d(2, 2) * gyy(a, b);
      k(2 * a, 2 * b + 1) =
          d(0, 1) * gxy(a, b) + d(0, 2) * gxx(a, b) + d(2, 1) * gyy(a, b) + d(2, 2) * gyx(a, b);
      k(2 * a + 1, 2 * b) =
          d(1, 0) * gyx(a, b) + d(1, 2) * gyy(a, b) + d(2, 0) * gxx(a, b) + d(2, 2) * gxy(a, b);
      k(2 * a + 1, 2 * b + 1) =
          d(1, 1) * gyy(a, b) + d(1, 2) * gyx(a, b) + d(2, 1) * gxy(a, b) + d(2, 2) * gxx(a, b);
    }
  }
  return thickness * k;
}

ShapeMatrix NmmElementIntegrals::scalar_mass(double density_thickness) const {
  const auto& c = shape_.values();
  return density_thickness * (c.transpose() * second_ * c);
}

ElementMatrix NmmElementIntegrals::mass(double density_thickness) const {
  const ShapeMatrix scalar = scalar_mass(1.0);
  const int n = shape_.n_shapes();
  ElementMatrix m = ElementMatrix::Zero(2 * n, 2 * n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      m(2 * a, 2 * b) = scalar(a, b);
      m(2 * a + 1, 2 * b + 1) = scalar(a, b);
    }
  }
  return density_thickness * m;
}

ElementVector NmmElementIntegrals::body_force(const Point2& force, double thickness) const {
  const ShapeVector integrals = shape_.values().transpose() * first_;
  const int n = shape_.n_shapes();
  ElementVector f(2 * n);
  for (int a = 0; a < n; ++a) {
    f(2 * a) = thickness * force.x() * integrals(a);
    f(2 * a + 1) = thickness * force.y() * integrals(a);
  }
  return f;
}

ElementVector NmmElementIntegrals::initial_stress_load(const LinearField3& stress,
                                                       double thickness) const {
  const LinearField3 local = stress.about(shape_.origin());
  const Eigen::Vector3d sxx = linear_ * local.coefficients.row(0).transpose();
  const Eigen::Vector3d syy = linear_ * local.coefficients.row(1).transpose();
  const Eigen::Vector3d sxy = linear_ * local.coefficients.row(2).transpose();
  const auto& dx = shape_.dx();
  const auto& dy = shape_.dy();
  const int n = shape_.n_shapes();
  ElementVector f(2 * n);
  for (int a = 0; a < n; ++a) {
    f(2 * a) = -thickness * (dx.col(a).dot(sxx) + dy.col(a).dot(sxy));
    f(2 * a + 1) = -thickness * (dy.col(a).dot(syy) + dx.col(a).dot(sxy));
  }
  return f;
}

} // namespace nmm
