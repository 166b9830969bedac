// SPDX-License-Identifier: MIT
// contact/contact_modes.cpp — ContactSystem: the open-close iteration's decisions after a
// solve (Shi 1997, 8.2): each contact's resultants, its new mode by Shi's table with the
// chatter rule, its entrance anchor, and its normal and friction forces.
#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

namespace nmm {

using detail::at;
using detail::closed;
using detail::GapProfile;

ModeUpdate ContactSystem::update_modes(const Model& model, const Eigen::VectorXd& raw) {
  ModeUpdate update;
  held_beyond_.clear();
  held_against_.clear();
  // Friction consistency is judged on the whole system, by the work of friction in the step:
  // the work of the change of the friction forces since they were applied against the work
  // of all friction. A contact carrying a few newtons may change by a large fraction without
  // any effect on the motion.
  FrictionWork work_done;
  std::vector<Measure> measure;
  std::vector<LiftOff> lift_off;
  double total_normal = 0.0;
  for (Group& g : groups_) {
    measure_points(model, g, raw, measure);
    const Resultants r = resultants(model, g, raw, measure);
    const ModeStep step = decide_mode(g, r);
    set_modes(model, g, measure, step);
    const bool partial = g.edge && !points_[at(g.first)].bonded; // springs on the pressed part
    if (partial && closed(step.after) && r.pressed.found)
      lift_off.push_back({static_cast<int>(&g - groups_.data()), r.pressed, !closed(step.before),
                          r.pulling, r.pushing, r.spring_noise, r.bearing});
    set_forces(g, measure, r, step, work_done);
    if (closed(step.after))
      total_normal += std::max(0.0, r.normal);
    if (step.after != step.before) {
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
  update.friction_residual = work_done.total > 0.0 ? work_done.change / work_done.total : 0.0;
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

void ContactSystem::measure_points(const Model& model,
                                   const Group& g,
                                   const Eigen::VectorXd& raw,
                                   std::vector<Measure>& measure) {
  // Gap, shear and step motion of every point with the new step displacement.
  measure.assign(at(g.count), Measure{});
  for (int q = 0; q < g.count; ++q) {
    ContactPoint& p = points_[at(g.first + q)];
    const Kinematics& k = cached_kinematics(model, p, at(g.first + q));
    const double ds = k.tangential(raw);
    measure[at(q)] = {k.gap(raw), k.s0 + ds, ds};
    p.gap = measure[at(q)].gap + p.offset + p.shift;
  }
}

ContactSystem::Resultants ContactSystem::resultants(const Model& model,
                                                    const Group& g,
                                                    const Eigen::VectorXd& raw,
                                                    const std::vector<Measure>& measure) const {
  // Modes by Shi's table (8.2), decided per contact from its resultants: an angle contact
  // is one point; the Gauss points of an edge-to-edge pair decide together, as one joint
  // element would.
  Resultants r;
  for (int q = 0; q < g.count; ++q) {
    const ContactPoint& p = points_[at(g.first + q)];
    r.stiffness += p.stiffness;
    r.normal -= p.stiffness * measure[at(q)].gap;
    r.shear += shear_stiffness(p) * measure[at(q)].shear;
    r.motion += p.stiffness * measure[at(q)].ds;
    r.gap += p.stiffness * measure[at(q)].gap;
    if (p.bonded) {
      r.cohesion += law_->bond_cohesion(p);
      r.tension += law_->bond_tension(p);
    }
  }
  if (r.stiffness > 0.0) {
    r.gap /= r.stiffness;
    r.motion /= r.stiffness;
  } else {
    r.gap = measure[0].gap;
    r.motion = measure[0].ds;
  }
  r.friction = law_->friction_coefficient(points_[at(g.first)]);
  r.noise = r.stiffness * rounding_;
  pressing(model, g, raw, measure, r);
  return r;
}

void ContactSystem::pressing(const Model& model,
                             const Group& g,
                             const Eigen::VectorXd& raw,
                             const std::vector<Measure>& measure,
                             Resultants& r) const {
  // Edge-to-edge: where the edges now press on each other (the gap is linear along the
  // edge for order-0 covers, quadratic for order 1), the force of the springs on parts that
  // no longer press and the force they would take on the parts that now press, and the
  // force of the pair's springs all along its overlap stretched by the rounding (a spring
  // move that gains or loses less is none).
  r.deepest = -r.gap;
  // The normal force the contact bears: the resultant of its springs, or, for the springs of
  // an edge-to-edge pair that go where the edges press, that of its springs that push. Springs
  // left where the edges have lifted off pull; their tension is no normal force for friction
  // (a pair tipping onto one end would otherwise slide on the force of a lifting end).
  r.bearing = r.normal;
  if (g.edge && !points_[at(g.first)].bonded) {
    r.bearing = 0.0;
    for (int q = 0; q < g.count; ++q)
      r.bearing += points_[at(g.first + q)].stiffness * std::max(0.0, -measure[at(q)].gap);
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
    r.pressed = profile.negative();
    r.deepest = -*std::min_element(samples.begin(), samples.end());
    r.tie = std::all_of(samples.begin(), samples.end(),
                        [&](double s) { return std::abs(s) <= rounding_; });
    if (r.pressed.found) {
      const double alpha =
          edge_stiffness(points_[at(g.first)].strength) * std::abs(g.t_next - g.t_first);
      r.pulling = alpha * profile.outside(g.from, g.to, r.pressed.from, r.pressed.to);
      r.pushing = alpha * profile.outside(r.pressed.from, r.pressed.to, g.from, g.to);
      r.spring_noise = alpha * rounding_ * (g.hi - g.lo);
    }
  }
  r.limit = law_->shear_limit(std::max(0.0, r.bearing), r.friction, r.cohesion);
}

ContactSystem::ModeStep ContactSystem::decide_mode(const Group& g, const Resultants& r) {
  const ContactPoint& lead = points_[at(g.first)];
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
  // An open bond closes again where its springs would pull within its tensile strength
  // (with no strength: where it penetrates, as any contact).
  const bool closes = partial       ? r.pressed.found && r.deepest > rounding_
                      : lead.bonded ? r.normal > -r.tension + r.noise
                                    : r.gap < -rounding_;
  if (before == ContactMode::open) {
    if (closes) {
      // Shi 8.2: open -> slide when the shear the lock would take, the step's tangential
      // motion against a spring of the same stiffness, beats friction on the normal force
      // the penetration gives; open -> lock otherwise.
      const double trial_shear =
          std::abs(r.motion) * r.stiffness * points_[at(g.first)].shear_ratio;
      const double trial_limit =
          law_->shear_limit(std::max(0.0, r.deepest) * r.stiffness, r.friction, r.cohesion);
      if (trial_shear > trial_limit && !hold_shear_) {
        after = ContactMode::slide;
        sign = r.motion > 0.0 ? 1 : -1;
      } else {
        after = ContactMode::lock;
      }
    }
  } else if (partial ? !r.pressed.found && !r.tie : r.normal < -r.tension - r.noise) {
    // Lifted off, or tension beyond the strength of a bond: a bond that is open when the
    // iteration has converged breaks (end_step()); one that an iteration on the way opens
    // keeps it, and holds again where it closes.
    after = ContactMode::open;
  } else {
    const ModeStep kept = closed_mode(lead, r);
    after = kept.after;
    sign = kept.sign;
  }
  // Chatter rule (docs/formulation.md): a contact that has switched between open and
  // closed chatter_limit times in the step lifts off whenever it is closed and penetrates
  // whenever it is open: the force it can carry is nil. It stays open for the rest of the
  // step (its small penetration is reported, and it is kept for the next step), unless it
  // penetrates by more than 1e-3 of the largest step displacement: then it is no near-zero
  // contact, it closes, and a step that cannot settle is cut.
  if (!closed(before) && closed(after) && lead.flips >= options_.chatter_limit &&
      r.deepest <= held_open_penetration_) {
    after = ContactMode::open;
    ++counters_.chatter_holds;
  }
  return {before, after, sign, coupled};
}

ContactSystem::ModeStep ContactSystem::closed_mode(const ContactPoint& lead, const Resultants& r) {
  const ContactMode before = lead.mode;
  ContactMode after = before;
  int sign = lead.slide_sign;
  if (before == ContactMode::lock) {
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
    if (std::abs(r.shear) > r.limit + r.noise && !hold_shear_) {
      if (r.limit > 0.0 && lead.slips >= options_.chatter_limit && !chatter_slides_) {
        ++counters_.chatter_holds;
        held_beyond_.emplace_back(std::abs(r.shear) - r.limit, std::abs(r.shear) / r.limit);
      } else {
        after = ContactMode::slide;
        sign = r.shear > 0.0 ? 1 : -1;
      }
    }
  } else if (r.motion * lead.slide_sign < -rounding_) {
    // The sliding reversed against its friction: it sticks. Without any friction or
    // cohesion nothing can hold it: it keeps sliding, the other way (a lock would let go
    // at once and the two would alternate for ever). In a dynamic step a contact at the
    // chatter limit keeps sliding, its friction at the limit and in its direction: the
    // force is Coulomb's, and what it does along a motion that turned back is reported
    // (ModeUpdate::slide_feed).
    if (r.limit > 0.0 && !hold_shear_ && chatter_slides_ && lead.slips >= options_.chatter_limit) {
      ++counters_.chatter_holds;
      held_against_.emplace_back(r.limit, std::abs(r.motion));
    } else if (r.limit > 0.0 && !hold_shear_) {
      after = ContactMode::lock;
    } else {
      sign = r.motion > 0.0 ? 1 : -1;
    }
  }
  return {before, after, sign, false};
}

void ContactSystem::set_modes(const Model& model,
                              const Group& g,
                              const std::vector<Measure>& measure,
                              const ModeStep& step) {
  const ContactMode before = step.before;
  const ContactMode after = step.after;
  const int sign = step.sign;
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
}

void ContactSystem::set_forces(const Group& g,
                               const std::vector<Measure>& measure,
                               const Resultants& r,
                               const ModeStep& step,
                               FrictionWork& work_done) {
  const auto [before, after, sign, coupled] = step;
  // Friction from this solve's normal force, shared by stiffness. A contact that just
  // closed has none yet: the penetration it reached while open, without its spring,
  // overestimates it many times (friction from it can throw a block back up a slope).
  const double used = [&] {
    double sum = 0.0;
    for (int q = 0; q < g.count; ++q)
      sum += points_[at(g.first + q)].normal_force;
    return sum;
  }();
  const double now = closed(after) && closed(before) ? r.bearing : 0.0;
  const double placed = group_stiffness(g);
  // The shear force on the master along its edge (first vertex to next): the spring's pull,
  // or friction's, which opposes the slave's sliding (sign) and so pulls the master along.
  for (int q = 0; q < g.count; ++q) {
    ContactPoint& p = points_[at(g.first + q)];
    const double share = placed > 0.0 ? p.stiffness / placed : 0.0;
    // An open bond pulls with its tensile strength (contribution()): a tensile normal force.
    const double pull = law_->bond_tension(p);
    p.normal_force = closed(after) ? now * share : pull > 0.0 ? -pull : 0.0;
    p.shear_force = after == ContactMode::lock ? shear_stiffness(p) * measure[at(q)].shear
                    : after == ContactMode::slide
                        ? sign * (std::max(0.0, now) * r.friction * share + law_->bond_cohesion(p))
                        : 0.0;
  }
  if (after == ContactMode::slide) {
    const double work = r.friction * std::abs(r.motion);
    // Friction acts on the compressive part of the normal force (a bond in tension slides
    // on its cohesion alone), and the cohesion a bond slides with is friction work too.
    work_done.total += work * std::max(0.0, now) + r.cohesion * std::abs(r.motion);
    // A change of the normal force within that of the springs stretched by the rounding is
    // none (the friction of a contact at a tie, on a normal force of rounding, would be
    // chased for ever: its relative change never settles). Coupled friction acted with the
    // normal force of this very solve: the springs' resultant, which differs from what the
    // pair bears only by springs that pull within tension_tolerance (or that the next
    // lift-off move takes away), so it has no change to chase.
    const double change = coupled                        ? 0.0
                          : before == ContactMode::slide ? std::max(0.0, now) - std::max(0.0, used)
                                                         : std::max(0.0, now);
    if (std::abs(change) > r.noise)
      work_done.change += work * std::abs(change);
  }
}

} // namespace nmm
