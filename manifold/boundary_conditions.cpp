// SPDX-License-Identifier: MIT
#include "manifold/boundary_conditions.hpp"

#include "mesh/error.hpp"

#include <cmath>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

void add_local(const ElementDofs& dofs, const ElementVector& local, Eigen::VectorXd& f) {
  for (Eigen::Index i = 0; i < dofs.size(); ++i)
    f(dofs(i)) += local(i);
}

} // namespace

std::vector<SupportPoint> curve_support_points(const Model& model,
                                               int curve,
                                               bool fix_x,
                                               bool fix_y,
                                               SupportMethod method,
                                               const std::string& origin) {
  std::vector<SupportPoint> points;
  for (const CurvePiece& piece : model.curve_pieces[at(curve)]) {
    for (const int element : {piece.left_element, piece.right_element}) {
      if (element < 0)
        continue;
      std::vector<Point2> where{piece.a, piece.b};
      if (model.order > 0)
        where.push_back(0.5 * (piece.a + piece.b));
      for (const Point2& x : where) {
        SupportPoint support;
        support.point = {element, x};
        support.fix_x = fix_x;
        support.fix_y = fix_y;
        support.method = method;
        support.origin = origin;
        support.start = x;
        points.push_back(std::move(support));
      }
    }
  }
  return points;
}

std::vector<LinearConstraint>
support_constraints(const Model& model, const std::vector<SupportPoint>& supports, double time) {
  std::vector<LinearConstraint> rows;
  for (const SupportPoint& s : supports) {
    if (s.method != SupportMethod::exact || s.point.element < 0)
      continue;
    const NmmShape shape = model.shape(s.point.element);
    const ShapeVector phi = shape.values_at(s.point.position);
    const ElementDofs dofs = model.element_dofs(s.point.element);
    for (int component = 0; component < 2; ++component) {
      if ((component == 0 && !s.fix_x) || (component == 1 && !s.fix_y))
        continue;
      LinearConstraint row;
      row.origin = s.origin + " at " + point_text(s.point.position, 6);
      const Point2 remaining = s.ramp.at(time) * s.displacement - (s.point.position - s.start);
      row.value = component == 0 ? remaining.x() : remaining.y();
      for (int a = 0; a < shape.n_shapes(); ++a) {
        if (phi(a) != 0.0)
          row.terms.emplace_back(dofs(2 * a + component), phi(a));
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

SupportSpring
support_spring(const Model& model, const SupportPoint& support, double stiffness, double time) {
  const InterpolationMatrix t =
      model.shape(support.point.element).interpolation_at(support.point.position);
  const Point2 remaining =
      support.ramp.at(time) * support.displacement - (support.point.position - support.start);
  SupportSpring spring{ElementMatrix::Zero(t.cols(), t.cols()), ElementVector::Zero(t.cols())};
  if (support.fix_x) {
    spring.stiffness += stiffness * t.row(0).transpose() * t.row(0);
    spring.load += stiffness * remaining.x() * t.row(0).transpose();
  }
  if (support.fix_y) {
    spring.stiffness += stiffness * t.row(1).transpose() * t.row(1);
    spring.load += stiffness * remaining.y() * t.row(1).transpose();
  }
  return spring;
}

ElementVector element_load(const Model& model,
                           int element,
                           const NmmElementIntegrals& integrals,
                           std::span<const BodyLoad> body_loads,
                           double time) {
  const ElasticMaterial& material = model.material_of(element);
  Point2 force = Point2::Zero();
  for (const BodyLoad& load : body_loads)
    force += load.ramp.at(time) * material.density * load.acceleration;
  ElementVector f = integrals.body_force(force, material.thickness_factor());
  const ModelElement& e = model.elements[at(element)];
  if (!e.stress.coefficients.isZero())
    f += integrals.initial_stress_load(e.stress, material.thickness_factor());
  return f;
}

void add_point_load(const Model& model, const PointLoad& load, double time, Eigen::VectorXd& f) {
  const double factor = load.ramp.at(time);
  if (factor == 0.0 || load.point.element < 0)
    return;
  const InterpolationMatrix t =
      model.shape(load.point.element).interpolation_at(load.point.position);
  add_local(model.element_dofs(load.point.element), t.transpose() * (factor * load.force), f);
}

void add_curve_load(const Model& model, const CurveLoad& load, double time, Eigen::VectorXd& f) {
  const double factor = load.ramp.at(time);
  if (factor == 0.0)
    return;
  // Two-point Gauss on each piece: exact for the shape functions of degree <= 2 times a
  // constant traction (degree 2 <= 3).
  const double g = 0.5 / std::sqrt(3.0);
  for (const CurvePiece& piece : model.curve_pieces[at(load.curve)]) {
    const bool left = piece.left_element >= 0;
    const int element = left ? piece.left_element : piece.right_element;
    if (element < 0)
      continue;
    const Point2 along = piece.b - piece.a;
    const double length = along.norm();
    if (length == 0.0)
      continue;
    // Outward normal: to the right of a -> b when the material is on the left.
    const Point2 right_normal = Point2(along.y(), -along.x()) / length;
    const Point2 outward = left ? right_normal : Point2(-right_normal);
    const double thickness = model.material_of(element).thickness_factor();
    const NmmShape shape = model.shape(element);
    ElementVector local = ElementVector::Zero(shape.n_dofs());
    // Constant loads: two Gauss points are exact. Loads given as fields of position: five
    // points per piece, exact to degree 9, so a smooth field is integrated to a tiny
    // fraction of the discretisation error.
    static const double five_points[5] = {0.04691007703066800, 0.23076534494715845, 0.5,
                                          0.76923465505284155, 0.95308992296933200};
    static const double five_weights[5] = {0.11846344252809454, 0.23931433524968324,
                                           0.28444444444444444, 0.23931433524968324,
                                           0.11846344252809454};
    const bool field = static_cast<bool>(load.traction_at) || static_cast<bool>(load.pressure_at);
    const int n_points = field ? 5 : 2;
    for (int q = 0; q < n_points; ++q) {
      const double s = field ? five_points[q] : (q == 0 ? 0.5 - g : 0.5 + g);
      const double w = field ? five_weights[q] : 0.5;
      const Point2 x = piece.a + s * along;
      double pressure = load.is_pressure ? load.pressure : 0.0;
      if (load.pressure_at)
        pressure += load.pressure_at(x);
      Point2 traction = (load.is_pressure ? Point2::Zero() : load.traction) - pressure * outward;
      if (load.traction_at)
        traction += load.traction_at(x);
      const InterpolationMatrix t = shape.interpolation_at(x);
      local += w * length * thickness * factor * (t.transpose() * traction);
    }
    add_local(model.element_dofs(element), local, f);
  }
}

} // namespace nmm
