// SPDX-License-Identifier: MIT
// contact/contact_kinematics.cpp — ContactSystem: the linearised kinematics of the contact
// points (Shi 1997, 3.4-3.5; eq. 3.12-3.16, 3.21-3.24), their cache and the gap samples of
// edge-to-edge pairs, the unknowns each point couples.
#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"
#include "mesh/error.hpp"
#include "mesh/parallel.hpp"

#include <algorithm>
#include <array>
#include <span>

namespace nmm {

using detail::at;
using detail::offset_at;
using detail::perp;

/// A term T_element(x)^T c of a point's gap or shear: the element's interpolation at x
/// (on the slave edge's line or the master's) against the direction c.
struct ContactSystem::Term {
  Point2 x;
  Point2 c;
};

/// What the kinematics of one point are assembled from: its two elements' unknowns and
/// shapes, the slave point and edge, the master edge with its unit tangent and outward
/// normal, and the master's terms of the gap and of the shear.
struct ContactSystem::PointTerms {
  std::span<const int> slave_dofs;
  std::span<const int> master_dofs;
  const ElementShape& slave_shape;
  const ElementShape& master_shape;
  Point2 slave;
  Point2 slave_a;
  Point2 slave_b;
  Point2 a;
  Point2 b;
  Point2 tangent;
  Point2 normal;
  std::array<Term, 5> master_normal{};
  std::size_t n_master_normal = 0;
  Term master_shear{};
};

double ContactSystem::projection(int master, const Point2& x) const {
  const Point2& a = boundary_.position[at(master)];
  const Point2 edge = boundary_.position[at(boundary_.next[at(master)])] - a;
  // Not clamped to the edge: a slave that has moved past the end of its master edge within
  // the step keeps its true offset (a clamped anchor would load the shear spring with a
  // displacement that never happened).
  return (x - a).dot(edge) / edge.squaredNorm();
}

std::pair<double, double> ContactSystem::start_gap_and_shear(const ContactPoint& p) const {
  const Point2& a = boundary_.position[at(p.master)];
  const Point2& b = boundary_.position[at(boundary_.next[at(p.master)])];
  const double l = (b - a).norm();
  // Normal gap (material on the left of a -> b; positive on the void side), and the shear
  // displacement of the slave point P1 relative to the anchor P0 along the edge (Shi eq.
  // 3.21).
  const double gap = (p.slave - a).dot(perp(b - a)) / l - p.offset - p.shift;
  const Point2 anchor = a + p.anchor * (b - a);
  return {gap, (p.slave - anchor).dot((b - a) / l)};
}

const ElementShape& ContactSystem::shape(int element) const {
  NMM_ASSERT(element >= 0 && at(element) < shape_of_element_.size() &&
                 shape_of_element_[at(element)] >= 0,
             "no shape built for this element in begin_step()");
  return shapes_[at(shape_of_element_[at(element)])];
}

void ContactSystem::kinematics(const Model& model,
                               const ContactPoint& p,
                               Kinematics& k,
                               KinematicsWork& work) const {
  const int slave_edge = p.slave_edge;
  const int master = p.master;
  const Point2& slave = p.slave;
  const int slave_element = edge_element_[at(slave_edge)];
  const int master_element = edge_element_[at(master)];
  const Point2& a = boundary_.position[at(master)];
  const Point2& b = boundary_.position[at(boundary_.next[at(master)])];
  const double l = (b - a).norm();
  PointTerms terms{.slave_dofs = model.element_dofs(slave_element),
                   .master_dofs = model.element_dofs(master_element),
                   .slave_shape = shape(slave_element),
                   .master_shape = shape(master_element),
                   .slave = slave,
                   .slave_a = boundary_.position[at(slave_edge)],
                   .slave_b = boundary_.position[at(boundary_.next[at(slave_edge)])],
                   .a = a,
                   .b = b,
                   .tangent = (b - a) / l,
                   .normal = perp(b - a) / l};
  const Point2& normal = terms.normal;
  const Point2& tangent = terms.tangent;
  // The terms T_element(x)^T c of the gap (hn) and of the shear (hs), on the slave's unknowns
  // (x on the slave edge's line) or the master's (x on the master edge's line).
  // Normal gap (material on the left of a -> b; positive on the void side):
  // g = cross(P1 - A, B - A) / l, linearised: u1 . perp(B - A) + uA . perp(P1 - B)
  // - uB . perp(P1 - A), all over l (Shi eq. 3.12 with our orientation).
  const auto [gap0, shear0] = start_gap_and_shear(p);
  k.g0 = gap0;
  std::array<Term, 5>& master_normal = terms.master_normal;
  std::size_t& n_master_normal = terms.n_master_normal;
  master_normal[n_master_normal++] = {a, perp(slave - b) / l};
  master_normal[n_master_normal++] = {b, Point2(-perp(slave - a) / l)};
  if (model.order >= 1 && terms.master_shape.nmm() != nullptr) {
    // The master terms above move the foot of the slave point, A + t (B - A), with the
    // straight line through the moved ends A and B: exact for a straight edge (order 0, DDA,
    // VEM). An order-1 edge bends (its displacement is quadratic along it); the foot moves
    // with the master's own field there: n . (T(foot) - (1 - t) T(A) - t T(B)) d less gap.
    const double foot = (slave - a).dot(b - a) / (l * l);
    master_normal[n_master_normal++] = {a + foot * (b - a), Point2(-normal)};
    master_normal[n_master_normal++] = {a, (1.0 - foot) * normal};
    master_normal[n_master_normal++] = {b, foot * normal};
  }
  // Shear displacement of P1 relative to the anchor P0 along the edge (Shi eq. 3.21).
  const Point2 anchor = a + p.anchor * (b - a);
  k.s0 = shear0;
  terms.master_shear = {anchor, Point2(-tangent)};
  k.dofs.clear();
  // The unknowns the point's terms involve, each at the position of its first use: the
  // slave element's first (all of an NMM element's or a DDA block's, a VEM block's slave
  // edge's two vertices), then the master's that the slave does not have. They depend on
  // the point's edges only, not on where it sits along them: the step's sparsity pattern
  // and plans are made with them at its start (point_dofs()).
  //
  // Two elements whose unknowns are apart (two blocks; NMM elements on either side of a
  // joint, mostly): the master's follow the slave's, in the order of the columns of their
  // interpolations, which are those of the edge for every point on its line. An element's
  // own unknowns are distinct. The same sums in the same order as kinematics_shared() (from a
  // zero, as there), without looking up any unknown, which is most of their cost.
  const auto [slave_min, slave_max] = std::ranges::minmax(terms.slave_dofs);
  const auto [master_min, master_max] = std::ranges::minmax(terms.master_dofs);
  if (slave_max < master_min || master_max < slave_min)
    kinematics_apart(terms, k, work);
  else
    kinematics_shared(terms, k, work);
}

void ContactSystem::kinematics_apart(const PointTerms& terms, Kinematics& k, KinematicsWork& work) {
  const auto& [slave_dofs, master_dofs, slave_shape, master_shape, slave, slave_a, slave_b, a, b,
               tangent, normal, master_normal, n_master_normal, master_shear] = terms;
  PointInterpolation& t = work.t;
  std::vector<int>& columns = work.columns;
  slave_shape.interpolation_on_edge(slave, slave_a, slave_b, t, columns);
  const auto ns = static_cast<Eigen::Index>(columns.size());
  for (const int column : columns)
    k.dofs.push_back(slave_dofs[at(column)]);
  std::vector<int>& master_columns = work.master_columns;
  // The columns of the master's interpolation, at the first master term's point.
  master_shape.interpolation_on_edge(master_normal[0].x, a, b, work.t_master, master_columns);
  const auto nm = static_cast<Eigen::Index>(master_columns.size());
  for (const int column : master_columns)
    k.dofs.push_back(master_dofs[at(column)]);
  k.hn.resize(ns + nm);
  k.hs.resize(ns + nm);
  for (Eigen::Index j = 0; j < ns; ++j) {
    k.hn(j) = 0.0 + (t(0, j) * normal.x() + t(1, j) * normal.y());
    k.hs(j) = 0.0 + (t(0, j) * tangent.x() + t(1, j) * tangent.y());
  }
  auto add_master = [&](Eigen::Ref<Eigen::VectorXd> h, const Term& term, bool first) {
    if (!first)
      master_shape.interpolation_on_edge(term.x, a, b, work.t_master, columns);
    NMM_ASSERT(first || columns == master_columns,
               "every point on an edge's line has the edge's columns");
    const PointInterpolation& tm = work.t_master;
    for (Eigen::Index j = 0; j < nm; ++j)
      h(j) += tm(0, j) * term.c.x() + tm(1, j) * term.c.y();
  };
  k.hn.tail(nm).setZero();
  k.hs.tail(nm).setZero();
  for (std::size_t q = 0; q < n_master_normal; ++q)
    add_master(k.hn.tail(nm), master_normal[q], q == 0);
  add_master(k.hs.tail(nm), master_shear, false);
}

void ContactSystem::kinematics_shared(const PointTerms& terms,
                                      Kinematics& k,
                                      KinematicsWork& work) {
  const auto& [slave_dofs, master_dofs, slave_shape, master_shape, slave, slave_a, slave_b, a, b,
               tangent, normal, master_normal, n_master_normal, master_shear] = terms;
  PointInterpolation& t = work.t;
  std::vector<int>& columns = work.columns;
  // Elements that share unknowns: each unknown is looked up where it is first used: local[c] for
  // the slave's column c, local[slave size + c] for the master's (-1: not used yet).
  const std::size_t bound = slave_dofs.size() + master_dofs.size();
  std::vector<double>& hn = work.hn;
  std::vector<double>& hs = work.hs;
  hn.assign(bound, 0.0);
  hs.assign(bound, 0.0);
  std::vector<Eigen::Index>& local = work.local;
  local.assign(bound, -1);
  // Adds T_element(x)^T c to hn (or hs if @p shear), on the slave's unknowns or the master's.
  auto add = [&](bool shear, bool on_master, const Term& term) {
    if (on_master)
      master_shape.interpolation_on_edge(term.x, a, b, t, columns);
    else
      slave_shape.interpolation_on_edge(term.x, slave_a, slave_b, t, columns);
    const std::span<const int> dofs = on_master ? master_dofs : slave_dofs;
    const std::size_t offset = on_master ? slave_dofs.size() : 0;
    std::vector<double>& h = shear ? hs : hn;
    for (std::size_t j = 0; j < columns.size(); ++j) {
      const std::size_t column = at(columns[j]);
      NMM_ASSERT(column < dofs.size(), "an element's interpolation has a column per unknown");
      Eigen::Index& position = local[offset + column];
      if (position < 0) { // an unknown the other element may have used already
        const auto found = std::find(k.dofs.begin(), k.dofs.end(), dofs[column]);
        position = found - k.dofs.begin();
        if (found == k.dofs.end())
          k.dofs.push_back(dofs[column]);
      }
      const auto col = static_cast<Eigen::Index>(j);
      h[static_cast<std::size_t>(position)] += t(0, col) * term.c.x() + t(1, col) * term.c.y();
    }
  };
  add(false, false, {slave, normal});
  for (std::size_t q = 0; q < n_master_normal; ++q)
    add(false, true, master_normal[q]);
  add(true, false, {slave, tangent});
  add(true, true, master_shear);
  // Cut to the unknowns used (fewer than bound on a VEM block's edge, or where the elements
  // share unknowns).
  const auto n = static_cast<Eigen::Index>(k.dofs.size());
  k.hn = Eigen::Map<const Eigen::VectorXd>(hn.data(), n);
  k.hs = Eigen::Map<const Eigen::VectorXd>(hs.data(), n);
}

const ContactSystem::Kinematics& ContactSystem::cached_kinematics(const Model& model,
                                                                  const ContactPoint& p,
                                                                  std::size_t slot) const {
  return cached_kinematics(model, p, slot, work_);
}

const ContactSystem::Kinematics& ContactSystem::cached_kinematics(const Model& model,
                                                                  const ContactPoint& p,
                                                                  std::size_t slot,
                                                                  KinematicsWork& work) const {
  NMM_ASSERT(slot < kinematics_cache_.size(), "a kinematics slot of this step");
  CachedKinematics& c = kinematics_cache_[slot];
  if (c.stamp != kinematics_stamp_ || c.slave_edge != p.slave_edge || c.master != p.master ||
      c.slave != p.slave || c.anchor != p.anchor || c.offset != p.offset || c.shift != p.shift) {
    kinematics(model, p, c.kinematics, work);
    c.stamp = kinematics_stamp_;
    c.slave_edge = p.slave_edge;
    c.master = p.master;
    c.slave = p.slave;
    c.anchor = p.anchor;
    c.offset = p.offset;
    c.shift = p.shift;
  }
  return c.kinematics;
}

// Each slot is written by the one chunk its point or group is in, each chunk with its own
// workspace: the kinematics are what the calls one by one compute, on any number of threads.
// At 10,004 DDA blocks they are a tenth of a step.
void ContactSystem::prepare_kinematics(const Model& model) const {
  works_.resize(static_cast<std::size_t>(worker_threads()));
  const std::size_t min_chunk = options_.parallel_min_chunk;
  parallel_for(points_.size(), min_chunk, [&](std::size_t first, std::size_t last, int chunk) {
    for (std::size_t i = first; i < last; ++i)
      static_cast<void>(cached_kinematics(model, points_[i], i, works_[at(chunk)]));
  });
  parallel_for(groups_.size(), min_chunk, [&](std::size_t first, std::size_t last, int chunk) {
    for (std::size_t k = first; k < last; ++k) {
      const Group& g = groups_[k];
      if (!g.edge)
        continue;
      const std::vector<std::pair<double, double>> shifts = shifts_of(g);
      for (int sample = 0; sample < 3; ++sample) {
        if (sample != 1 || gauss_ == 3)
          static_cast<void>(sample_kinematics(model, g, sample, shifts, works_[at(chunk)]));
      }
    }
  });
}

const ContactSystem::Kinematics&
ContactSystem::sample_kinematics(const Model& model,
                                 const Group& g,
                                 int sample,
                                 const std::vector<std::pair<double, double>>& shifts,
                                 KinematicsWork& work) const {
  const double u = sample == 0 ? g.lo : sample == 1 ? 0.5 * (g.lo + g.hi) : g.hi;
  ContactPoint p = points_[at(g.first)];
  const Point2& a = boundary_.position[at(p.slave_edge)];
  const Point2& d = boundary_.position[at(boundary_.next[at(p.slave_edge)])];
  p.slave = a + u * (d - a);
  p.anchor = 0.0; // the gap does not depend on it: one slot for the whole step
  p.shift = shifts.empty() ? 0.0 : offset_at(shifts, u);
  const auto group = static_cast<std::size_t>(&g - groups_.data());
  return cached_kinematics(model, p, points_.size() + 3 * group + at(sample), work);
}

double ContactSystem::gap_at(const Model& model,
                             const Group& g,
                             int sample,
                             const std::vector<std::pair<double, double>>& shifts,
                             const Eigen::VectorXd& raw) const {
  return sample_kinematics(model, g, sample, shifts, work_).gap(raw);
}

std::vector<std::pair<double, double>> ContactSystem::shifts_of(const Group& g) const {
  const auto first = points_.begin() + g.first;
  const auto last = first + g.count;
  std::vector<std::pair<double, double>> shifts;
  if (std::any_of(first, last, [](const ContactPoint& p) { return p.shift != 0.0; })) {
    for (auto p = first; p != last; ++p)
      shifts.emplace_back(p->u, p->shift);
  }
  return shifts;
}

std::vector<int> ContactSystem::point_dofs(const Model& model, int i) const {
  std::vector<int> dofs;
  append_point_dofs(model, i, dofs);
  return dofs;
}

void ContactSystem::append_point_dofs(const Model& model, int i, std::vector<int>& out) const {
  const std::vector<int>& dofs = cached_kinematics(model, points_[at(i)], at(i)).dofs;
  out.insert(out.end(), dofs.begin(), dofs.end());
}

} // namespace nmm
