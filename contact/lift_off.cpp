// SPDX-License-Identifier: MIT
// contact/lift_off.cpp — where the springs of an edge-to-edge contact go: its Gauss points
// placed on the part with springs, moved to where the edges press, and the search of the
// lift-off point (docs/formulation.md, "Lift-off").
#include "contact/lift_off.hpp"

#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace nmm {

using detail::at;
using detail::offset_at;
using detail::w2;
using detail::w3;
using detail::xi2;
using detail::xi3;

double LiftOffEnd::next(double now, double wanted, double negligible) {
  const double g = wanted - now;
  if (g == 0.0)
    return now;
  if (!bracketed) {
    if (g * moved >= 0.0) {
      moved = g;
      return wanted;
    }
    // The move went back: the root lies between the place before the last move (which
    // wanted the end where the move took it) and this one.
    bracketed = true;
    a = now - moved;
    ga = moved;
    b = now;
    gb = g;
    kept = 0;
  } else if (g * ga > 0.0) {
    a = now;
    ga = g;
    if (kept == +1)
      gb *= 0.5; // Illinois: an end kept twice counts half, so the bracket shrinks from it too
    kept = +1;
  } else {
    b = now;
    gb = g;
    if (kept == -1)
      ga *= 0.5;
    kept = -1;
  }
  if (std::abs(b - a) < negligible) {
    bracketed = false;
    moved = g;
    return wanted;
  }
  const double place = a - ga * (b - a) / (gb - ga);
  moved = place - now;
  return place;
}

void ContactSystem::place(Group& g,
                          double from,
                          double to,
                          const std::vector<std::pair<double, double>>* offsets) {
  g.from = from;
  g.to = to;
  const ContactPoint& lead = points_[at(g.first)];
  const Point2& a = boundary_.position[at(lead.slave_edge)];
  const Point2& d = boundary_.position[at(boundary_.next[at(lead.slave_edge)])];
  // Lengths along the master (the projection of the part), so that a pair of parallel
  // edges integrates exactly as one joint element (Goodman).
  const double span = std::abs(g.t_next - g.t_first) * (to - from);
  const double alpha = edge_stiffness(lead.strength);
  for (int q = 0; q < g.count; ++q) {
    ContactPoint& p = points_[at(g.first + q)];
    const double xi = gauss_ == 2 ? xi2[at(q)] : xi3[at(q)];
    const double w = gauss_ == 2 ? w2[at(q)] : w3[at(q)];
    p.u = from + (to - from) * xi;
    p.slave = a + p.u * (d - a);
    p.length = w * span;
    p.stiffness = alpha * p.length;
    p.anchor =
        projection(lead.master, p.slave) + (offsets != nullptr ? offset_at(*offsets, p.u) : 0.0);
  }
}

OverlapPart ContactSystem::lift_off_part(const LiftOff& l, double total_normal) {
  Group& g = groups_[at(l.group)];
  double from = l.part.from;
  double to = l.part.to;
  if (!l.just_closed) {
    const bool pulls =
        l.pulling > std::max(options_.tension_tolerance * total_normal, l.spring_noise);
    const bool pushes =
        l.pushing > std::max(options_.lift_off_tolerance * total_normal, l.spring_noise);
    // A lift-off point at nearly zero pressure can swing between two places for ever: its
    // first move back is made, and then the contact settles: from then on it only gives
    // up springs that pull (shrinking cannot cycle; what it leaves out penetrates at
    // nearly zero pressure). Settling instead of that first move back kept springs off a
    // part that pressed hard again (a block tipping forward on its base while locked in
    // the first solve, then sliding flat: docs/formulation.md, "Lift-off"). What it leaves
    // out does not always press at nearly zero pressure: in a pile of blocks landing, the
    // other contacts' changes swing a pair's pressed part between 0.6 mm and 76 mm of its
    // edge, the shrinking kept the 0.6 mm, and the block sank 2.1 mm into the other where
    // the left-out part would have taken 50 times the pair's force. So when the part left
    // out would take more than all the pair bears, its ends search for the place between
    // their last two (LiftOffEnd) for a few moves, and then the contact settles for good.
    // When the part that presses no longer meets the part with springs, every spring pulls
    // and the pressed part has none: the springs move there (kept, they held a cylinder on
    // a block with 3.3e6 N of tension against a load of 1e7 N; examples/17 at 1000 E).
    const bool back =
        (from - g.from) * g.from_end.moved < 0.0 || (to - g.to) * g.to_end.moved < 0.0;
    const bool overlap = std::min(to, g.to) - std::max(from, g.from) > 1e-6 * (g.hi - g.lo);
    if (g.searching && g.searches >= options_.lift_off_searches)
      g.stop_search(); // settled for good
    if (!g.settled && back && (pulls || pushes)) {
      g.settled = true; // this first move back is made
    } else if (g.settled && overlap && g.searches < options_.lift_off_searches &&
               (g.searching || l.pushing > l.bearing)) {
      if (!pulls && !pushes)
        return {};
      g.searching = true;
      ++g.searches;
      const double negligible = 1e-9 * (g.hi - g.lo);
      const double wanted_from = from;
      const double wanted_to = to;
      from = g.from_end.next(g.from, wanted_from, negligible);
      to = g.to_end.next(g.to, wanted_to, negligible);
      if (!(from < to)) { // the two ends crossed: the part that presses now
        from = wanted_from;
        to = wanted_to;
        g.from_end = LiftOffEnd{from - g.from};
        g.to_end = LiftOffEnd{to - g.to};
      }
    } else if (g.settled && overlap && l.pushing > l.bearing && pushes) {
      // The search is spent and the part left out would still take more than all the pair
      // bears: the springs take it in (growing, as shrinking, cannot cycle).
      from = std::min(from, g.from);
      to = std::max(to, g.to);
    } else if (g.settled && overlap) {
      from = std::max(from, g.from);
      to = std::min(to, g.to);
      if (!pulls)
        return {};
    } else if (g.settled) {
      if (!pulls && !pushes)
        return {};
      g.stop_search();
    } else if (!pulls && !pushes) {
      return {};
    }
    if (!g.searching) {
      g.from_end.moved = from - g.from;
      g.to_end.moved = to - g.to;
    }
  } else {
    g.stop_search();
  }
  return {true, from, to};
}

void ContactSystem::move_springs(const LiftOff& l, const OverlapPart& part, ModeUpdate& update) {
  Group& g = groups_[at(l.group)];
  std::vector<std::pair<double, double>> offsets;
  const std::vector<std::pair<double, double>> shifts = shifts_of(g);
  double normal = 0.0;
  for (int q = 0; q < g.count; ++q) {
    const ContactPoint& p = points_[at(g.first + q)];
    offsets.emplace_back(p.u, p.anchor - projection(p.master, p.slave));
    normal += p.normal_force;
  }
  place(g, part.from, part.to, &offsets);
  // The springs' multipliers go with them as the anchors do (interpolated along the pair).
  if (!shifts.empty()) {
    for (int q = 0; q < g.count; ++q) {
      ContactPoint& p = points_[at(g.first + q)];
      p.shift = offset_at(shifts, p.u);
    }
  }
  const double placed = group_stiffness(g);
  for (int q = 0; q < g.count; ++q) {
    ContactPoint& p = points_[at(g.first + q)];
    p.normal_force = placed > 0.0 ? normal * p.stiffness / placed : 0.0;
  }
  if (!l.just_closed) { // (a contact that just closed is counted already)
    ++update.changes;
    ++update.moves;
    last_changed_ = g.first;
  }
}

} // namespace nmm
