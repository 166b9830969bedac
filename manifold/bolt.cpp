// SPDX-License-Identifier: MIT
#include "manifold/bolt.hpp"

#include "manifold/element.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>

namespace nmm {

namespace {

/// Parameters t in (0, 1) at which the segment p + t (q - p) crosses an edge of @p loop.
void add_crossings(const Loop& loop, const Point2& p, const Point2& q, std::vector<double>& ts) {
  const Point2 r = q - p;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Point2& a = loop[i];
    const Point2 s = loop[(i + 1) % loop.size()] - a;
    const double denominator = r.x() * s.y() - r.y() * s.x();
    if (denominator == 0.0)
      continue; // parallel: the ends of the edge's neighbours cross instead
    const Point2 ap = a - p;
    const double t = (ap.x() * s.y() - ap.y() * s.x()) / denominator;
    const double u = (ap.x() * r.y() - ap.y() * r.x()) / denominator;
    if (t > 0.0 && t < 1.0 && u >= 0.0 && u <= 1.0)
      ts.push_back(t);
  }
}

/// The pieces of the segment @p p -> @p q in the material, in order: (element, t0, t1).
struct Chord {
  int element = -1;
  double t0 = 0.0;
  double t1 = 0.0;
};

std::vector<Chord>
chords_through(const Model& model, const Point2& p, const Point2& q, double tolerance) {
  BoundingBox segment;
  segment.extend(p);
  segment.extend(q);
  std::vector<double> ts{0.0, 1.0};
  for (const ModelElement& element : model.elements) {
    for (const Polygon& polygon : element.polygons) {
      const BoundingBox box = bounding_box(polygon.outer);
      if (box.min.x() > segment.max.x() || box.max.x() < segment.min.x() ||
          box.min.y() > segment.max.y() || box.max.y() < segment.min.y())
        continue;
      add_crossings(polygon.outer, p, q, ts);
      for (const Loop& hole : polygon.holes)
        add_crossings(hole, p, q, ts);
    }
  }
  std::sort(ts.begin(), ts.end());
  const double length = (q - p).norm();
  std::vector<Chord> chords;
  for (std::size_t i = 0; i + 1 < ts.size(); ++i) {
    if ((ts[i + 1] - ts[i]) * length <= tolerance)
      continue;
    const int element = model.find_element(p + 0.5 * (ts[i] + ts[i + 1]) * (q - p), 0.0);
    if (element < 0)
      continue; // an opening the bolt spans
    if (!chords.empty() && chords.back().element == element && chords.back().t1 == ts[i])
      chords.back().t1 = ts[i + 1];
    else
      chords.push_back({element, ts[i], ts[i + 1]});
  }
  return chords;
}

/// The unit vector from a bar's first point to its second, at their current positions.
Point2 direction(const BoltBar& bar) {
  const Point2 d = bar.b.position - bar.a.position;
  const double length = d.norm();
  return length > 0.0 ? Point2(d / length) : Point2(1.0, 0.0);
}

/// b: the bar's elongation is b^T d on its unknowns @p dofs (append_bar_dofs()).
Eigen::VectorXd
elongation_vector(const Model& model, const BoltBar& bar, std::span<const int> dofs) {
  const Point2 n = direction(bar);
  const PointInterpolation ta = model.shape(bar.a.element).interpolation_at(bar.a.position);
  const PointInterpolation tb = model.shape(bar.b.element).interpolation_at(bar.b.position);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(dofs.size()));
  b.head(ta.cols()) = -(ta.transpose() * n);
  const std::span<const int> b_dofs = model.element_dofs(bar.b.element);
  for (std::size_t j = 0; j < b_dofs.size(); ++j) {
    const auto k = std::find(dofs.begin(), dofs.end(), b_dofs[j]) - dofs.begin();
    b(k) += tb.col(static_cast<Eigen::Index>(j)).dot(n);
  }
  return b;
}

/// Whether both ends of @p bar are in material that is still there.
bool anchored(const Model& model, const BoltBar& bar) {
  return !model.elements[static_cast<std::size_t>(bar.a.element)].excavated &&
         !model.elements[static_cast<std::size_t>(bar.b.element)].excavated;
}

double tangent_stiffness(const Bolt& bolt, const BoltBar& bar) {
  switch (bar.state) {
  case BoltState::elastic:
    return bar.stiffness;
  case BoltState::yielding:
    return bolt.hardening * bar.stiffness;
  case BoltState::ruptured:
    break;
  }
  return 0.0;
}

/// One bar through a step of elongation @p d (Bolt::hardening, rupture_force): its new
/// force and state, and the work its force did along the path, J.
double advance_bar(const Bolt& bolt, BoltBar& bar, double d) {
  const double k = bar.stiffness;
  const double kt = bolt.hardening * k;
  const double n0 = bar.force;
  double work = 0.0;
  double force = n0;
  const bool loading = d * n0 > 0.0;
  if (bar.state == BoltState::yielding && loading) {
    force = n0 + kt * d; // along the hardening line
    work = n0 * d + 0.5 * kt * d * d;
  } else {
    bar.state = BoltState::elastic; // (a yielding bar that unloads)
    const double trial = n0 + k * d;
    if (std::abs(trial) <= bar.yield_force) {
      force = trial;
      work = n0 * d + 0.5 * k * d * d;
    } else {
      // Elastic to the yield force, then along the hardening line.
      const double sign = trial > 0.0 ? 1.0 : -1.0;
      const double yield = sign * bar.yield_force;
      const double plastic = (trial - yield) / k; // the elongation beyond the yield point
      force = yield + kt * plastic;
      work = (yield * yield - n0 * n0) / (2.0 * k) + yield * plastic + 0.5 * kt * plastic * plastic;
      bar.state = BoltState::yielding;
    }
  }
  if (bar.state == BoltState::yielding)
    bar.yield_force = std::max(bar.yield_force, std::abs(force));
  if (std::abs(force) >= bolt.rupture_force) {
    bar.state = BoltState::ruptured;
    force = 0.0;
  }
  bar.force = force;
  return work;
}

} // namespace

