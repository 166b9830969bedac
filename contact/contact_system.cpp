// SPDX-License-Identifier: MIT
// contact/contact_system.cpp — ContactSystem: the contacts of a step made from the
// detection's candidates with their states at its start (begin_step()), the bonds of the
// interfaces that have yielded by its end, and what the contacts are now for output.
#include "contact/contact_system.hpp"

#include "contact/detail/contact_support.hpp"
#include "contact/key_set.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <sstream>

namespace nmm {

using detail::at;
using detail::closed;
using detail::GapProfile;
using detail::offset_at;
using detail::perp;

namespace {

/// Where the slave material point of @p p is in the boundary @p now.
Point2 point_now(const ContactBoundary& now, const ContactPoint& p) {
  if (!is_edge_pair(p.key))
    return now.position[at(p.slave_edge)];
  return (1.0 - p.u) * now.position[at(p.slave_edge)] +
         p.u * now.position[at(now.next[at(p.slave_edge)])];
}

} // namespace

ContactSystem::ContactSystem(ContactOptions options,
                             std::vector<std::vector<JointStrength>> strength_of_edge,
                             std::vector<std::vector<bool>> bonded_edge)
    : options_(options), law_(std::make_shared<const MohrCoulombJoint>(std::move(strength_of_edge),
                                                                       std::move(bonded_edge))) {
  NMM_ASSERT(options_.penalty > 0.0 && options_.spring_length > 0.0,
             "contact springs need stiffness");
}

bool ContactSystem::can_touch(const Model& model) {
  if (model.blocks.size() > 1)
    return true;
  for (const BoundaryLoop& loop : model.loops) {
    for (const BoundaryEdge& edge : loop.edges) {
      if (edge.joint >= 0)
        return true;
    }
  }
  return false;
}

ContactBoundary contact_boundary(const Model& model) {
  ContactBoundary boundary;
  for (std::size_t l = 0; l < model.loops.size(); ++l) {
    const BoundaryLoop& loop = model.loops[l];
    const int base = boundary.n_vertices();
    const int n = loop.n_vertices();
    for (int k = 0; k < n; ++k) {
      boundary.position.push_back(loop.vertices[at(k)]);
      boundary.next.push_back(base + (k + 1) % n);
      boundary.previous.push_back(base + (k + n - 1) % n);
      boundary.block.push_back(loop.block);
    }
  }
  // Block areas as meshed: the choice of master edges never changes with the deformation
  // (contact keys stay the same).
  for (const Block& block : model.blocks)
    boundary.block_area.push_back(block.area);
  return boundary;
}

void ContactSystem::begin_step(const Model& model, double max_step_displacement) {
  coupled_friction_ = false;
  set_up_boundary(model);
  DetectionOptions detection = options_.detection;
  detection.distance = 2.0 * max_step_displacement;
  detection.penetration = 0.1 * detection.distance;
  held_open_penetration_ = 1e-3 * max_step_displacement;
  // A body at rest moves by about a unit in the last place of the coordinates in a step, and
  // the gaps and shear offsets computed from them carry as much: a decision on less would
  // be a coin toss.
  rounding_ = rounding_length(boundary_);
  // In the order of their keys, not of the hash table: which of two carried contacts a
  // transfer finds first must not depend on the table's history (a restarted run has
  // another), or a restart would not continue the run exactly.
  std::vector<std::uint64_t> keep = carried_keys_;
  std::sort(keep.begin(), keep.end());
  const std::vector<ContactCandidate> candidates =
      detect_contacts(boundary_, detection, keep, &counters_.detection);

  const CarriedByEdge carried = carried_by_edge(keep);
  // Angle contacts already made, by (vertex, entrance line): two candidates can end on the
  // same pair (an angle-to-edge contact and an angle-to-angle one whose line is that edge),
  // and one spring is all the pair may have.
  KeySet angle_pairs(candidates.size());

  points_.clear();
  groups_.clear();
  gauss_ = model.order == 0 ? 2 : 3;
  std::vector<double> g0; // per candidate: its gap at the start of the step (kept storage)
  std::vector<std::pair<double, double>> offsets; // per candidate: a carried lock's anchors
  for (const ContactCandidate& c : candidates)
    add_contact(c, carried, angle_pairs, g0, offsets);
  counters_.points += static_cast<long>(points_.size());
  last_changed_ = 0;
  holds_ = {};
  save(start_);
  has_converged_ = false;
  // Every slot's kinematics are of the last step: a new stamp (no pass over 20 MB of slots
  // at 10,004 blocks).
  ++kinematics_stamp_;
  kinematics_cache_.resize(points_.size() + 3 * groups_.size());
  set_up_shapes(model);
}

void ContactSystem::set_up_boundary(const Model& model) {
  // The boundary at the start of the step, and what each edge carries.
  boundary_ = contact_boundary(model);
  edge_element_.clear();
  edge_strength_.clear();
  edge_bonded_.clear();
  edge_joint_.clear();
  edge_material_.clear();
  edge_excavated_.clear();
  materials_ = model.materials;
  for (std::size_t l = 0; l < model.loops.size(); ++l) {
    const BoundaryLoop& loop = model.loops[l];
    for (int k = 0; k < loop.n_vertices(); ++k) {
      const BoundaryEdge& edge = loop.edges[at(k)];
      edge_element_.push_back(edge.element);
      edge_strength_.push_back(law_->surface(l, at(k)));
      edge_bonded_.push_back(law_->is_bonded(l, at(k)) ? 1 : 0);
      edge_joint_.push_back(edge.joint);
      edge_material_.push_back(edge.element >= 0 ? model.elements[at(edge.element)].material : -1);
      edge_excavated_.push_back(
          edge.element >= 0 && model.elements[at(edge.element)].excavated ? 1 : 0);
    }
  }
}

Eigen::Vector3d ContactSystem::initial_stress_at(int edge, const Point2& x) const {
  const int material = edge_material_[at(edge)];
  return material < 0 ? Eigen::Vector3d::Zero() : materials_[at(material)].initial_stress_at(x.y());
}

Point2
ContactSystem::in_situ_traction(int slave, int slave_other, int master, const Point2& x) const {
  // The initial stress sigma0 is in equilibrium inside each body; across a joint the two
  // faces press on each other with its traction sigma0 n. Each body's initial-stress load
  // -integral B^T sigma0 (Shi 1997, eq. 2.10) is, by the divergence theorem, that traction on
  // its boundary pushing outwards; the joint's springs carry it from the start, or the
  // bodies expand into each other until their penetration does (docs/formulation.md,
  // "In-situ stress"). The two sides' stresses at the contact point x, averaged (the same
  // where one rock is cut); a field growing with depth ([in_situ]) is taken at x's height.
  const int joint = edge_joint_[at(master)];
  if (joint < 0 || edge_joint_[at(slave)] != joint || edge_joint_[at(slave_other)] != joint)
    return Point2::Zero();
  const Eigen::Vector3d s = 0.5 * (initial_stress_at(slave, x) + initial_stress_at(master, x));
  if (s.isZero())
    return Point2::Zero();
  const Point2& a = boundary_.position[at(master)];
  const Point2 tangent = (boundary_.position[at(boundary_.next[at(master)])] - a).normalized();
  const Point2 normal = perp(tangent); // out of the master, towards the slave
  const Point2 traction(s(0) * normal.x() + s(2) * normal.y(),
                        s(2) * normal.x() + s(1) * normal.y()); // sigma0 n
  // On the slave (outward normal -n) the master presses with -sigma0 n: its normal part is
  // -n.sigma0 n (compressive positive); its shear -t.sigma0 n is what the shear spring
  // pushes the slave with, -p s0 along t (ContactSystem::contribution()): a stretch s0 of
  // t.sigma0 n over the spring's stiffness per unit length.
  return {-normal.dot(traction), tangent.dot(traction)};
}

void ContactSystem::choose_entrance_line(const ContactCandidate& c, ContactPoint& p) const {
  // Two convex angles (Shi 3.2 [1]): they penetrate only when both entrance lines are
  // passed, so the spring goes on the line with the smaller passing distance: the larger
  // signed distance at the start of the step (outside positive). That is the line still
  // to be passed, or, when both are, the shortest way out. The other line can have been
  // passed long ago: a block tip that slid past a corner leaves the corner far behind
  // the tip's other face, and a spring there pushed the corner out through the whole
  // block (1e3 m/s in one step; test Incline.SharpTipSlidesPastTheCorner...). Chosen
  // once here, so that the springs, the anchor and its transfer all refer to one edge.
  const auto distance = [&](int vertex, int edge) {
    const Point2& a = boundary_.position[at(edge)];
    const Point2& b = boundary_.position[at(boundary_.next[at(edge)])];
    return (boundary_.position[at(vertex)] - a).dot(perp(b - a)) / (b - a).norm();
  };
  if (distance(c.alternative_slave, c.alternative_master) > distance(c.slave, c.master)) {
    p.slave_edge = c.alternative_slave;
    p.master = c.alternative_master;
  }
}

void ContactSystem::add_contact(const ContactCandidate& c,
                                const CarriedByEdge& carried,
                                KeySet& angle_pairs,
                                std::vector<double>& g0,
                                std::vector<std::pair<double, double>>& offsets) {
  // The corner that ends a face on a joint (ContactCandidate::end_face) while that face is
  // bonded: the face's pair has springs all along its overlap up to the corner, and
  // represents that part of the joint; a point spring there would be a second, concentrated
  // one on the same place, representing no length (docs/formulation.md, "Joint strength").
  if (c.kind != ContactKind::edge_edge && c.end_face >= 0 && bonded_face(c.end_face, c.end_beyond))
    return;
  // Excavated material touches nothing: no contact on its edges (an angle's two edges).
  const auto gone = [&](int edge) { return edge >= 0 && edge_excavated_[at(edge)] != 0; };
  if (gone(c.slave) || gone(c.master) || gone(c.alternative_slave) || gone(c.alternative_master) ||
      (c.kind != ContactKind::edge_edge && gone(boundary_.previous[at(c.slave)])))
    return;
  Group g;
  g.key = c.key();
  g.edge = c.kind == ContactKind::edge_edge;
  g.first = n_points();
  ContactPoint p;
  p.key = g.key;
  p.slave_edge = c.slave;
  p.master = c.master;
  if (!g.edge && c.alternative_master >= 0)
    choose_entrance_line(c, p);
  if (!g.edge && !angle_pairs.insert(static_cast<std::uint64_t>(at(p.slave_edge)) << 32U |
                                     static_cast<std::uint64_t>(at(p.master))))
    return;
  g0.clear(); // gap at the start of the step: at the point, or along the overlap
  if (!g.edge)
    add_angle_point(c, g, p, g0);
  else if (!add_edge_points(c, g, p, g0))
    return;
  start_contact(g, p, carried, g0, offsets);
  groups_.push_back(g);
}

void ContactSystem::add_angle_point(const ContactCandidate& c,
                                    Group& g,
                                    ContactPoint& p,
                                    std::vector<double>& g0) {
  const Point2& ma = boundary_.position[at(p.master)];
  const Point2& mb = boundary_.position[at(boundary_.next[at(p.master)])];
  const Point2 normal = perp(mb - ma).normalized();
  const int v = p.slave_edge;
  p.slave = boundary_.position[at(v)];
  // Half of the vertex's two edges (Shi), or none at the end of an edge-to-edge contact
  // that represents that face already (docs/formulation.md, "Joint strength").
  p.length = c.end_face >= 0
                 ? 0.0
                 : 0.5 * ((boundary_.position[at(boundary_.next[at(v)])] - p.slave).norm() +
                          (boundary_.position[at(boundary_.previous[at(v)])] - p.slave).norm());
  p.stiffness = options_.penalty;
  p.strength = law_->contact_strength(
      law_->contact_strength(edge_strength_[at(v)], edge_strength_[at(boundary_.previous[at(v)])]),
      edge_strength_[at(p.master)]);
  // A corner at the end of a bonded face belongs to that face's bond (it holds no length
  // of its own, so no strength either: its spring yields with friction alone).
  p.bonded = c.end_face >= 0
                 ? edge_bonded_[at(c.end_face)] != 0 && edge_bonded_[at(c.end_beyond)] != 0
                 : edge_bonded_[at(v)] != 0 && edge_bonded_[at(p.master)] != 0;
  // Across a joint under initial stress, the springs pre-compressed and pre-sheared to carry
  // the in-situ traction on the point's length (none for a corner of no length).
  const Point2 traction = in_situ_traction(v, boundary_.previous[at(v)], p.master, p.slave);
  // A tensile initial stress pre-loads only a bond (an unbonded joint carries no tension).
  p.shift = p.bonded ? traction.x() * p.length / p.stiffness
                     : std::max(0.0, traction.x() * p.length / p.stiffness);
  g.in_situ_shear = traction.y() * p.length / p.stiffness;
  g.count = 1;
  g.in_situ_shift = {p.shift, p.shift};
  points_.push_back(p);
  g0.push_back((p.slave - ma).dot(normal));
}

bool ContactSystem::add_edge_points(const ContactCandidate& c,
                                    Group& g,
                                    ContactPoint& p,
                                    std::vector<double>& g0) {
  const Point2& ma = boundary_.position[at(p.master)];
  const Point2& mb = boundary_.position[at(boundary_.next[at(p.master)])];
  const Point2 tangent = (mb - ma).normalized();
  const Point2 normal = perp(mb - ma).normalized();
  // The overlap of the slave edge's projection on the master, as slave parameters.
  const Point2& a = boundary_.position[at(c.slave)];
  const Point2& d = boundary_.position[at(boundary_.next[at(c.slave)])];
  const double length = (mb - ma).norm();
  g.t_first = (a - ma).dot(tangent);
  g.t_next = (d - ma).dot(tangent);
  const double t_lo = std::max(0.0, std::min(g.t_first, g.t_next));
  const double t_hi = std::min(length, std::max(g.t_first, g.t_next));
  if (t_hi - t_lo <= touching_end * length) // as in the detection: an end that only touches
    return false;
  const double u1 = (t_lo - g.t_first) / (g.t_next - g.t_first);
  const double u2 = (t_hi - g.t_first) / (g.t_next - g.t_first);
  g.lo = std::clamp(std::min(u1, u2), 0.0, 1.0);
  g.hi = std::clamp(std::max(u1, u2), 0.0, 1.0);
  p.strength = law_->contact_strength(edge_strength_[at(c.slave)], edge_strength_[at(c.master)]);
  p.bonded = edge_bonded_[at(c.slave)] != 0 && edge_bonded_[at(c.master)] != 0;
  p.shear_ratio = edge_shear_ratio(p.strength);
  // The pre-compression of the in-situ traction at the overlap's ends, for the test whether
  // the pair touches; each point's own is set where place() puts it (start_contact()).
  for (int end = 0; end < 2; ++end) {
    ContactPoint at_end = p;
    at_end.slave = a + (end == 0 ? g.lo : g.hi) * (d - a);
    g.in_situ_shift[at(end)] = edge_preload(at_end, p.bonded).first;
  }
  g.count = gauss_;
  for (int q = 0; q < gauss_; ++q) {
    points_.push_back(p);
  }
  for (const double u : {g.lo, g.hi})
    g0.push_back((a + u * (d - a) - ma).dot(normal));
  return true;
}

std::pair<double, double> ContactSystem::edge_preload(const ContactPoint& p, bool bonded) const {
  // The pre-compression and pre-shear of the in-situ traction at the point (as for an angle
  // point): the springs' stiffness per unit length is edge_stiffness(), the same at every
  // point, so each Gauss point carries the traction at its own place and the pair the
  // traction's integral along it (exact for a field linear in depth).
  const Point2 traction = in_situ_traction(p.slave_edge, p.slave_edge, p.master, p.slave);
  const double compliance = p.strength.normal_stiffness > 0.0
                                ? 1.0 / p.strength.normal_stiffness
                                : options_.spring_length / options_.penalty;
  return {bonded ? traction.x() * compliance : std::max(0.0, traction.x() * compliance),
          traction.y() * compliance / p.shear_ratio};
}

void ContactSystem::start_contact(Group& g,
                                  const ContactPoint& p,
                                  const CarriedByEdge& carried,
                                  const std::vector<double>& g0,
                                  std::vector<std::pair<double, double>>& offsets) {
  ContactPoint& lead = points_[at(g.first)];
  const bool preload_bonded = lead.bonded; // (the in-situ pre-load as the pair was made)
  if (broken_.count(g.key) != 0 || broken_.count(interface_key(p.slave_edge, p.master)) != 0) {
    for (int q = 0; q < g.count; ++q)
      points_[at(g.first + q)].bonded = false;
  }
  // The state at the start of the step (Shi 3.3): carried, taken over from the contact
  // the slave moved on from, or new. An intact joint, and a contact already touching,
  // start locked (not open for one free-flight iteration: that would take a whole step's
  // worth of penetration first). A contact takes over another pair's closed mode only
  // where it touches: a slave that moved on presses on its new master, but a pair that
  // merely lies beside a closed one (the next piece of a sliding block's underside, with a
  // gap) is no continuation of it. Closed from the start it pulled, opened in the first
  // solve and was taken over again the next step: on examples/03 a refactorisation every
  // step at 40 E, and 96 step cuts in 200 steps at 100 E (2 now).
  bool same = false;
  const Carried* state = carried_state(carried, g.key, p.slave_edge, p.master, g.edge, &same);
  // Gaps as the springs see them: less an in-situ pre-compression (ContactPoint::shift; for
  // an edge pair at each end of its overlap).
  const double pre = g.in_situ_shift[0];
  const bool touching =
      g.edge ? std::min(g0[0] - g.in_situ_shift[0], g0[1] - g.in_situ_shift[1]) <= rounding_
             : g0.front() - pre <= rounding_;
  ContactMode mode = ContactMode::open;
  int sign = 0;
  double normal_force = 0.0;
  if (state != nullptr && (same || touching)) {
    mode = state->mode;
    sign = state->slide_sign;
    normal_force = same ? state->normal : 0.0;
  } else if (lead.bonded && opened_.count(g.key) != 0) {
    // A bond that ended the last step open, yielded in tension, starts open (pulling with
    // its strength): started locked with a new anchor, it would open again and lose the
    // shear its springs had taken, every step (a creep).
    mode = ContactMode::open;
  } else if (lead.bonded || touching) {
    mode = ContactMode::lock;
  }
  if (!g.edge) {
    // The springs' zero (ContactPoint::offset): a new contact's penetration; a carried one
    // keeps its own; one taken over from the slave's last edge keeps that one's unless it
    // now penetrates less.
    lead.offset = std::min(0.0, g0.front());
    if (same)
      lead.offset = state->offset;
    else if (state != nullptr)
      lead.offset = std::max(state->offset, lead.offset);
  }
  // A lock carried on the same pair keeps its anchors (material points of the master), as
  // shear offsets from where its slave points are now; otherwise it anchors where the slave
  // is now, on its own entrance line (not the candidate's: an angle-to-angle contact's
  // spring may be on the alternative line, and an anchor measured along the other edge put
  // millimetres of shear into the spring).
  offsets.clear();
  if (same) {
    const Point2& a = boundary_.position[at(p.slave_edge)];
    const Point2& d = boundary_.position[at(boundary_.next[at(p.slave_edge)])];
    for (const auto& [u, anchor] : anchors_of(*state)) {
      const Point2 slave = g.edge ? Point2(a + u * (d - a)) : a;
      offsets.emplace_back(u, anchor - projection(p.master, slave));
    }
  }
  // A new contact across a joint under initial stress anchors its shear springs the
  // in-situ pre-shear behind its slave points (Group::in_situ_shear), a carried one keeps
  // its anchors.
  const double master_length =
      (boundary_.position[at(boundary_.next[at(p.master)])] - boundary_.position[at(p.master)])
          .norm();
  const double pre_shear = same ? 0.0 : g.in_situ_shear / master_length;
  auto anchor_of = [&](double u, const Point2& slave) {
    return projection(p.master, slave) + (same ? offset_at(offsets, u) : -pre_shear);
  };
  if (g.edge) {
    // Springs where the edges press on each other; all along an intact joint.
    double from = g.lo;
    double to = g.hi;
    if (closed(mode) && !lead.bonded) {
      NMM_ASSERT(g0.size() == 2, "an edge pair's gaps at the ends of its overlap");
      const std::array<double, 2> pressed{g0[0] - g.in_situ_shift[0], g0[1] - g.in_situ_shift[1]};
      if (const OverlapPart part = GapProfile(g.lo, g.hi, pressed).negative(); part.found) {
        from = part.from;
        to = part.to;
      }
    }
    place(g, from, to, same ? &offsets : nullptr);
    // Each spring pre-compressed and (new) pre-sheared by the traction at its own place.
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& point = points_[at(g.first + q)];
      const auto [shift, shear] = edge_preload(point, preload_bonded);
      point.shift = shift;
      if (!same)
        point.anchor -= shear / master_length;
    }
  } else {
    lead.anchor = anchor_of(0.0, lead.slave);
  }
  const double total = group_stiffness(g);
  for (int q = 0; q < g.count; ++q) {
    ContactPoint& point = points_[at(g.first + q)];
    point.mode = mode;
    point.slide_sign = sign;
    point.flips = 0;
    point.slips = 0;
    point.normal_force = total > 0.0 ? normal_force * point.stiffness / total : 0.0;
    point.shear_force = 0.0;
    point.gap = 0.0;
  }
}

