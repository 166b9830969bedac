// SPDX-License-Identifier: MIT
// contact/contact_system.cpp — ContactSystem: the contacts of a step from the detection's
// candidates, the open-close mode decisions, transfer of closed contacts to the next step.
#include "contact/contact_system.hpp"

#include "contact/detail/contact_support.hpp"
#include "contact/key_set.hpp"
#include "mesh/error.hpp"
#include "mesh/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <span>
#include <sstream>

namespace nmm {

using detail::at;
using detail::closed;
using detail::GapProfile;
using detail::offset_at;
using detail::perp;

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
  // The boundary at the start of the step, and what each edge carries.
  boundary_ = contact_boundary(model);
  edge_element_.clear();
  edge_strength_.clear();
  edge_bonded_.clear();
  for (std::size_t l = 0; l < model.loops.size(); ++l) {
    const BoundaryLoop& loop = model.loops[l];
    for (int k = 0; k < loop.n_vertices(); ++k) {
      edge_element_.push_back(loop.edges[at(k)].element);
      edge_strength_.push_back(law_->surface(l, at(k)));
      edge_bonded_.push_back(law_->is_bonded(l, at(k)) ? 1 : 0);
    }
  }
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
  for (const ContactCandidate& c : candidates) {
    Group g;
    g.key = c.key();
    g.edge = c.kind == ContactKind::edge_edge;
    g.first = n_points();
    ContactPoint p;
    p.key = g.key;
    p.slave_edge = c.slave;
    p.master = c.master;
    if (!g.edge && c.alternative_master >= 0) {
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
    if (!g.edge && !angle_pairs.insert(static_cast<std::uint64_t>(at(p.slave_edge)) << 32U |
                                       static_cast<std::uint64_t>(at(p.master))))
      continue;
    const Point2& ma = boundary_.position[at(p.master)];
    const Point2& mb = boundary_.position[at(boundary_.next[at(p.master)])];
    const Point2 tangent = (mb - ma).normalized();
    const Point2 normal = perp(mb - ma).normalized();
    g0.clear(); // gap at the start of the step: at the point, or along the overlap
    if (!g.edge) {
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
          law_->contact_strength(edge_strength_[at(v)],
                                 edge_strength_[at(boundary_.previous[at(v)])]),
          edge_strength_[at(p.master)]);
      // A corner at the end of a bonded face belongs to that face's bond (it holds no length
      // of its own, so no strength either: its spring yields with friction alone).
      p.bonded = c.end_face >= 0
                     ? edge_bonded_[at(c.end_face)] != 0 && edge_bonded_[at(c.end_beyond)] != 0
                     : edge_bonded_[at(v)] != 0 && edge_bonded_[at(p.master)] != 0;
      g.count = 1;
      points_.push_back(p);
      g0.push_back((p.slave - ma).dot(normal));
    } else {
      // The overlap of the slave edge's projection on the master, as slave parameters.
      const Point2& a = boundary_.position[at(c.slave)];
      const Point2& d = boundary_.position[at(boundary_.next[at(c.slave)])];
      const double length = (mb - ma).norm();
      g.t_first = (a - ma).dot(tangent);
      g.t_next = (d - ma).dot(tangent);
      const double t_lo = std::max(0.0, std::min(g.t_first, g.t_next));
      const double t_hi = std::min(length, std::max(g.t_first, g.t_next));
      if (t_hi - t_lo <= touching_end * length) // as in the detection: an end that only touches
        continue;
      const double u1 = (t_lo - g.t_first) / (g.t_next - g.t_first);
      const double u2 = (t_hi - g.t_first) / (g.t_next - g.t_first);
      g.lo = std::clamp(std::min(u1, u2), 0.0, 1.0);
      g.hi = std::clamp(std::max(u1, u2), 0.0, 1.0);
      p.strength =
          law_->contact_strength(edge_strength_[at(c.slave)], edge_strength_[at(c.master)]);
      p.bonded = edge_bonded_[at(c.slave)] != 0 && edge_bonded_[at(c.master)] != 0;
      g.count = gauss_;
      for (int q = 0; q < gauss_; ++q) {
        points_.push_back(p);
      }
      for (const double u : {g.lo, g.hi})
        g0.push_back((a + u * (d - a) - ma).dot(normal));
    }
    ContactPoint& lead = points_[at(g.first)];
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
    const bool touching = *std::min_element(g0.begin(), g0.end()) <= rounding_;
    ContactMode mode = ContactMode::open;
    int sign = 0;
    double normal_force = 0.0;
    if (state != nullptr && (same || touching)) {
      mode = state->mode;
      sign = state->slide_sign;
      normal_force = same ? state->normal : 0.0;
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
    auto anchor_of = [&](double u, const Point2& slave) {
      return projection(p.master, slave) + (same ? offset_at(offsets, u) : 0.0);
    };
    if (g.edge) {
      // Springs where the edges press on each other; all along an intact joint.
      double from = g.lo;
      double to = g.hi;
      if (closed(mode) && !lead.bonded) {
        if (const OverlapPart part = GapProfile(g.lo, g.hi, g0).negative(); part.found) {
          from = part.from;
          to = part.to;
        }
      }
      place(g, from, to, same ? &offsets : nullptr);
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
    groups_.push_back(g);
  }
  counters_.points += static_cast<long>(points_.size());
  last_changed_ = 0;
  holds_ = {};
  save(start_);
  has_converged_ = false;
  // Every slot's kinematics are of the last step: a new stamp (no pass over 20 MB of slots
  // at 10,004 blocks).
  ++kinematics_stamp_;
  kinematics_cache_.resize(points_.size() + 3 * groups_.size());
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

void ContactSystem::set_dynamic(bool dynamic) { dynamic_ = dynamic; }

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
}

ModeUpdate ContactSystem::update_modes(const Model& model, const Eigen::VectorXd& raw) {
  ModeUpdate update;
  held_beyond_.clear();
  held_against_.clear();
  // Friction consistency is judged on the whole system, by the work of friction in the step:
  // the work of the change of the friction forces since they were applied against the work
  // of all friction. A contact carrying a few newtons may change by a large fraction without
  // any effect on the motion.
  double friction_change = 0.0;
  double friction_total = 0.0;
  struct Measure {
    double gap = 0.0;
    double shear = 0.0;
    double ds = 0.0;
  };
  std::vector<Measure> measure;
  std::vector<LiftOff> lift_off;
  double total_normal = 0.0;
  for (Group& g : groups_) {
    // Gap, shear and step motion of every point with the new step displacement.
    measure.assign(at(g.count), Measure{});
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& p = points_[at(g.first + q)];
      const Kinematics& k = cached_kinematics(model, p, at(g.first + q));
      const double ds = k.tangential(raw);
      measure[at(q)] = {k.gap(raw), k.s0 + ds, ds};
      p.gap = measure[at(q)].gap + p.offset + p.shift;
    }
    // Modes by Shi's table (8.2), decided per contact from its resultants: an angle contact
    // is one point; the Gauss points of an edge-to-edge pair decide together, as one joint
    // element would.
    double stiffness = 0.0;
    double normal = 0.0; // resultant, compressive positive
    double shear = 0.0;  // resultant of the shear springs (lock)
    double motion = 0.0; // stiffness-weighted tangential step motion
    double gap = 0.0;    // stiffness-weighted gap
    double cohesion = 0.0;
    double tension = 0.0;
    for (int q = 0; q < g.count; ++q) {
      const ContactPoint& p = points_[at(g.first + q)];
      stiffness += p.stiffness;
      normal -= p.stiffness * measure[at(q)].gap;
      shear += p.stiffness * measure[at(q)].shear;
      motion += p.stiffness * measure[at(q)].ds;
      gap += p.stiffness * measure[at(q)].gap;
      if (p.bonded) {
        cohesion += law_->bond_cohesion(p);
        tension += law_->bond_tension(p);
      }
    }
    ContactPoint& lead = points_[at(g.first)];
    if (stiffness > 0.0) {
      gap /= stiffness;
      motion /= stiffness;
    } else {
      gap = measure[0].gap;
      motion = measure[0].ds;
    }
    // Edge-to-edge: where the edges now press on each other (the gap is linear along the
    // edge for order-0 covers, quadratic for order 1).
    OverlapPart pressed;
    double deepest = -gap;
    double pulling = 0.0; // force of the springs on parts that no longer press
    double pushing = 0.0; // force the springs would take on the parts that now press
    // The force of the pair's springs all along its overlap stretched by the rounding: a
    // spring move that gains or loses less is none.
    double spring_noise = 0.0;
    bool tie = false; // every gap sample within the rounding
    // The normal force the contact bears: the resultant of its springs, or, for the springs of
    // an edge-to-edge pair that go where the edges press, that of its springs that push. Springs
    // left where the edges have lifted off pull; their tension is no normal force for friction
    // (a pair tipping onto one end would otherwise slide on the force of a lifting end).
    double bearing = normal;
    if (g.edge && !lead.bonded) {
      bearing = 0.0;
      for (int q = 0; q < g.count; ++q)
        bearing += points_[at(g.first + q)].stiffness * std::max(0.0, -measure[at(q)].gap);
    }
    if (g.edge) {
      const std::vector<std::pair<double, double>> shifts = shifts_of(g);
      std::array<double, 3> gaps{gap_at(model, g, 0, shifts, raw)};
      std::size_t n = 1;
      if (gauss_ == 3)
        gaps[n++] = gap_at(model, g, 1, shifts, raw);
      gaps[n++] = gap_at(model, g, 2, shifts, raw);
      const std::span<const double> samples(gaps.data(), n);
      const GapProfile profile(g.lo, g.hi, samples);
      pressed = profile.negative();
      deepest = -*std::min_element(samples.begin(), samples.end());
      tie = std::all_of(samples.begin(), samples.end(),
                        [&](double s) { return std::abs(s) <= rounding_; });
      if (pressed.found) {
        const double alpha =
            options_.penalty / options_.spring_length * std::abs(g.t_next - g.t_first);
        pulling = alpha * profile.outside(g.from, g.to, pressed.from, pressed.to);
        pushing = alpha * profile.outside(pressed.from, pressed.to, g.from, g.to);
        spring_noise = alpha * rounding_ * (g.hi - g.lo);
      }
    }
    const double friction = law_->friction_coefficient(lead);
    const double limit = law_->shear_limit(std::max(0.0, bearing), friction, cohesion);
    const ContactMode before = lead.mode;
    const bool coupled = friction_coupled(lead); // in the solve that gave raw
    ContactMode after = before;
    int sign = lead.slide_sign;
    const bool partial = g.edge && !lead.bonded; // springs only on the pressed part
    // Gaps, motions and the forces of springs stretched by them that are within the rounding
    // of the coordinates change no mode: at rest they are noise, and a contact at a tie (a
    // joint face touching with no force, a contact sitting at the limit of friction) would
    // flip on every solve. The mode it is in holds it there. So an edge-to-edge pair closes
    // when it presses by more than the rounding somewhere, and opens when it presses nowhere
    // unless all its gaps are within the rounding: faces cut from one rock touch at such a tie
    // (a jointed rock mass dropped from rest, 1,003 blocks: 25 refactorisations a step, now
    // 1.4; docs/formulation.md, "Rounding").
    const double noise = stiffness * rounding_;
    // An open bond closes again where its springs would pull within its tensile strength
    // (with no strength: where it penetrates, as any contact).
    const bool closes = partial       ? pressed.found && deepest > rounding_
                        : lead.bonded ? normal > -tension + noise
                                      : gap < -rounding_;
    if (before == ContactMode::open) {
      if (closes) {
        // Shi 8.2: open -> slide when the shear the lock would take, the step's tangential
        // motion against a spring of the same stiffness, beats friction on the normal force
        // the penetration gives; open -> lock otherwise.
        const double trial_shear = std::abs(motion) * stiffness;
        const double trial_limit =
            law_->shear_limit(std::max(0.0, deepest) * stiffness, friction, cohesion);
        if (trial_shear > trial_limit && !hold_shear_) {
          after = ContactMode::slide;
          sign = motion > 0.0 ? 1 : -1;
        } else {
          after = ContactMode::lock;
        }
      }
    } else if (partial ? !pressed.found && !tie : normal < -tension - noise) {
      // Lifted off, or tension beyond the strength of a bond: a bond that is open when the
      // iteration has converged breaks (end_step()); one that an iteration on the way opens
      // keeps it, and holds again where it closes.
      after = ContactMode::open;
    } else if (before == ContactMode::lock) {
      // A contact that has switched between lock and slide chatter_limit times in the step
      // sits at the limit of friction: locked it needs more than friction, sliding it turns
      // back against it (the chatter rule, docs/formulation.md). In a static step it stays
      // locked, and the step reports by how much it exceeds its limit (ModeUpdate::
      // lock_excess): the excess leaves a state beyond Coulomb's law, but no motion. In a
      // dynamic step it slides at its limit instead (below): a lock held beyond it acts on the
      // bodies for the whole step, and the impulse stays in their velocities (in the
      // 1000-block pile of bench/stress.py a lock held at 6.8 times its limit spun a settled
      // block up to 17 rad/s and threw a top-row block 2 m up). A lock without any friction
      // limit is never held: with no normal force and no cohesion it slides freely, which
      // cannot chatter (a tunnel's faces at a tie were held with 0.42 MN of shear and no
      // normal force).
      if (std::abs(shear) > limit + noise && !hold_shear_) {
        if (limit > 0.0 && lead.slips >= options_.chatter_limit && !dynamic_) {
          ++counters_.chatter_holds;
          held_beyond_.emplace_back(std::abs(shear) - limit, std::abs(shear) / limit);
        } else {
          after = ContactMode::slide;
          sign = shear > 0.0 ? 1 : -1;
        }
      }
    } else if (motion * lead.slide_sign < -rounding_) {
      // The sliding reversed against its friction: it sticks. Without any friction or
      // cohesion nothing can hold it: it keeps sliding, the other way (a lock would let go
      // at once and the two would alternate for ever). In a dynamic step a contact at the
      // chatter limit keeps sliding, its friction at the limit and in its direction: the
      // force is Coulomb's, and what it does along a motion that turned back is reported
      // (ModeUpdate::slide_feed).
      if (limit > 0.0 && !hold_shear_ && dynamic_ && lead.slips >= options_.chatter_limit) {
        ++counters_.chatter_holds;
        held_against_.emplace_back(limit, std::abs(motion));
      } else if (limit > 0.0 && !hold_shear_) {
        after = ContactMode::lock;
      } else {
        sign = motion > 0.0 ? 1 : -1;
      }
    }
    // Chatter rule (docs/formulation.md): a contact that has switched between open and
    // closed chatter_limit times in the step lifts off whenever it is closed and penetrates
    // whenever it is open: the force it can carry is nil. It stays open for the rest of the
    // step (its small penetration is reported, and it is kept for the next step), unless it
    // penetrates by more than 1e-3 of the largest step displacement: then it is no near-zero
    // contact, it closes, and a step that cannot settle is cut.
    if (!closed(before) && closed(after) && lead.flips >= options_.chatter_limit &&
        deepest <= held_open_penetration_) {
      after = ContactMode::open;
      ++counters_.chatter_holds;
    }
    const bool flip = closed(after) != closed(before);
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& p = points_[at(g.first + q)];
      const double length =
          (boundary_.position[at(boundary_.next[at(p.master)])] - boundary_.position[at(p.master)])
              .norm();
      const Measure& m = measure[at(q)];
      if (!closed(before) && closed(after)) {
        // Locked at its entrance position (Shi eq. 3.4-3.6): where the gap crosses zero, a
        // fraction t0 of the step's tangential motion along the edge.
        const Kinematics& k = cached_kinematics(model, p, at(g.first + q));
        const double t0 = k.g0 > 0.0 ? std::clamp(k.g0 / (k.g0 - m.gap), 0.0, 1.0) : 0.0;
        p.anchor = projection(p.master, p.slave) + t0 * m.ds / length;
      }
      // slide -> lock keeps the anchor the step started with: it sticks where it was. The
      // slide of this iteration's trial (with friction from the last iteration's normal force)
      // is no motion that happened; anchoring there froze it into the step (examples/10: a
      // pivot slid 2.4 mm against the way the load pushes it).
      p.mode = after;
      p.slide_sign = sign;
      if (flip)
        ++p.flips;
      if (closed(before) && closed(after) && before != after)
        ++p.slips;
    }
    if (partial && closed(after) && pressed.found)
      lift_off.push_back({static_cast<int>(&g - groups_.data()), pressed, !closed(before), pulling,
                          pushing, spring_noise, bearing});
    // Friction from this solve's normal force, shared by stiffness. A contact that just
    // closed has none yet: the penetration it reached while open, without its spring,
    // overestimates it many times (friction from it can throw a block back up a slope).
    const double used = [&] {
      double sum = 0.0;
      for (int q = 0; q < g.count; ++q)
        sum += points_[at(g.first + q)].normal_force;
      return sum;
    }();
    const double now = closed(after) && closed(before) ? bearing : 0.0;
    const double placed = group_stiffness(g);
    // The shear force on the master along its edge (first vertex to next): the spring's pull,
    // or friction's, which opposes the slave's sliding (sign) and so pulls the master along.
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& p = points_[at(g.first + q)];
      const double share = placed > 0.0 ? p.stiffness / placed : 0.0;
      p.normal_force = now * share;
      p.shear_force = after == ContactMode::lock ? p.stiffness * measure[at(q)].shear
                      : after == ContactMode::slide
                          ? sign * (std::max(0.0, now) * friction * share + law_->bond_cohesion(p))
                          : 0.0;
    }
    if (after == ContactMode::slide) {
      const double work = friction * std::abs(motion);
      // Friction acts on the compressive part of the normal force (a bond in tension slides
      // on its cohesion alone), and the cohesion a bond slides with is friction work too.
      friction_total += work * std::max(0.0, now) + cohesion * std::abs(motion);
      // A change of the normal force within that of the springs stretched by the rounding is
      // none (the friction of a contact at a tie, on a normal force of rounding, would be
      // chased for ever: its relative change never settles). Coupled friction acted with the
      // normal force of this very solve: the springs' resultant, which differs from what the
      // pair bears only by springs that pull within tension_tolerance (or that the next
      // lift-off move takes away), so it has no change to chase.
      const double change = coupled ? 0.0
                            : before == ContactMode::slide
                                ? std::max(0.0, now) - std::max(0.0, used)
                                : std::max(0.0, now);
      if (std::abs(change) > noise)
        friction_change += work * std::abs(change);
    }
    if (closed(after))
      total_normal += std::max(0.0, normal);
    if (after != before) {
      ++update.changes;
      last_changed_ = g.first;
    }
  }
  // The springs of edge-to-edge contacts move to the parts that press (a semi-smooth active
  // set on each overlap), for a contact that just closed, and for the others when the force
  // of the springs that come or go is not negligible against all contact force (near the
  // lift-off point the gaps are at the level of the springs' own penetration; chasing them
  // there would only cost iterations). The anchors of a lock follow the slave material
  // points.
  for (const LiftOff& l : lift_off) {
    if (const OverlapPart part = lift_off_part(l, total_normal); part.found)
      move_springs(l, part, update);
  }
  update.friction_residual = friction_total > 0.0 ? friction_change / friction_total : 0.0;
  // Locks held beyond friction by more than the iteration's negligible force (what the
  // lift-off tolerance lets springs leave or not take): a hold of 0.09 N beyond a limit of
  // 5e-4 N on a slope carrying meganewtons is no violation to report.
  for (const auto& [excess, ratio] : held_beyond_) {
    if (excess > options_.lift_off_tolerance * total_normal)
      update.lock_excess = std::max(update.lock_excess, ratio);
  }
  // Held slides whose motion turned back: the work of their friction along it, where that
  // friction is not negligible in the same sense.
  for (const auto& [force, motion] : held_against_) {
    if (force > options_.lift_off_tolerance * total_normal)
      update.slide_feed += force * motion;
  }
  holds_ = {update.lock_excess, update.slide_feed};
  return update;
}

