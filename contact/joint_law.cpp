// SPDX-License-Identifier: MIT
// contact/joint_law.cpp — Mohr-Coulomb joints with cohesion and tensile strength.
#include "contact/joint_law.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace nmm {

JointStrength reduced_strength(const JointStrength& strength, double factor) {
  NMM_ASSERT(factor > 0.0, "a strength reduction factor is > 0");
  if (factor == 1.0)
    return strength;
  JointStrength reduced = strength;
  reduced.friction_angle = std::atan(std::tan(strength.friction_angle) / factor);
  reduced.cohesion = strength.cohesion / factor;
  reduced.tensile_strength = strength.tensile_strength / factor;
  return reduced;
}

MohrCoulombJoint::MohrCoulombJoint(std::vector<std::vector<JointStrength>> strength_of_edge,
                                   std::vector<std::vector<bool>> bonded_edge)
    : strength_of_edge_(std::move(strength_of_edge)), bonded_edge_(std::move(bonded_edge)) {}

std::size_t MohrCoulombJoint::n_surfaces() const {
  std::size_t n = 0;
  for (const auto& loop : strength_of_edge_)
    n += loop.size();
  return n;
}

JointStrength MohrCoulombJoint::surface(std::size_t loop, std::size_t edge) const {
  return strength_of_edge_[loop][edge];
}

bool MohrCoulombJoint::is_bonded(std::size_t loop, std::size_t edge) const {
  return bonded_edge_[loop][edge];
}

JointStrength MohrCoulombJoint::contact_strength(const JointStrength& a,
                                                 const JointStrength& b) const {
  // The softer of the stiffnesses given (0: none given, the penalty).
  const auto softer = [](double x, double y) {
    return x > 0.0 && y > 0.0 ? std::min(x, y) : std::max(x, y);
  };
  return {std::min(a.friction_angle, b.friction_angle), std::min(a.cohesion, b.cohesion),
          std::min(a.tensile_strength, b.tensile_strength),
          softer(a.normal_stiffness, b.normal_stiffness),
          softer(a.shear_stiffness, b.shear_stiffness)};
}

double MohrCoulombJoint::friction_coefficient(const ContactPoint& p) const {
  return std::tan(p.strength.friction_angle);
}

double MohrCoulombJoint::bond_cohesion(const ContactPoint& p) const {
  return p.bonded ? p.strength.cohesion * p.length : 0.0;
}

double MohrCoulombJoint::bond_tension(const ContactPoint& p) const {
  return p.bonded ? p.strength.tensile_strength * p.length : 0.0;
}

double MohrCoulombJoint::shear_limit(double normal, double friction, double cohesion) const {
  return normal * friction + cohesion;
}

double MohrCoulombJoint::friction_force(const ContactPoint& p) const {
  if (p.mode != ContactMode::slide)
    return 0.0;
  const double bond = bond_cohesion(p);
  if (p.normal_force <= 0.0 || p.strength.friction_angle == 0.0)
    return bond;
  return p.normal_force * std::tan(p.strength.friction_angle) + bond;
}

bool MohrCoulombJoint::has_pure_friction(const ContactPoint& p) const {
  return p.strength.friction_angle > 0.0 && !p.bonded;
}

bool MohrCoulombJoint::yields_open(std::span<const ContactPoint> points) const {
  double pull = 0.0;
  double strength = 0.0;
  for (const ContactPoint& p : points) {
    pull += p.stiffness * p.gap;
    strength += p.strength.tensile_strength * p.length;
  }
  return pull > strength;
}

} // namespace nmm
