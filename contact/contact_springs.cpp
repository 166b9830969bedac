// SPDX-License-Identifier: MIT
// contact/contact_springs.cpp — ContactSystem: the normal and shear penalty springs of a
// contact point and its friction loads (Shi 1997, eq. 3.17-3.18, 3.25-3.33), and friction
// coupled to the normal force in the solve.
#include "contact/contact_system.hpp"
#include "contact/detail/contact_support.hpp"
#include "mesh/error.hpp"

#include <cmath>

namespace nmm {

using detail::at;

namespace {

/// m += (s h) h^T, entry (a, b) as (s h(a)) h(b): what Eigen's outer product computes, without
/// its temporary for s h (an allocation for every spring in every open-close iteration); only
/// the upper triangle (a <= b) when @p upper.
void add_outer(Eigen::MatrixXd& m, double s, const Eigen::VectorXd& h, bool upper) {
  const Eigen::Index n = h.size();
  for (Eigen::Index b = 0; b < n; ++b) {
    const double hb = h(b);
    double* column = m.col(b).data();
    const Eigen::Index rows = upper ? b + 1 : n;
    for (Eigen::Index a = 0; a < rows; ++a)
      column[a] += (s * h(a)) * hb;
  }
}

} // namespace

bool ContactSystem::contribution(const Model& model,
                                 int i,
                                 Eigen::MatrixXd* stiffness,
                                 Eigen::VectorXd& load,
                                 bool upper) const {
  const ContactPoint& p = points_[at(i)];
  // One kinematics: its unknowns are point_dofs(i), in that order.
  const Kinematics& k = cached_kinematics(model, p, at(i));
  const Eigen::Index n = static_cast<Eigen::Index>(k.dofs.size());
  if (stiffness != nullptr)
    stiffness->setZero(n, n);
  load.setZero(n);
  const Eigen::VectorXd& hn = k.hn;
  if (p.mode == ContactMode::open) {
    // A bonded point opened by a pull beyond its tensile strength yields plastically: it
    // keeps pulling the two sides together with that strength, t L, as a constant load (the
    // force of a normal spring stretched to it), until its interface has yielded all along
    // and breaks (docs/formulation.md, "Joint strength").
    if (const double tension = law_->bond_tension(p); tension > 0.0)
      load -= tension * hn;
    return false;
  }
  const Eigen::VectorXd& hs = k.hs;
  // Normal spring (Shi eq. 3.17-3.18): energy p/2 g², g = g0 + hn.d.
  if (stiffness != nullptr)
    add_outer(*stiffness, p.stiffness, hn, upper);
  load -= p.stiffness * k.g0 * hn;
  if (p.mode == ContactMode::lock) {
    // Shear spring (eq. 3.25-3.26) anchored at P0.
    if (stiffness != nullptr)
      add_outer(*stiffness, shear_stiffness(p), hs, upper);
    load -= shear_stiffness(p) * k.s0 * hs;
  } else if (friction_coupled(p)) {
    return true; // its friction is in the solve: friction_coupling()
  } else if (const double friction = law_->friction_force(p); friction != 0.0) {
    // Sliding: a pair of friction forces as loads, opposing the sliding (eq. 3.27-3.33),
    // from the normal force of the last iteration so that the matrix stays symmetric. What
    // follows the normal force is friction; a bond's cohesion alone is a constant load.
    load -= static_cast<double>(p.slide_sign) * friction * hs;
    return friction != law_->bond_cohesion(p);
  }
  return false;
}

double ContactSystem::group_stiffness(const Group& g) const {
  double sum = 0.0;
  for (int q = 0; q < g.count; ++q)
    sum += points_[at(g.first + q)].stiffness;
  return sum;
}

std::vector<ContactSystem::FrictionCoupling>
ContactSystem::friction_coupling(const Model& model) const {
  std::vector<FrictionCoupling> coupling;
  for (const Group& g : groups_) {
    const ContactPoint& lead = points_[at(g.first)];
    if (!friction_coupled(lead))
      continue;
    const double placed = group_stiffness(g);
    FrictionCoupling f;
    f.point = g.first;
    f.coef = static_cast<double>(lead.slide_sign) * law_->friction_coefficient(lead);
    const std::vector<int>& dofs = cached_kinematics(model, lead, at(g.first)).dofs;
    f.w.setZero(static_cast<Eigen::Index>(dofs.size()));
    f.a.setZero(f.w.size());
    // The friction of the pair, tan(phi) times the springs' resultant, shared among its points
    // by stiffness as update_modes() shares the normal force.
    for (int q = 0; q < g.count; ++q) {
      const ContactPoint& p = points_[at(g.first + q)];
      const Kinematics& k = cached_kinematics(model, p, at(g.first + q));
      NMM_ASSERT(k.dofs == dofs, "the points of a contact couple the same unknowns");
      f.w += (placed > 0.0 ? p.stiffness / placed : 0.0) * k.hs;
      f.a += p.stiffness * k.hn;
      f.c0 += p.stiffness * k.g0;
    }
    coupling.push_back(std::move(f));
  }
  return coupling;
}

} // namespace nmm
