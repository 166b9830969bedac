// SPDX-License-Identifier: MIT
#include "manifold/dda_block.hpp"

#include "manifold/simplex_integration.hpp"

#include <cmath>

namespace nmm {

Eigen::Matrix<double, 2, 6> dda_basis(const Point2& origin, const Point2& x) {
  const double dx = x.x() - origin.x();
  const double dy = x.y() - origin.y();
  Eigen::Matrix<double, 2, 6> t;
  t << 1.0, 0.0, -dy, dx, 0.0, 0.5 * dy, //
      0.0, 1.0, dx, 0.0, dy, 0.5 * dx;
  return t;
}

DdaMoments dda_moments(const Point2& origin, std::span<const Polygon> polygons) {
  Moments2 m(2, origin);
  for (const Polygon& polygon : polygons)
    m += polygon_moments(polygon, 2, origin);
  DdaMoments result;
  result.area = m.area();
  // T = [1 0 -Y X 0 Y/2; 0 1 X 0 Y X/2]: each entry a polynomial a + b X + c Y.
  using Row = std::array<Eigen::Vector3d, 6>;
  const Row u = {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, -1),
                 Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 0.5)};
  const Row v = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 1, 0),
                 Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0.5, 0)};
  // ∫ (1, X, Y)^T (1, X, Y).
  Eigen::Matrix3d products;
  products << m(0, 0), m(1, 0), m(0, 1), //
      m(1, 0), m(2, 0), m(1, 1),         //
      m(0, 1), m(1, 1), m(0, 2);
  const Eigen::Vector3d first(m(0, 0), m(1, 0), m(0, 1));
  for (int i = 0; i < 6; ++i) {
    result.mean(0, i) = u[static_cast<std::size_t>(i)].dot(first);
    result.mean(1, i) = v[static_cast<std::size_t>(i)].dot(first);
    for (int j = 0; j < 6; ++j) {
      const auto a = static_cast<std::size_t>(i);
      const auto b = static_cast<std::size_t>(j);
      result.mass(i, j) = u[a].dot(products * u[b]) + v[a].dot(products * v[b]);
    }
  }
  return result;
}

Point2 DdaShape::displacement_at(const Point2& x, std::span<const double> d) const {
  const Eigen::Map<const Eigen::Matrix<double, 6, 1>> values(d.data());
  return dda_basis(origin_, x) * values;
}

Point2 DdaShape::moved(const Point2& x, std::span<const double> d) const {
  const Point2 r = x - origin_;
  const double c = std::cos(d[2]);
  const double s = std::sin(d[2]);
  const Point2 turned(c * r.x() - s * r.y(), s * r.x() + c * r.y());
  const Point2 stretched(d[3] * r.x() + 0.5 * d[5] * r.y(), 0.5 * d[5] * r.x() + d[4] * r.y());
  return origin_ + Point2(d[0], d[1]) + turned + stretched;
}

LinearField3 DdaShape::strain(std::span<const double> d) const {
  LinearField3 field;
  field.origin = origin_;
  field.coefficients.col(0) = Eigen::Vector3d(d[3], d[4], d[5]);
  return field;
}

DdaIntegrals::DdaIntegrals(const DdaShape& shape, std::span<const Polygon> polygons)
    : shape_(shape), moments_(dda_moments(shape.origin(), polygons)) {
  // ∫ (X, Y) from the mean of T: its entries (0, 3) = ∫ X and (1, 4) = ∫ Y.
  first_ = Eigen::Vector2d(moments_.mean(0, 3), moments_.mean(1, 4));
}

Eigen::Matrix<double, 6, 6> DdaIntegrals::stiffness(const Eigen::Matrix3d& d,
                                                    double thickness) const {
  Eigen::Matrix<double, 6, 6> k = Eigen::Matrix<double, 6, 6>::Zero();
  k.bottomRightCorner<3, 3>() = moments_.area * thickness * d;
  return k;
}

Eigen::Matrix<double, 6, 6> DdaIntegrals::mass(double density_thickness) const {
  return density_thickness * moments_.mass;
}

Eigen::Matrix<double, 6, 1> DdaIntegrals::body_force(const Point2& force, double thickness) const {
  return thickness * moments_.mean.transpose() * force;
}

Eigen::Matrix<double, 6, 1> DdaIntegrals::initial_stress_load(const LinearField3& stress,
                                                              double thickness) const {
  // ∫ sigma = sigma(origin) area + gradient . ∫ (x - origin).
  const Eigen::Vector3d at_origin = stress.at(shape_.origin());
  const Eigen::Vector3d integral = at_origin * moments_.area +
                                   stress.coefficients.col(1) * first_.x() +
                                   stress.coefficients.col(2) * first_.y();
  Eigen::Matrix<double, 6, 1> f = Eigen::Matrix<double, 6, 1>::Zero();
  f.tail<3>() = -thickness * integral;
  return f;
}

} // namespace nmm