void ContactSystem::set_up_shapes(const Model& model) {
  shapes_.clear();
  shape_of_element_.assign(static_cast<std::size_t>(model.n_elements()), -1);
  for (const ContactPoint& p : points_) {
    for (const int edge : {p.slave_edge, p.master}) {
      int& index = shape_of_element_[at(edge_element_[at(edge)])];
      if (index < 0) {
        index = static_cast<int>(shapes_.size());
        shapes_.push_back(model.shape(edge_element_[at(edge)]));
      }
    }
  }
}

void ContactSystem::set_chatter_slides(bool slides) { chatter_slides_ = slides; }

void ContactSystem::set_hold_shear(bool hold) {
  hold_shear_ = hold;
  if (!hold)
    return;
  for (ContactPoint& p : points_) {
    if (p.mode == ContactMode::slide) {
      p.mode = ContactMode::lock;
      p.anchor = projection(p.master, p.slave);
    }
  }
  if (tie_)
    tie_touching();
}

void ContactSystem::tie_touching() {
  // A tensile strength beyond any force, finite so that a length of zero gives zero.
  constexpr double unlimited = 1e300;
  tie_capacity_.assign(points_.size(), -1.0); // (-1: not tied)
  std::vector<std::pair<double, double>> offsets;
  for (Group& g : groups_) {
    ContactPoint& lead = points_[at(g.first)];
    if (lead.mode == ContactMode::open || lead.length <= 0.0)
      continue;
    if (g.edge && (g.from != g.lo || g.to != g.hi)) {
      // Springs along the whole overlap, as on an intact joint, keeping the anchors' shear
      // offsets (an in-situ pre-shear among them).
      offsets.clear();
      for (int q = 0; q < g.count; ++q) {
        const ContactPoint& p = points_[at(g.first + q)];
        offsets.emplace_back(p.u, p.anchor - projection(p.master, p.slave));
      }
      place(g, g.lo, g.hi, &offsets);
    }
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& p = points_[at(g.first + q)];
      tie_capacity_[at(g.first + q)] = law_->bond_tension(p);
      p.bonded = true;
      p.strength.tensile_strength = unlimited;
    }
  }
}

