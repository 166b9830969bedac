// SPDX-License-Identifier: MIT
// contact/joint_law.hpp — the law of a joint's strength, as the open-close iteration asks it
// (docs/formulation.md, "Joint strength"): JointLaw, and Mohr-Coulomb with cohesion and
// tensile strength (MohrCoulombJoint) its first implementation.
#pragma once

#include "contact/contact_point.hpp"

#include <cstddef>
#include <span>
#include <vector>

namespace nmm {

/// What the strength of the surfaces in contact decides: the strength of each boundary edge's
/// surface and whether it is a face of an intact joint, the strength of a contact between two
/// surfaces, the friction and the bond's cohesion of a sliding point, the tension a bond
/// holds, and when an open bond breaks. ContactSystem makes every such decision through this
/// interface, with the resultants of a contact's points summed in its own order (a law only
/// evaluates, so that the sums stay the same whichever law it is). A further law (a
/// Barton-Bandis joint, a softening bond) is another implementation beside MohrCoulombJoint.
class JointLaw {
public:
  virtual ~JointLaw() = default;

  /// Number of boundary edges the law has surfaces for (the model's, loop after loop).
  [[nodiscard]] virtual std::size_t n_surfaces() const = 0;
  /// Strength of the surface of edge @p edge of boundary loop @p loop.
  [[nodiscard]] virtual JointStrength surface(std::size_t loop, std::size_t edge) const = 0;
  /// Whether that surface is a face of an intact joint (bonded until it breaks).
  [[nodiscard]] virtual bool is_bonded(std::size_t loop, std::size_t edge) const = 0;
  /// The strength of a contact between surfaces of strengths @p a and @p b.
  [[nodiscard]] virtual JointStrength contact_strength(const JointStrength& a,
                                                       const JointStrength& b) const = 0;
  /// Shear limit per unit of compressive normal force of point @p p (its friction
  /// coefficient).
  [[nodiscard]] virtual double friction_coefficient(const ContactPoint& p) const = 0;
  /// The shear a bonded point @p p keeps while it slides at its limit, N; 0 unbonded.
  [[nodiscard]] virtual double bond_cohesion(const ContactPoint& p) const = 0;
  /// The tension a bonded point @p p holds before it opens, and keeps pulling with while it
  /// is open (yielded in tension), N; 0 unbonded.
  [[nodiscard]] virtual double bond_tension(const ContactPoint& p) const = 0;
  /// Shear limit of a contact bearing the compressive normal force @p normal (>= 0, N) with
  /// the friction coefficient @p friction and the bonds' cohesion @p cohesion (N), N.
  [[nodiscard]] virtual double
  shear_limit(double normal, double friction, double cohesion) const = 0;
  /// The friction force of a sliding point @p p as its spring pair's load (Shi eq.
  /// 3.27-3.33), from the normal force of the last iteration, N; 0 when the point does not
  /// slide, or has neither friction nor cohesion (no friction term is assembled then).
  [[nodiscard]] virtual double friction_force(const ContactPoint& p) const = 0;
  /// Whether the friction of point @p p follows its normal force alone, with no constant
  /// part (so that it can be coupled to the normal force in the solve).
  [[nodiscard]] virtual bool has_pure_friction(const ContactPoint& p) const = 0;
  /// Whether the bond of an open contact, its points @p points with their gaps after the
  /// step, has yielded in tension: its springs would pull beyond what it holds.
  [[nodiscard]] virtual bool yields_open(std::span<const ContactPoint> points) const = 0;
};

/// @p strength reduced by the factor @p factor (strength reduction, `nmm fos`): friction
/// coefficient tan(phi) / F, cohesion c / F, tensile strength T / F; the joint's stiffnesses
/// unchanged. F = 1 gives @p strength to the bit (the atan of the tan would not).
/// @pre factor > 0.
[[nodiscard]] JointStrength reduced_strength(const JointStrength& strength, double factor);

/// Mohr-Coulomb joints with cohesion and tensile strength: a point
/// slides when its shear exceeds N tan(phi) + c L, a bonded point holds a tension up to
/// t L, and a contact's strength is the weaker of its two surfaces' property by property.
/// An intact joint yields plastically: sliding, a bonded point keeps its cohesion c L, and
/// opened by a pull beyond t L it keeps pulling with t L, until the whole interface has
/// yielded (ContactSystem breaks it then).
class MohrCoulombJoint final : public JointLaw {
public:
  /// @param strength_of_edge  strength of every boundary edge's surface (its joint set's
  ///                          or the [contact] default), indexed by loop then edge.
  /// @param bonded_edge       whether an edge is a face of an intact joint
  MohrCoulombJoint(std::vector<std::vector<JointStrength>> strength_of_edge,
                   std::vector<std::vector<bool>> bonded_edge);

  [[nodiscard]] std::size_t n_surfaces() const override;
  [[nodiscard]] JointStrength surface(std::size_t loop, std::size_t edge) const override;
  [[nodiscard]] bool is_bonded(std::size_t loop, std::size_t edge) const override;
  [[nodiscard]] JointStrength contact_strength(const JointStrength& a,
                                               const JointStrength& b) const override;
  /// tan(phi).
  [[nodiscard]] double friction_coefficient(const ContactPoint& p) const override;
  /// c times the length the point represents.
  [[nodiscard]] double bond_cohesion(const ContactPoint& p) const override;
  /// t times the length the point represents.
  [[nodiscard]] double bond_tension(const ContactPoint& p) const override;
  /// N tan(phi) + c L.
  [[nodiscard]] double shear_limit(double normal, double friction, double cohesion) const override;
  /// N tan(phi) + c L on the normal force of the last iteration when it presses, c L alone
  /// otherwise.
  [[nodiscard]] double friction_force(const ContactPoint& p) const override;
  /// Friction (phi > 0) on an unbonded point.
  [[nodiscard]] bool has_pure_friction(const ContactPoint& p) const override;
  /// The springs' pull, sum of p (gap), beyond the tensile strength, sum of t L.
  [[nodiscard]] bool yields_open(std::span<const ContactPoint> points) const override;

private:
  std::vector<std::vector<JointStrength>> strength_of_edge_;
  std::vector<std::vector<bool>> bonded_edge_;
};

} // namespace nmm
