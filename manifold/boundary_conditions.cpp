// SPDX-License-Identifier: MIT
#include "manifold/boundary_conditions.hpp"

#include "mesh/error.hpp"

#include <cmath>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

void add_local(std::span<const int> dofs, const Eigen::VectorXd& local, Eigen::VectorXd& f) {
  for (std::size_t i = 0; i < dofs.size(); ++i)
    f(dofs[i]) += local(static_cast<Eigen::Index>(i));
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
    if (s.method != SupportMethod::exact || s.point.element < 0 ||
        model.elements[at(s.point.element)].excavated)
      continue; // (a support on excavated material went with it)
    const PointInterpolation t = model.shape(s.point.element).interpolation_at(s.point.position);
    const std::span<const int> dofs = model.element_dofs(s.point.element);
    for (int component = 0; component < 2; ++component) {
      if ((component == 0 && !s.fix_x) || (component == 1 && !s.fix_y))
        continue;
      LinearConstraint row;
      row.origin = s.origin + " at " + point_text(s.point.position, 6);
      const Point2 remaining = s.ramp.at(time) * s.displacement - (s.point.position - s.start);
      row.value = component == 0 ? remaining.x() : remaining.y();
      for (std::size_t j = 0; j < dofs.size(); ++j) {
        const double coefficient = t(component, static_cast<Eigen::Index>(j));
        if (coefficient != 0.0)
          row.terms.emplace_back(dofs[j], coefficient);
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

void hold_supported_points(std::vector<SupportPoint>& supports, double time) {
  for (SupportPoint& s : supports) {
    if (s.method != SupportMethod::exact)
      continue;
    const Point2 held = s.start + s.ramp.at(time) * s.displacement;
    if (s.fix_x)
      s.point.position.x() = held.x();
    if (s.fix_y)
      s.point.position.y() = held.y();
  }
}

SupportSpring
support_spring(const Model& model, const SupportPoint& support, double stiffness, double time) {
  const PointInterpolation t =
      model.shape(support.point.element).interpolation_at(support.point.position);
  const Point2 remaining =
      support.ramp.at(time) * support.displacement - (support.point.position - support.start);
  SupportSpring spring{Eigen::MatrixXd::Zero(t.cols(), t.cols()), Eigen::VectorXd::Zero(t.cols())};
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

void element_load(const Model& model,
                  int element,
                  const ElementIntegrals& integrals,
                  std::span<const BodyLoad> body_loads,
                  double time,
                  Eigen::VectorXd& out) {
  const ElasticMaterial& material = model.material_of(element);
  Point2 force = Point2::Zero();
  for (const BodyLoad& load : body_loads)
    force += load.ramp.at(time) * material.density * load.acceleration;
  const ModelElement& e = model.elements[at(element)];
  integrals.loads(force, e.stress, material.thickness_factor(), out);
  integrals.add_stabilisation_load(e.stabilisation_force, out);
}

void add_point_load(const Model& model, const PointLoad& load, double time, Eigen::VectorXd& f) {
  const double factor = load.scale * load.ramp.at(time);
  if (factor == 0.0 || load.point.element < 0 || model.elements[at(load.point.element)].excavated)
    return;
  const PointInterpolation t =
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
    if (element < 0 || model.elements[at(element)].excavated)
      continue;
    const Point2 along = piece.b - piece.a;
    const double length = along.norm();
    if (length == 0.0)
      continue;
    // Outward normal: to the right of a -> b when the material is on the left.
    const Point2 right_normal = Point2(along.y(), -along.x()) / length;
    const Point2 outward = left ? right_normal : Point2(-right_normal);
    const double thickness = model.material_of(element).thickness_factor();
    const ElementShape shape = model.shape(element);
    Eigen::VectorXd local = Eigen::VectorXd::Zero(shape.n_dofs());
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
      const PointInterpolation t = shape.interpolation_at(x);
      local += w * length * thickness * factor * (t.transpose() * traction);
    }
    add_local(model.element_dofs(element), local, f);
  }
}

} // namespace nmm