std::string ContactSystem::untenable_tension(const Model& model) const {
  if (tie_capacity_.size() != points_.size())
    return {};
  // Net normal force and bond strength of the tied contacts between each pair of blocks.
  struct Pair {
    int a = -1;
    int b = -1;
    double normal = 0.0;
    double capacity = 0.0;
    double length = 0.0;
    Point2 where = Point2::Zero();
  };
  std::vector<Pair> pairs;
  const auto block_of = [&](int edge) { return model.elements[at(edge_element_[at(edge)])].block; };
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const ContactPoint& p = points_[i];
    if (tie_capacity_[i] < 0.0 || p.mode == ContactMode::open)
      continue;
    const int a = std::min(block_of(p.slave_edge), block_of(p.master));
    const int b = std::max(block_of(p.slave_edge), block_of(p.master));
    auto it = std::find_if(pairs.begin(), pairs.end(),
                           [&](const Pair& q) { return q.a == a && q.b == b; });
    if (it == pairs.end()) {
      pairs.push_back({a, b, 0.0, 0.0, 0.0, p.slave});
      it = pairs.end() - 1;
    }
    it->normal += p.normal_force;
    it->capacity += tie_capacity_[i];
    it->length += p.length;
  }
  const auto name = [&](int block) {
    for (const ModelElement& e : model.elements) {
      if (e.block == block)
        return "block " + std::to_string(block) + " (material \"" +
               model.materials[at(e.material)].name + "\")";
    }
    return "block " + std::to_string(block);
  };
  for (const Pair& q : pairs) {
    // Beyond the bonds by more than the rounding of the forces.
    if (-q.normal <= q.capacity * (1.0 + 1e-9) + 1e-12 * std::abs(q.normal))
      continue;
    std::ostringstream out;
    out.precision(4);
    out << name(q.b) << " and " << name(q.a) << " near " << point_text(q.where, 6)
        << " are held together by nothing but tension: their contacts would have to pull with "
        << -q.normal << " N, and their bond's tensile strength holds " << q.capacity
        << " N (tensile_strength times the " << q.length
        << " m in contact); a tensile_strength of at least " << -q.normal / q.length
        << " Pa on that joint, a support, or no initial_equilibrium lets it start";
    return out.str();
  }
  return {};
}

