// SPDX-License-Identifier: MIT
// contact/contact_energy.cpp — the contacts' terms of the energy balance: the energy in the
// closed springs and what the springs and friction take in a step (docs/formulation.md,
// "Energy balance").
#include "contact/contact_system.hpp"

#include <cmath>

namespace nmm {

namespace {

/// Energy of a point's springs with gap @p gap and shear displacement @p shear in mode
/// @p mode: p g² / 2 of a closed normal spring, pressed, or pulled when @p bonded (Shi eq.
/// 3.17-3.18), and ks s² / 2 of a locked shear spring (eq. 3.25-3.26; ks = p but for a
/// joint's own stiffnesses). An unbonded closed point where the faces are apart holds
/// nothing: it carries no tension, and springs that the lift-off moves onto a part of the
/// overlap still open at the start of the step (it presses at the end) did not exist there
/// then, nor did the shear their anchors carry.
double energy_of(ContactMode mode, const ContactPoint& p, double gap, double shear, bool bonded) {
  if (mode == ContactMode::open || !(p.stiffness > 0.0) || (!bonded && gap > 0.0))
    return 0.0;
  double energy = 0.5 * p.stiffness * gap * gap;
  if (mode == ContactMode::lock)
    energy += 0.5 * shear_stiffness(p) * shear * shear;
  return energy;
}

} // namespace

ContactSystem::SpringWork ContactSystem::spring_work(const Model& model,
                                                     const Eigen::VectorXd& raw) const {
  // Per point: its springs at the start of the step (the mode begin_step() gave it, the
  // gap g0 and shear offset s0 of the start geometry) and at the end of the last solve (its
  // mode now, g1 = g0 + hn d, s1 = s0 + hs d). The solve takes the springs' forces at the end
  // of the step, -p g1 and -p s1, along the whole step's change: the bodies do p g1 (g1 - g0)
  // + p s1 (s1 - s0) on the springs of the final mode. Of that work and the energy the point
  // started with, what its springs do not hold at the end is lost: p (g1 - g0)² / 2 for a
  // spring closed throughout, the whole start energy of one that opened or slipped. A point
  // whose springs end with more than that (a spring that started stretched while it was
  // open: an overlap found by the detection) made energy. A lock that opened and closed
  // again in the step has a new anchor (its entrance position): its shear spring at the
  // start is the one of the anchor the step began with, not the new one, which did not
  // exist then. (Springs the lift-off moves along a pair are taken where they end: the
  // pair's pressed part at the start geometry, as the next step's detection places them.)
  SpringWork work;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const ContactPoint& p = points_[i];
    const ContactMode before = start_.points[i].mode;
    // A bonded point open at the end, yielded in tension, pulled with its strength t L as a
    // constant load along the step's opening: plastic work, lost.
    const double tension = p.mode == ContactMode::open ? law_->bond_tension(p) : 0.0;
    if (before == ContactMode::open && p.mode == ContactMode::open && !(tension > 0.0))
      continue;
    const Kinematics& k = cached_kinematics(model, p, i);
    const double g1 = k.gap(raw);
    const double s1 = k.s0 + k.tangential(raw);
    const ContactPoint& s = start_.points[i];
    const bool anchored_anew = s.anchor != p.anchor && s.slave == p.slave && s.master == p.master &&
                               s.stiffness == p.stiffness;
    const double s0 = anchored_anew ? start_gap_and_shear(s).second : k.s0;
    const double start = energy_of(before, p, k.g0, s0, s.bonded);
    const double end = energy_of(p.mode, p, g1, s1, p.bonded);
    double done = tension > 0.0 ? tension * (g1 - k.g0) : 0.0;
    if (p.mode != ContactMode::open)
      done += p.stiffness * g1 * (g1 - k.g0);
    if (p.mode == ContactMode::lock)
      done += shear_stiffness(p) * s1 * (s1 - k.s0);
    const double lost = done + start - end;
    work.start += start;
    work.end += end;
    if (before == ContactMode::open && p.mode == ContactMode::open) {
      // A yielded bond open throughout pulls with the constant t L: a force of fixed size,
      // whose work along the step's opening is lost and along a closing comes back out of
      // what its opening took (its net opening times t L is what it dissipates).
      work.lost += lost;
      continue;
    }
    (lost >= 0.0 ? work.lost : work.made) += std::abs(lost);
  }
  return work;
}

double ContactSystem::friction_dissipation(const Model& model, const Eigen::VectorXd& raw) const {
  double work = 0.0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const ContactPoint& p = points_[i];
    if (p.mode != ContactMode::slide || p.shear_force == 0.0)
      continue;
    work += std::abs(p.shear_force * cached_kinematics(model, p, i).tangential(raw));
  }
  return work;
}

} // namespace nmm
