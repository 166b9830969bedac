// SPDX-License-Identifier: MIT
#include "manifold/element.hpp"

#include "mesh/error.hpp"

#include <numeric>

namespace nmm {

namespace {

template <class... F> struct Overloaded : F... { using F::operator()...; };
template <class... F> Overloaded(F...) -> Overloaded<F...>;

} // namespace

int ElementShape::n_dofs() const {
  return std::visit(Overloaded{[](const NmmShape& s) { return s.n_dofs(); },
                               [](const DdaShape&) { return dda_block_dofs; },
                               [](const VemShape& s) { return s.n_dofs(); }},
                    shape_);
}

Point2 ElementShape::origin() const {
  return std::visit([](const auto& s) { return Point2(s.origin()); }, shape_);
}

PointInterpolation ElementShape::interpolation_at(const Point2& x) const {
  PointInterpolation t;
  interpolation_at(x, t);
  return t;
}

void ElementShape::interpolation_at(const Point2& x, PointInterpolation& out) const {
  std::visit([&](const auto& s) { out = s.interpolation_at(x); }, shape_);
}

void ElementShape::interpolation_on_edge(const Point2& x,
                                         const Point2& a,
                                         const Point2& b,
                                         PointInterpolation& out,
                                         std::vector<int>& columns) const {
  if (const VemShape* vem = std::get_if<VemShape>(&shape_)) {
    vem->interpolation_on_edge(x, a, b, out, columns);
    return;
  }
  interpolation_at(x, out);
  columns.resize(static_cast<std::size_t>(out.cols()));
  std::iota(columns.begin(), columns.end(), 0);
}

Point2 ElementShape::displacement_at(const Point2& x, std::span<const double> d) const {
  return std::visit([&](const auto& s) { return s.displacement_at(x, d); }, shape_);
}

Point2 ElementShape::moved(const Point2& x, std::span<const double> d) const {
  return std::visit(Overloaded{[&](const DdaShape& s) { return s.moved(x, d); },
                               [&](const auto& s) { return Point2(x + s.displacement_at(x, d)); }},
                    shape_);
}

LinearField3 ElementShape::strain(std::span<const double> d) const {
  return std::visit([&](const auto& s) { return s.strain(d); }, shape_);
}

double ElementShape::rotation(std::span<const double> d) const {
  return std::visit(Overloaded{[&](const NmmShape& s) {
                                 // (dv/dx - du/dy) / 2 at the origin of the local coordinates.
                                 double du_dy = 0.0;
                                 double dv_dx = 0.0;
                                 for (int a = 0; a < s.n_shapes(); ++a) {
                                   du_dy += s.dy()(0, a) * d[static_cast<std::size_t>(2 * a)];
                                   dv_dx += s.dx()(0, a) * d[static_cast<std::size_t>(2 * a + 1)];
                                 }
                                 return 0.5 * (dv_dx - du_dy);
                               },
                               [&](const DdaShape&) { return d[2]; },
                               [&](const VemShape& s) { return s.rotation(d); }},
                    shape_);
}

void ElementMass::add_to(Eigen::MatrixXd& local, double factor) const {
  if (!scalar) {
    local += factor * matrix;
    return;
  }
  const Eigen::Index n = matrix.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    for (Eigen::Index i = 0; i < n; ++i) {
      local(2 * i, 2 * j) += factor * matrix(i, j);
      local(2 * i + 1, 2 * j + 1) += factor * matrix(i, j);
    }
  }
}

void ElementMass::times(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  out.resize(v.size());
  if (!scalar) {
    out.noalias() = matrix * v;
    return;
  }
  // The scalar matrix on u (even entries) and on v (odd entries) alike.
  const Eigen::Index n = matrix.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    double u_sum = 0.0;
    double v_sum = 0.0;
    for (Eigen::Index j = 0; j < n; ++j) {
      u_sum += matrix(i, j) * v(2 * j);
      v_sum += matrix(i, j) * v(2 * j + 1);
    }
    out(2 * i) = u_sum;
    out(2 * i + 1) = v_sum;
  }
}

double ElementMass::energy(const Eigen::VectorXd& v) const {
  if (!scalar)
    return 0.5 * v.dot(matrix * v);
  double sum = 0.0;
  const Eigen::Index n = matrix.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    for (Eigen::Index j = 0; j < n; ++j)
      sum += matrix(i, j) * (v(2 * i) * v(2 * j) + v(2 * i + 1) * v(2 * j + 1));
  }
  return 0.5 * sum;
}

ElementIntegrals::ElementIntegrals(const ElementShape& shape, std::span<const Polygon> polygons)
    : integrals_(std::visit(
          Overloaded{[&](const NmmShape& s) {
                       return std::variant<NmmElementIntegrals, DdaIntegrals, VemIntegrals>(
                           std::in_place_type<NmmElementIntegrals>, s, polygons);
                     },
                     [&](const DdaShape& s) {
                       return std::variant<NmmElementIntegrals, DdaIntegrals, VemIntegrals>(
                           std::in_place_type<DdaIntegrals>, s, polygons);
                     },
                     [&](const VemShape& s) {
                       return std::variant<NmmElementIntegrals, DdaIntegrals, VemIntegrals>(
                           std::in_place_type<VemIntegrals>, s, polygons);
                     }},
          shape.shape_)) {}

double ElementIntegrals::area() const {
  return std::visit([](const auto& i) { return i.area(); }, integrals_);
}

void ElementIntegrals::stiffness(const Eigen::Matrix3d& d,
                                 double thickness,
                                 Eigen::MatrixXd& out) const {
  std::visit([&](const auto& i) { out = i.stiffness(d, thickness); }, integrals_);
}

void ElementIntegrals::mass(double density_thickness, ElementMass& out) const {
  std::visit(Overloaded{[&](const NmmElementIntegrals& i) {
                          out.scalar = true;
                          out.matrix = i.scalar_mass(density_thickness);
                        },
                        [&](const auto& i) {
                          out.scalar = false;
                          out.matrix = i.mass(density_thickness);
                        }},
             integrals_);
}

void ElementIntegrals::loads(const Point2& force,
                             const LinearField3& stress,
                             double thickness,
                             Eigen::VectorXd& out) const {
  std::visit(
      [&](const auto& i) {
        out = i.body_force(force, thickness);
        if (!stress.coefficients.isZero())
          out += i.initial_stress_load(stress, thickness);
      },
      integrals_);
}

void ElementIntegrals::add_stabilisation_load(const Eigen::VectorXd& carried,
                                              Eigen::VectorXd& out) const {
  if (carried.size() == 0)
    return;
  const VemIntegrals* vem = std::get_if<VemIntegrals>(&integrals_);
  NMM_ASSERT(vem != nullptr, "a carried stabilisation force on an element that is not VEM");
  out += vem->stabilisation_load(carried);
}

} // namespace nmm