bool ContactSystem::bonded_face(int face, int other) const {
  if (edge_bonded_[at(face)] == 0 || edge_bonded_[at(other)] == 0 ||
      broken_.count(interface_key(face, other)) != 0)
    return false;
  for (const auto& [s, m] : {std::pair{face, other}, std::pair{other, face}}) {
    ContactCandidate pair;
    pair.kind = ContactKind::edge_edge;
    pair.slave = s;
    pair.master = m;
    if (broken_.count(pair.key()) != 0)
      return false;
  }
  return true;
}

std::uint64_t ContactSystem::interface_key(int slave, int master) const {
  const auto a = static_cast<std::uint64_t>(at(boundary_.block[at(slave)]));
  const auto b = static_cast<std::uint64_t>(at(boundary_.block[at(master)]));
  return std::uint64_t{1} << 63U | std::min(a, b) << 32U | std::max(a, b);
}

void ContactSystem::break_yielded_interfaces(const Model& model, const Eigen::VectorXd& raw) {
  // An interface whose bonded contacts all slide or pull open beyond their tensile strength
  // has yielded all along: no elastic part of it is left to take more load, and
  // Mohr-Coulomb's residual strength (friction) is all it keeps. Until then its sliding
  // contacts carry their cohesion and its open ones pull with their tensile strength
  // (plastic yield), so that the load they shed goes to the parts that still hold and the
  // joint holds up to its whole strength, c L + N tan(phi) in shear and T L in tension,
  // whatever its stress concentrations. A contact in slide mode whose step motion is within
  // the rounding does not move: it holds (friction at or above what acts on it, the mode it
  // is in keeps it there).
  // Most scenes have no bond at all: nothing to allocate or walk then (a step of 10,004
  // blocks has 60,000 contacts).
  opened_.clear();
  if (std::none_of(points_.begin(), points_.end(), [](const ContactPoint& p) { return p.bonded; }))
    return;
  KeySet holding(groups_.size());
  KeySet yielded(groups_.size());
  const auto unbond = [&](const Group& g, std::uint64_t key) {
    broken_[key] = true;
    ++counters_.bonds_broken;
    for (int q = 0; q < g.count; ++q)
      points_[at(g.first + q)].bonded = false;
  };
  for (const Group& g : groups_) {
    const ContactPoint& lead = points_[at(g.first)];
    if (!lead.bonded)
      continue;
    const std::uint64_t key = interface_key(lead.slave_edge, lead.master);
    if (lead.mode == ContactMode::open) {
      // Open at the end of the step: this part has yielded in tension where its springs would
      // pull beyond its tensile strength (not where the chatter rule holds it open within it).
      // It pulls with that strength (plastic yield; with none, with nothing) and keeps its
      // bond until its interface has yielded all along, and it starts the next step open.
      const std::span<const ContactPoint> part =
          std::span<const ContactPoint>(points_).subspan(at(g.first), at(g.count));
      if (!law_->yields_open(part))
        continue;
      yielded.insert(key);
      opened_[g.key] = true;
      continue;
    }
    bool holds = lead.mode == ContactMode::lock;
    if (lead.mode == ContactMode::slide) {
      double stiffness = 0.0;
      double motion = 0.0;
      for (int q = 0; q < g.count; ++q) {
        const ContactPoint& p = points_[at(g.first + q)];
        stiffness += p.stiffness;
        motion += p.stiffness * cached_kinematics(model, p, at(g.first + q)).tangential(raw);
      }
      holds = std::abs(motion) <= rounding_ * stiffness;
    }
    if (holds)
      holding.insert(key);
    else
      yielded.insert(key);
  }
  for (const Group& g : groups_) {
    ContactPoint& lead = points_[at(g.first)];
    if (!lead.bonded)
      continue;
    const std::uint64_t key = interface_key(lead.slave_edge, lead.master);
    if (!holding.contains(key) && yielded.contains(key))
      unbond(g, key);
  }
}

