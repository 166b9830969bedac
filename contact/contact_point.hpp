// SPDX-License-Identifier: MIT
// contact/contact_point.hpp — one contact point with its state in the open-close iteration
// (Shi 1997, 3.3-3.6 and 8.2), and the strength of the surfaces it joins.
#pragma once

#include "mesh/geometry.hpp"

#include <cstdint>

namespace nmm {

/// Mohr-Coulomb strength of a joint or a contact surface, and its own spring stiffness.
struct JointStrength {
  double friction_angle = 0.0;   ///< radians, in [0, pi/2)
  double cohesion = 0.0;         ///< Pa
  double tensile_strength = 0.0; ///< Pa
  /// The joint's normal and shear stiffness per unit length of contact (`normal_stiffness`,
  /// `shear_stiffness`), Pa/m; 0: the penalty (ContactOptions). Edge-to-edge contacts take
  /// them per unit of the length they represent, as a Goodman joint element of that
  /// stiffness (Riahi et al., eq. 21 and 43); angle contacts keep the penalty.
  double normal_stiffness = 0.0;
  double shear_stiffness = 0.0;
};

/// The three contact modes of Shi's open-close iteration (1997, 8.2).
enum class ContactMode : std::uint8_t { open, slide, lock };

/// One contact point: an angle against its entrance line, or one Gauss point of an
/// edge-to-edge pair, with its own state.
struct ContactPoint {
  std::uint64_t key = 0;         ///< identity of the contact (ContactCandidate::key)
  int slave_edge = -1;           ///< the edge (element) the slave point moves with
  Point2 slave = Point2::Zero(); ///< slave point at the start of the step
  /// Edge-to-edge: position of the slave point on its edge (0 at its first vertex, 1 at the
  /// next); the same material point from step to step.
  double u = 0.0;
  int master = -1;        ///< master edge (entrance line)
  double length = 0.0;    ///< tributary length for strengths and integrated stiffness, m
  double stiffness = 0.0; ///< normal spring stiffness, N/m
  /// Shear over normal spring stiffness: 1 but where a joint's own stiffnesses differ.
  double shear_ratio = 1.0;
  JointStrength strength; ///< of the pair (the weaker of the two sides)
  bool bonded = false;    ///< intact joint: holds tension and cohesion until it breaks
  ContactMode mode = ContactMode::open;
  /// Contact position on the master edge's line (parameter: 0 at its first vertex, 1 at the
  /// next; beyond them when the slave has moved past an end) where the shear spring of a
  /// locked contact is anchored (Shi 3.5, P0), carried to the next step.
  double anchor = 0.0;
  /// Sliding direction along the master edge (+1, -1).
  int slide_sign = 0;
  int flips = 0;             ///< open/closed switches in this step (chatter rule)
  int slips = 0;             ///< lock/slide switches in this step (chatter rule)
  double normal_force = 0.0; ///< compressive positive, N
  double shear_force = 0.0;  ///< along the master edge, N
  double gap = 0.0;          ///< normal gap at the end of the last solve (negative: penetration)
  /// Angle contacts: the gap at which the normal spring starts to push (<= 0). A contact that
  /// appears already penetrating, because the contact it replaces had softer springs (a
  /// face that turned past the angle criterion: edge-to-edge springs on a short pressed part
  /// let a corner sink in hundreds of times deeper than a point spring would), takes that
  /// penetration as its springs' zero instead of throwing the bodies apart. It rises with
  /// the gap once the contact opens, and is 0 for everything that meets in the ordinary
  /// way. The springs push with p (offset + shift - gap).
  double offset = 0.0;
  /// The springs' zero moved into the bodies, m: at the start of every step the
  /// pre-compression of a contact across a joint under initial stress (the in-situ normal
  /// traction times the point's length over its stiffness, so that the springs carry that
  /// traction at zero gap: docs/formulation.md, "In-situ stress"), 0 for any other contact;
  /// then the augmented-Lagrange multiplier over the spring stiffness (ContactOptions::
  /// penetration_tolerance) added: the springs' zero moved by the penetrations of the step's
  /// earlier solves, so that they push with the force the multiplier carries plus p times
  /// the penetration left; it decides opening and closing as the springs' force does (an open
  /// contact's falls back by its gap at the next pass). Multipliers are not carried to the
  /// next step (as Lin et al. do, that pushed landing blocks off again: docs/formulation.md,
  /// "Augmented Lagrange").
  double shift = 0.0;
};

/// The shear spring stiffness of @p p, N/m.
[[nodiscard]] inline double shear_stiffness(const ContactPoint& p) noexcept {
  return p.stiffness * p.shear_ratio;
}

} // namespace nmm
