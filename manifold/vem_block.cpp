// SPDX-License-Identifier: MIT
#include "manifold/vem_block.hpp"

#include "manifold/dda_block.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

} // namespace

VemShape::VemShape(std::span<const Polygon> polygons) {
  auto add_loop = [&](const Loop& loop) {
    const int first = n_vertices();
    const int n = static_cast<int>(loop.size());
    for (int k = 0; k < n; ++k) {
      vertices_.push_back(loop[at(k)]);
      next_.push_back(first + (k + 1) % n);
    }
  };
  for (const Polygon& polygon : polygons) {
    add_loop(polygon.outer);
    for (const Loop& hole : polygon.holes)
      add_loop(hole);
  }
  const int n = n_vertices();
  NMM_ASSERT(n >= 3, "a VEM block needs at least three vertices");
  for (const Point2& p : vertices_)
    origin_ += p / static_cast<double>(n);
  BoundingBox box;
  for (const Point2& p : vertices_)
    box.extend(p);
  size_ = std::max(box.size().x(), box.size().y());
  // q_i = (l_i n_i + l_{i+1} n_{i+1}) / 2 over the two edges at vertex i (eq. 34): the
  // boundary integral of u n with u linear on each edge gives sum_i q_i u_i. With the
  // material on the left of every edge a -> b, l n = (b.y - a.y, a.x - b.x). The area
  // comes from the same edges (about the origin, for accuracy far from 0).
  std::vector<Point2> q(at(n), Point2::Zero());
  double twice_area = 0.0;
  for (int i = 0; i < n; ++i) {
    const Point2 a = vertices_[at(i)] - origin_;
    const Point2 b = vertices_[at(next_[at(i)])] - origin_;
    const Point2 ln(b.y() - a.y(), a.x() - b.x());
    q[at(i)] += 0.5 * ln;
    q[at(next_[at(i)])] += 0.5 * ln;
    twice_area += a.x() * b.y() - a.y() * b.x();
  }
  area_ = 0.5 * twice_area;
  projector_ = Eigen::MatrixXd::Zero(6, 2 * n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Index u = 2 * i;
    const Eigen::Index v = 2 * i + 1;
    const Point2 g = q[at(i)] / area_;
    projector_(0, u) = 1.0 / n;
    projector_(1, v) = 1.0 / n;
    projector_(2, u) = -0.5 * g.y();
    projector_(2, v) = 0.5 * g.x();
    projector_(3, u) = g.x();
    projector_(4, v) = g.y();
    projector_(5, u) = g.y();
    projector_(5, v) = g.x();
  }
}

Eigen::Matrix<double, 2, Eigen::Dynamic> VemShape::interpolation_at(const Point2& x) const {
  Eigen::Matrix<double, 2, Eigen::Dynamic> t =
      Eigen::Matrix<double, 2, Eigen::Dynamic>::Zero(2, n_dofs());
  // The nearest edge.
  int best = -1;
  double best_distance = std::numeric_limits<double>::infinity();
  double best_s = 0.0;
  for (int i = 0; i < n_vertices(); ++i) {
    const Point2& a = vertices_[at(i)];
    const Point2& b = vertices_[at(next_[at(i)])];
    const Point2 ab = b - a;
    const double length2 = ab.squaredNorm();
    const double s = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    const double distance = (x - (a + s * ab)).norm();
    if (distance < best_distance) {
      best_distance = distance;
      best = i;
      best_s = s;
    }
  }
  if (best >= 0 && best_distance <= 1e-9 * size_) {
    const int j = next_[at(best)];
    t(0, 2 * best) = 1.0 - best_s;
    t(1, 2 * best + 1) = 1.0 - best_s;
    t(0, 2 * j) += best_s;
    t(1, 2 * j + 1) += best_s;
    return t;
  }
  return dda_basis(origin_, x) * projector_;
}

void VemShape::interpolation_on_edge(const Point2& x,
                                     const Point2& a,
                                     const Point2& b,
                                     Eigen::Matrix<double, 2, Eigen::Dynamic>& out,
                                     std::vector<int>& columns) const {
  // The edge a -> b among the block's: its own vertices (the contact boundary and the shape
  // are built from the same coordinates), else the nearest pair.
  int edge = -1;
  double nearest = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n_vertices() && nearest > 0.0; ++i) {
    const double d = (vertices_[at(i)] - a).norm() + (vertices_[at(next_[at(i)])] - b).norm();
    if (d < nearest) {
      nearest = d;
      edge = i;
    }
  }
  const int i = edge;
  const int j = next_[at(i)];
  const Point2 ab = vertices_[at(j)] - vertices_[at(i)];
  const double length2 = ab.squaredNorm();
  // As interpolation_at() on the edge; past its ends, the edge's line.
  const double s = length2 > 0.0 ? (x - vertices_[at(i)]).dot(ab) / length2 : 0.0;
  out.setZero(2, 4);
  out(0, 0) = 1.0 - s;
  out(1, 1) = 1.0 - s;
  out(0, 2) = s;
  out(1, 3) = s;
  columns.assign({2 * i, 2 * i + 1, 2 * j, 2 * j + 1});
}

Point2 VemShape::displacement_at(const Point2& x, std::span<const double> d) const {
  const Eigen::Map<const Eigen::VectorXd> values(d.data(), n_dofs());
  return interpolation_at(x) * values;
}

LinearField3 VemShape::strain(std::span<const double> d) const {
  const Eigen::Map<const Eigen::VectorXd> values(d.data(), n_dofs());
  LinearField3 field;
  field.origin = origin_;
  field.coefficients.col(0) = projector_.bottomRows<3>() * values;
  return field;
}

double VemShape::rotation(std::span<const double> d) const {
  const Eigen::Map<const Eigen::VectorXd> values(d.data(), n_dofs());
  return projector_.row(2).dot(values);
}

