// SPDX-License-Identifier: MIT
// contact/augmented_lagrange.cpp — ContactSystem: augmented-Lagrange passes that hold the
// closed contacts to ContactOptions::penetration_tolerance (Simo and Laursen 1992; Lin,
// Amadei, Jung and Dwyer 1996; docs/formulation.md, "Augmented Lagrange"), and the least
// penetrating converged solve a step falls back on.
#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"

#include <algorithm>

namespace nmm {

using detail::closed;

bool ContactSystem::augment(Eigen::VectorXd& raw) {
  const double tolerance = options_.penetration_tolerance;
  if (tolerance <= 0.0)
    return false;
  // Converged: no closed contact penetrates by more than the tolerance, and none pushes across
  // a gap wider than it (a multiplier left from a deeper solve).
  const double penetration = max_penetration();
  const bool again = penetration > tolerance ||
                     std::any_of(points_.begin(), points_.end(), [&](const ContactPoint& p) {
                       return closed(p.mode) && p.shift > 0.0 && p.gap - p.offset > tolerance;
                     });
  if (!again)
    return false;
  // The solve to fall back on: of the converged ones, the least penetrating (a pass can close
  // a contact deeper than any before it where the pushes move bodies into others).
  if (has_converged_ && penetration > tolerance && penetration >= converged_penetration_) {
    // The last pass left the deepest contact no shallower: a body squeezed between contacts
    // whose multipliers grow without pushing it out (the 100-block pile: 0.78 mm -> 0.88 mm
    // over four passes while the multiplier grew to 3.4 mm; in the 1000-block pile such
    // passes launched a top-row block 1.1 m up). The step ends on the least penetrating
    // solve.
    back_to_kept(raw);
    return false;
  }
  if (!has_converged_ || penetration < converged_penetration_) {
    save(converged_);
    converged_raw_ = raw;
    converged_penetration_ = penetration;
    has_converged_ = true;
  }
  // Uzawa's update of the multipliers, lambda = max(0, lambda + p x penetration), as lengths
  // (lambda / p): a spring's zero moves by what it penetrates now, back by a gap (Simo and
  // Laursen 1992, eq. 4.6; for DDA Lin et al. 1996). A contact without a bond only pushes:
  // its multiplier stays >= 0. An open contact's goes the same way (to 0 across its gap).
  for (ContactPoint& p : points_) {
    if (!closed(p.mode) && p.shift == 0.0)
      continue;
    const double shift = p.shift + (p.offset - p.gap);
    p.shift = p.bonded ? shift : std::max(0.0, shift);
  }
  return true;
}

bool ContactSystem::back_to_converged(Eigen::VectorXd& raw) {
  // Only a solve that nearly met the tolerance: a deeper one (a landing impact the passes
  // could not hold) is better cut, which shortens the impact's step and so its penetration
  // (docs/formulation.md, "Augmented Lagrange").
  if (!has_converged_ || converged_penetration_ > fallback_depth * options_.penetration_tolerance)
    return false;
  back_to_kept(raw);
  return true;
}

void ContactSystem::back_to_kept(Eigen::VectorXd& raw) {
  restore(converged_);
  raw = converged_raw_;
  has_converged_ = false;
}

double ContactSystem::max_penetration() const {
  double worst = 0.0;
  for (const ContactPoint& p : points_) {
    if (closed(p.mode))
      worst = std::max(worst, p.offset - p.gap);
  }
  return worst;
}

} // namespace nmm