std::uint64_t ContactSystem::interface_key(int slave, int master) const {
  const auto a = static_cast<std::uint64_t>(at(boundary_.block[at(slave)]));
  const auto b = static_cast<std::uint64_t>(at(boundary_.block[at(master)]));
  return std::uint64_t{1} << 63U | std::min(a, b) << 32U | std::max(a, b);
}

void ContactSystem::break_yielded_interfaces(const Model& model, const Eigen::VectorXd& raw) {
  // An interface whose bonded contacts all slide has yielded all along: no elastic part of
  // it is left to take more load, and Mohr-Coulomb's residual strength (friction) is all it
  // keeps. Until then its sliding contacts carry their cohesion (plastic yield), so that
  // the load they shed goes to the parts that still hold and the joint holds up to its
  // whole strength c L + N tan(phi) whatever its stress concentrations. A contact in slide
  // mode whose step motion is within the rounding does not move: it holds (friction at or
  // above what acts on it, the mode it is in keeps it there).
  // Most scenes have no bond at all: nothing to allocate or walk then (a step of 10,004
  // blocks has 60,000 contacts).
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
    if (lead.mode == ContactMode::open) {
      // Open at the end of the step: this part breaks where its springs would pull beyond
      // its tensile strength (not where the chatter rule holds it open within it).
      if (law_->breaks_open(
              std::span<const ContactPoint>(points_).subspan(at(g.first), at(g.count))))
        unbond(g, g.key);
      continue;
    }
    const std::uint64_t key = interface_key(lead.slave_edge, lead.master);
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

std::vector<ContactSystem::Place> ContactSystem::current_places(const Model& model) const {
  // The boundary numbered as begin_step() numbers it, at its current place.
  const ContactBoundary now = contact_boundary(model);
  const std::vector<Point2>& position = now.position;
  const std::vector<int>& next = now.next;
  NMM_ASSERT(position.size() == boundary_.position.size(), "the boundary changed its vertices");
  std::vector<Place> result;
  result.reserve(points_.size());
  for (const ContactPoint& p : points_) {
    Place place;
    place.position = is_edge_pair(p.key) ? Point2((1.0 - p.u) * position[at(p.slave_edge)] +
                                                  p.u * position[at(next[at(p.slave_edge)])])
                                         : position[at(p.slave_edge)];
    place.normal = perp(position[at(next[at(p.master)])] - position[at(p.master)]).normalized();
    result.push_back(place);
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