Eigen::MatrixXd VemShape::vertex_projection() const {
  const int n = n_vertices();
  Eigen::MatrixXd pu(2 * n, 2 * n);
  for (int i = 0; i < n; ++i)
    pu.middleRows(2 * i, 2) = dda_basis(origin_, vertices_[at(i)]) * projector_;
  return pu;
}

Eigen::MatrixXd VemShape::consistency_stiffness(const Eigen::Matrix3d& elasticity,
                                                double thickness) const {
  const Eigen::MatrixXd pc = projector_.bottomRows<3>();
  return (area_ * thickness) * pc.transpose() * elasticity * pc;
}

Eigen::VectorXd VemShape::stabilisation_force(const Eigen::Matrix3d& elasticity,
                                              double thickness,
                                              std::span<const double> d) const {
  const Eigen::Map<const Eigen::VectorXd> values(d.data(), n_dofs());
  const Eigen::MatrixXd pu = vertex_projection();
  // eq. 49 with eta_E of eq. 52, as in VemIntegrals::stiffness(): eta (I - P_u)^T (I - P_u) d.
  const double eta = consistency_stiffness(elasticity, thickness).trace() / pu.squaredNorm();
  const Eigen::VectorXd residual = values - pu * values;
  return eta * (residual - pu.transpose() * residual);
}

VemIntegrals::VemIntegrals(const VemShape& shape, std::span<const Polygon> polygons)
    : shape_(shape) {
  const int n = shape.n_vertices();
  // P_u (eq. 50): Pi_P u at the vertices, T*(x_i) H.
  const Eigen::MatrixXd pu = shape.vertex_projection();
  residual_ = Eigen::MatrixXd::Identity(2 * n, 2 * n) - pu;
  stabilisation_ = residual_.transpose() * residual_;
  projection_trace_ = pu.squaredNorm(); // trace(P_u^T P_u)
  const DdaMoments m = dda_moments(shape.origin(), polygons);
  basis_mass_ = m.mass;
  basis_mean_ = m.mean;
  first_ = Eigen::Vector2d(m.mean(0, 3), m.mean(1, 4));
}

Eigen::MatrixXd VemIntegrals::stiffness(const Eigen::Matrix3d& d, double thickness) const {
  const Eigen::MatrixXd consistency = shape_.consistency_stiffness(d, thickness);
  const double eta = consistency.trace() / projection_trace_;
  return consistency + eta * stabilisation_;
}

Eigen::MatrixXd VemIntegrals::mass(double density_thickness) const {
  const Eigen::MatrixXd& h = shape_.projector();
  const Eigen::MatrixXd consistency = density_thickness * h.transpose() * basis_mass_ * h;
  const double eta = consistency.trace() / projection_trace_;
  return consistency + eta * stabilisation_;
}

Eigen::VectorXd VemIntegrals::body_force(const Point2& force, double thickness) const {
  return thickness * shape_.projector().transpose() * (basis_mean_.transpose() * force);
}

Eigen::VectorXd VemIntegrals::initial_stress_load(const LinearField3& stress,
                                                  double thickness) const {
  if (!stress.coefficients.rightCols<2>().isZero())
    return linear_stress_load(stress, thickness);
  const Eigen::Vector3d integral = stress.at(shape_.origin()) * shape_.area() +
                                   stress.coefficients.col(1) * first_.x() +
                                   stress.coefficients.col(2) * first_.y();
  return -thickness * shape_.projector().bottomRows<3>().transpose() * integral;
}

Eigen::VectorXd VemIntegrals::linear_stress_load(const LinearField3& stress,
                                                 double thickness) const {
  // -∫ eps(v) : sigma = -∮ v . sigma n + ∫ v . div sigma. On the boundary v is linear along
  // each edge and sigma n linear: two Gauss points per edge are exact. Inside v is virtual;
  // its integral against the constant div sigma goes through the projection, as the body
  // force does (eq. 61-63), so that with div sigma = -rho g the two cancel exactly and a
  // block whose faces carry sigma n (its joints' pre-loaded springs) stays in equilibrium.
  // The projected -S P_c^T sigma(mean) instead misses what the field's variation does on
  // the non-linear part of v: a block of a 10 m box under gravity moved 0.2 mm.
  const int n = shape_.n_vertices();
  Eigen::VectorXd f = Eigen::VectorXd::Zero(shape_.n_dofs());
  const double offset = 0.5 / std::sqrt(3.0);
  for (int i = 0; i < n; ++i) {
    const int j = shape_.next(i);
    const Point2& a = shape_.vertices()[at(i)];
    const Point2& b = shape_.vertices()[at(j)];
    const Point2 ln(b.y() - a.y(), a.x() - b.x()); // outward normal times length
    for (const double s : {0.5 - offset, 0.5 + offset}) {
      const Eigen::Vector3d sigma = stress.at(a + s * (b - a));
      const Point2 traction = 0.5 * Point2(sigma(0) * ln.x() + sigma(2) * ln.y(),
                                           sigma(2) * ln.x() + sigma(1) * ln.y());
      f.segment<2>(2 * i) -= (1.0 - s) * traction;
      f.segment<2>(2 * j) -= s * traction;
    }
  }
  const Eigen::Matrix3d& c = stress.coefficients;
  const Point2 divergence(c(0, 1) + c(2, 2), c(2, 1) + c(1, 2));
  return thickness * (f + body_force(divergence, 1.0));
}

Eigen::VectorXd VemIntegrals::stabilisation_load(const Eigen::VectorXd& carried) const {
  NMM_ASSERT(carried.size() == shape_.n_dofs(), "carried stabilisation force of the wrong size");
  return -(residual_.transpose() * carried);
}

} // namespace nmm
