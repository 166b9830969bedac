// SPDX-License-Identifier: MIT
// contact/contact_transfer.cpp — ContactSystem: the states of closed contacts carried from
// one step to the next (Shi 1997, 3.3) and found again by the next step's contacts, the
// state of an open-close iteration saved and restored within a step, and what a restart
// checkpoint keeps.
#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <numeric>
#include <span>
#include <string>
#include <unordered_map>

namespace nmm {

using detail::at;
using detail::closed;

const ContactSystem::Carried* ContactSystem::carried_at(std::uint64_t key) const {
  const int k = carried_index_.find(key);
  return k == KeyIndex::none ? nullptr : &carried_[at(k)];
}

std::span<const std::pair<double, double>> ContactSystem::anchors_of(const Carried& state) const {
  return {carried_anchors_.data() + state.first_anchor, at(state.n_anchors)};
}

void ContactSystem::carry(std::uint64_t key,
                          Carried state,
                          std::span<const std::pair<double, double>> anchors) {
  state.first_anchor = static_cast<int>(carried_anchors_.size());
  state.n_anchors = static_cast<int>(anchors.size());
  carried_anchors_.insert(carried_anchors_.end(), anchors.begin(), anchors.end());
  const auto k = static_cast<int>(carried_.size());
  if (carried_index_.insert(key, k)) {
    carried_.push_back(state);
    carried_keys_.push_back(key);
  } else { // the key carried already: the new state replaces it
    carried_[at(carried_index_.find(key))] = state;
  }
}

void ContactSystem::clear_carried() {
  carried_.clear();
  carried_keys_.clear();
  carried_index_.clear();
  carried_anchors_.clear();
}

// Contacts found by the slave or the master of a carried contact, for the transfer of a
// contact whose slave moved on to the next edge (Shi 3.3): (edge, key, state) sorted by
// edge, and for one edge by decreasing key (the order an std::unordered_multimap filled in
// increasing key order gave, which decides between two candidates for a transfer: kept so
// that the runs stay what they were). A counting sort by edge of the keys taken in
// decreasing order (keep increases): linear in the carried contacts, where sorting both
// lists would cost milliseconds a step at tens of thousands of them.
ContactSystem::CarriedByEdge
ContactSystem::carried_by_edge(const std::vector<std::uint64_t>& keep) const {
  std::vector<const Carried*> states;
  states.reserve(keep.size());
  int n_edges = 0;
  for (const std::uint64_t key : keep) {
    states.push_back(carried_at(key));
    NMM_ASSERT(states.back()->slave >= 0 && states.back()->master >= 0,
               "a carried contact has its two edges");
    n_edges = std::max({n_edges, states.back()->slave + 1, states.back()->master + 1});
  }
  auto sorted_by_edge = [&](auto edge_of) {
    std::vector<int> start(at(n_edges) + 1, 0);
    for (const Carried* state : states)
      ++start[at(edge_of(*state)) + 1];
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<ByEdge> list(keep.size());
    for (std::size_t i = keep.size(); i-- > 0;) {
      const int edge = edge_of(*states[i]);
      list[at(start[at(edge)]++)] = {edge, keep[i], states[i]};
    }
    return list;
  };
  return {sorted_by_edge([](const Carried& state) { return state.slave; }),
          sorted_by_edge([](const Carried& state) { return state.master; })};
}

// Among the carried contacts, the one stored under the same key, or another that had the
// same slave and master (an angle-to-angle contact whose candidate changed), or else one
// whose slave moved on from an adjacent master (Shi 3.3).
const ContactSystem::Carried* ContactSystem::carried_state(const CarriedByEdge& carried,
                                                           std::uint64_t key,
                                                           int slave,
                                                           int master,
                                                           bool edge,
                                                           bool* identical) const {
  auto on_edge = [](const std::vector<ByEdge>& list, int which) {
    const auto first = std::lower_bound(list.begin(), list.end(), which,
                                        [](const ByEdge& e, int value) { return e.edge < value; });
    auto last = first;
    while (last != list.end() && last->edge == which)
      ++last;
    return std::span<const ByEdge>(first, last);
  };
  *identical = false;
  auto adjacent = [&](int e, int f) {
    return boundary_.next[at(e)] == f || boundary_.next[at(f)] == e;
  };
  const Carried* moved = nullptr;
  if (const Carried* same = carried_at(key); same != nullptr) {
    *identical = same->slave == slave && same->master == master;
    if (*identical || !closed(same->mode))
      return same;
    moved = same; // the same contact on its other entrance line
  }
  for (const ByEdge& e : on_edge(carried.slave, slave)) {
    const Carried& state = *e.state;
    if (!closed(state.mode) || is_edge_pair(e.key) != edge)
      continue;
    if (state.master == master) {
      *identical = true;
      return &state;
    }
    if (moved == nullptr && adjacent(state.master, master))
      moved = &state;
  }
  if (moved != nullptr || !edge)
    return moved;
  for (const ByEdge& e : on_edge(carried.master, master)) {
    const Carried& state = *e.state;
    if (closed(state.mode) && is_edge_pair(e.key) && adjacent(state.slave, slave))
      return &state;
  }
  return nullptr;
}

void ContactSystem::end_step(const Model& model, const Eigen::VectorXd& raw) {
  break_yielded_interfaces(model, raw);
  clear_carried();
  carried_index_.reserve(groups_.size());
  std::vector<std::pair<double, double>> anchors;
  for (const Group& g : groups_) {
    const ContactPoint& lead = points_[at(g.first)];
    // Closed contacts carry their state; an open one that penetrates (held open by the
    // chatter rule) is kept so that the next detection does not drop it.
    const bool penetrating =
        std::any_of(points_.begin() + g.first, points_.begin() + g.first + g.count,
                    [](const ContactPoint& p) { return p.gap < p.offset; });
    if (!closed(lead.mode) && !penetrating)
      continue;
    Carried state;
    state.slave = lead.slave_edge;
    state.master = lead.master;
    state.mode = lead.mode;
    state.slide_sign = lead.slide_sign;
    // An open contact's offset follows its gap up (it never grows: a permanent overlap is
    // one the springs found, not one they make).
    state.offset = std::min(0.0, std::max(lead.offset, lead.gap));
    anchors.clear();
    for (int q = 0; q < g.count; ++q) {
      const ContactPoint& p = points_[at(g.first + q)];
      state.normal += p.normal_force;
      double anchor = p.anchor;
      if (p.mode == ContactMode::slide) {
        // The next lock anchors where the slave point ends up on the edge. (Less the stretch
        // of its spring at the friction it slid with, sign N tan(phi) / p, a lock taking over
        // would start with that force: tried, and not kept: docs/formulation.md, "Anchors".)
        const Kinematics& k = cached_kinematics(model, p, at(g.first + q));
        const double l = (boundary_.position[at(boundary_.next[at(p.master)])] -
                          boundary_.position[at(p.master)])
                             .norm();
        anchor = p.anchor + (k.s0 + k.tangential(raw)) / l;
      }
      anchors.emplace_back(p.u, anchor);
    }
    carry(g.key, state, anchors);
  }
}

void ContactSystem::save(State& state) const {
  state.groups = groups_;
  state.points = points_;
  state.broken = broken_;
  state.bonds_broken = counters_.bonds_broken;
  state.holds = holds_;
}

void ContactSystem::restore(const State& state) {
  groups_ = state.groups;
  points_ = state.points;
  broken_ = state.broken;
  counters_.bonds_broken = state.bonds_broken;
  holds_ = state.holds;
  last_changed_ = 0;
}

void ContactSystem::restart_step() {
  restore(start_);
  has_converged_ = false;
  set_hold_shear(hold_shear_);
}

void ContactSystem::save_state(StateWriter& out) const {
  out.section("CONT");
  std::vector<std::uint64_t> keys = carried_keys_;
  std::sort(keys.begin(), keys.end());
  out.put_count(keys.size());
  for (const std::uint64_t key : keys) {
    const Carried& state = *carried_at(key);
    out.put(static_cast<std::int64_t>(key));
    out.put(static_cast<std::int64_t>(state.slave));
    out.put(static_cast<std::int64_t>(state.master));
    out.put(static_cast<std::int64_t>(state.mode));
    out.put(static_cast<std::int64_t>(state.slide_sign));
    out.put(state.normal);
    out.put(state.offset);
    out.put_count(at(state.n_anchors));
    for (const auto& [u, anchor] : anchors_of(state)) {
      out.put(u);
      out.put(anchor);
    }
  }
  // The keys marked in a map of broken bonds or open ones, in order.
  const auto put_marked = [&](const std::unordered_map<std::uint64_t, bool>& marked) {
    keys.clear();
    for (const auto& [key, set] : marked) {
      if (set)
        keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    out.put_count(keys.size());
    for (const std::uint64_t key : keys)
      out.put(static_cast<std::int64_t>(key));
  };
  put_marked(broken_);
  put_marked(opened_);
  out.put(static_cast<std::int64_t>(counters_.points));
  out.put(static_cast<std::int64_t>(counters_.chatter_holds));
  out.put(static_cast<std::int64_t>(counters_.bonds_broken));
  out.put(static_cast<std::int64_t>(counters_.detection.edge_pairs));
  out.put(static_cast<std::int64_t>(counters_.detection.vertex_edge));
  out.put(static_cast<std::int64_t>(counters_.detection.vertex_vertex));
  out.put(static_cast<std::int64_t>(counters_.detection.edge_edge));
}

void ContactSystem::load_state(StateReader& in) {
  in.section("CONT");
  const std::size_t n_edges = law_->n_surfaces();
  auto edge = [&](std::int64_t e) {
    if (e < 0 || static_cast<std::size_t>(e) >= n_edges)
      in.fail("a contact names edge " + std::to_string(e) + " of " + std::to_string(n_edges));
    return static_cast<int>(e);
  };
  clear_carried();
  const std::size_t n = in.count();
  std::vector<std::pair<double, double>> anchors;
  for (std::size_t k = 0; k < n; ++k) {
    const auto key = static_cast<std::uint64_t>(in.integer());
    Carried state;
    state.slave = edge(in.integer());
    state.master = edge(in.integer());
    const std::int64_t mode = in.integer();
    if (mode < 0 || mode > static_cast<std::int64_t>(ContactMode::lock))
      in.fail("a contact mode of " + std::to_string(mode));
    state.mode = static_cast<ContactMode>(mode);
    state.slide_sign = static_cast<int>(in.integer());
    state.normal = in.real();
    state.offset = in.real();
    anchors.resize(in.count());
    for (auto& [u, anchor] : anchors) {
      u = in.real();
      anchor = in.real();
    }
    carry(key, state, anchors);
  }
  for (std::unordered_map<std::uint64_t, bool>* marked : {&broken_, &opened_}) {
    marked->clear();
    const std::size_t n_marked = in.count();
    for (std::size_t k = 0; k < n_marked; ++k)
      (*marked)[static_cast<std::uint64_t>(in.integer())] = true;
  }
  counters_.points = in.integer();
  counters_.chatter_holds = in.integer();
  counters_.bonds_broken = in.integer();
  counters_.detection.edge_pairs = in.integer();
  counters_.detection.vertex_edge = in.integer();
  counters_.detection.vertex_vertex = in.integer();
  counters_.detection.edge_edge = in.integer();
}

} // namespace nmm