const char* bolt_state_name(BoltState state) {
  switch (state) {
  case BoltState::elastic:
    return "elastic";
  case BoltState::yielding:
    return "yielding";
  case BoltState::ruptured:
    break;
  }
  return "ruptured";
}

double Bolt::force() const {
  double largest = 0.0;
  for (const BoltBar& bar : bars) {
    if (std::abs(bar.force) > std::abs(largest))
      largest = bar.force;
  }
  return largest;
}

BoltState Bolt::state() const {
  const BoltBar* largest = nullptr;
  for (const BoltBar& bar : bars) {
    if (bar.state != BoltState::ruptured &&
        (largest == nullptr || std::abs(bar.force) > std::abs(largest->force)))
      largest = &bar;
  }
  return largest == nullptr ? BoltState::ruptured : largest->state;
}

std::vector<BoltBar> make_bolt_bars(const Model& model,
                                    BoltKind kind,
                                    const Point2& from,
                                    const Point2& to,
                                    double axial_rigidity,
                                    double pretension,
                                    double yield_force,
                                    double tolerance) {
  const int first = model.find_element(from, tolerance);
  const int last = model.find_element(to, tolerance);
  if (first < 0 || last < 0)
    return {};
  std::vector<MaterialPoint> nodes{{first, from}};
  if (kind == BoltKind::grouted) {
    const std::vector<Chord> chords = chords_through(model, from, to, tolerance);
    // Interior nodes: the mid-points of the chords between the first and the last.
    for (std::size_t i = 1; i + 1 < chords.size(); ++i)
      nodes.push_back(
          {chords[i].element, from + 0.5 * (chords[i].t0 + chords[i].t1) * (to - from)});
  }
  nodes.push_back({last, to});
  std::vector<BoltBar> bars;
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) {
    BoltBar bar;
    bar.a = nodes[i];
    bar.b = nodes[i + 1];
    const double length = (bar.b.position - bar.a.position).norm();
    NMM_ASSERT(length > 0.0, "a bolt's bars have a length");
    bar.stiffness = axial_rigidity / length;
    bar.force = pretension;
    bar.yield_force = yield_force;
    bars.push_back(bar);
  }
  return bars;
}

void append_bar_dofs(const Model& model, const BoltBar& bar, std::vector<int>& dofs) {
  const std::span<const int> a = model.element_dofs(bar.a.element);
  const auto first = static_cast<std::ptrdiff_t>(dofs.size());
  dofs.insert(dofs.end(), a.begin(), a.end());
  // Neighbouring NMM elements share covers: each unknown once.
  for (const int d : model.element_dofs(bar.b.element)) {
    if (std::find(dofs.begin() + first, dofs.begin() + first + std::ssize(a), d) ==
        dofs.begin() + first + std::ssize(a))
      dofs.push_back(d);
  }
}

void bar_spring(const Model& model,
                const Bolt& bolt,
                const BoltBar& bar,
                std::span<const int> dofs,
                Eigen::MatrixXd& stiffness,
                Eigen::VectorXd& load) {
  const Eigen::VectorXd b = elongation_vector(model, bar, dofs);
  if (!anchored(model, bar)) { // an end on excavated material: nothing to hold
    stiffness = Eigen::MatrixXd::Zero(b.size(), b.size());
    load = Eigen::VectorXd::Zero(b.size());
    return;
  }
  stiffness = tangent_stiffness(bolt, bar) * b * b.transpose();
  load = -bar.force * b;
}

double elastic_energy(std::span<const Bolt> bolts) {
  double energy = 0.0;
  for (const Bolt& bolt : bolts) {
    for (const BoltBar& bar : bolt.bars)
      energy += bar.elastic_energy();
  }
  return energy;
}

BoltWork advance_bolts(const Model& model, std::span<Bolt> bolts, const Eigen::VectorXd& raw) {
  BoltWork work;
  for (Bolt& bolt : bolts) {
    for (BoltBar& bar : bolt.bars) {
      if (bar.state == BoltState::ruptured)
        continue;
      if (!anchored(model, bar)) {
        work.dissipated += bar.elastic_energy();
        work.elastic_change -= bar.elastic_energy();
        bar.force = 0.0;
        continue;
      }
      const double d = direction(bar).dot(model.displacement(bar.b.element, bar.b.position, raw) -
                                          model.displacement(bar.a.element, bar.a.position, raw));
      const double tangent = tangent_stiffness(bolt, bar);
      work.quadratic += 0.5 * tangent * d * d;
      const double before = bar.elastic_energy();
      const double done = advance_bar(bolt, bar, d);
      const double after = bar.elastic_energy();
      work.elastic_change += after - before;
      work.dissipated += done - (after - before);
    }
  }
  return work;
}

} // namespace nmm