int ContactSystem::n_closed() const {
  return static_cast<int>(std::count_if(points_.begin(), points_.end(),
                                        [](const ContactPoint& p) { return closed(p.mode); }));
}

int ContactSystem::n_sliding() const {
  return static_cast<int>(std::count_if(points_.begin(), points_.end(), [](const ContactPoint& p) {
    return p.mode == ContactMode::slide;
  }));
}

std::vector<ContactSystem::Place> ContactSystem::current_places(const Model& model) const {
  if (points_.empty())
    return {}; // (before the first step too, when begin_step() has numbered nothing yet)
  // The boundary numbered as begin_step() numbers it, at its current place.
  const ContactBoundary now = contact_boundary(model);
  const std::vector<Point2>& position = now.position;
  const std::vector<int>& next = now.next;
  NMM_ASSERT(position.size() == boundary_.position.size(), "the boundary changed its vertices");
  std::vector<Place> result;
  result.reserve(points_.size());
  for (const ContactPoint& p : points_) {
    Place place;
    place.position = point_now(now, p);
    place.normal = perp(position[at(next[at(p.master)])] - position[at(p.master)]).normalized();
    result.push_back(place);
  }
  return result;
}

std::vector<ContactSystem::PointForce>
ContactSystem::forces_of_excavated(const Model& model) const {
  std::vector<PointForce> result;
  if (points_.empty())
    return result;
  const ContactBoundary now = contact_boundary(model);
  NMM_ASSERT(now.position.size() == boundary_.position.size(), "the boundary changed its vertices");
  const auto excavated = [&](int edge) {
    const int element = edge_element_[at(edge)];
    return element >= 0 && model.elements[at(element)].excavated;
  };
  for (const ContactPoint& p : points_) {
    const bool slave_gone = excavated(p.slave_edge);
    if (slave_gone == excavated(p.master) || (p.normal_force == 0.0 && p.shear_force == 0.0))
      continue;
    const Point2 slave = point_now(now, p);
    const Point2& a = now.position[at(p.master)];
    const Point2 edge = now.position[at(now.next[at(p.master)])] - a;
    const Point2 tangent = edge.normalized();
    const Point2 normal = perp(tangent); // out of the master, towards the slave
    // The master presses the slave with N n and pulls it against the shear force, -S t;
    // the slave the master with the opposite (set_forces()).
    const Point2 on_slave = p.normal_force * normal - p.shear_force * tangent;
    if (!slave_gone) {
      result.push_back({{edge_element_[at(p.slave_edge)], slave}, on_slave});
      continue;
    }
    // On the master: at the slave point's projection on its edge, kept on the edge.
    const double s = std::clamp((slave - a).dot(edge) / edge.squaredNorm(), 0.0, 1.0);
    result.push_back({{edge_element_[at(p.master)], a + s * edge}, -on_slave});
  }
  return result;
}

std::string ContactSystem::describe(int i) const {
  if (points_.empty())
    return "no contact";
  const ContactPoint& p = points_[at(std::clamp(i, 0, n_points() - 1))];
  const Point2& a = boundary_.position[at(p.master)];
  const Point2& b = boundary_.position[at(boundary_.next[at(p.master)])];
  return "contact of " + point_text(p.slave, 6) + " against the edge " + point_text(a, 6) + "-" +
         point_text(b, 6);
}

} // namespace nmm
