// SPDX-License-Identifier: MIT
// manifold/exact_rotation.cpp — Model::turn_exactly(): the step's rigid rotation applied
// exactly, as DDA's post-adjustment does, to the VEM blocks and the NMM blocks whose material
// has `exact_rotation` (docs/formulation.md, "VEM block: exact rotation" and "NMM blocks:
// exact rotation").
#include "manifold/model.hpp"
#include "manifold/simplex_integration.hpp"

#include <Eigen/Geometry>

#include <vector>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// R(r) - I - r J, J = [[0, -1], [1, 0]] the quarter turn: what the linear step r J (x - c)
/// of a rotation by r leaves out, second order in r.
Eigen::Matrix2d rotation_rest(double r) {
  Eigen::Matrix2d rest = Eigen::Rotation2Dd(r).toRotationMatrix() - Eigen::Matrix2d::Identity();
  rest(0, 1) += r;
  rest(1, 0) -= r;
  return rest;
}

void turn_vem_blocks(const Model& model, Eigen::VectorXd& raw, Eigen::VectorXd& velocity) {
  Eigen::VectorXd values;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ModelElement& element = model.elements[at(e)];
    if (element.kind != ElementKind::vem || !model.material_of(e).exact_rotation)
      continue;
    const ElementShape s = model.shape(e);
    const VemShape& vem = *s.vem();
    model.element_values(e, raw, values);
    const double r0 = vem.rotation({values.data(), static_cast<std::size_t>(values.size())});
    if (r0 == 0.0)
      continue;
    const Point2 centre = centroid(element.polygons);
    const Eigen::Matrix2d turn = Eigen::Rotation2Dd(r0).toRotationMatrix();
    const Eigen::Matrix2d rest = rotation_rest(r0);
    // The centroid's velocity: that of the projection, whose mean over the block is its value
    // at the centroid (the block's momentum over its mass: (I - P_u) has no resultant).
    model.element_values(e, velocity, values);
    const Point2 centre_velocity =
        vem.displacement_at(centre, {values.data(), static_cast<std::size_t>(values.size())});
    for (int k = 0; k < vem.n_vertices(); ++k) {
      const auto u = static_cast<Eigen::Index>(element.dofs[at(2 * k)]);
      const auto v = static_cast<Eigen::Index>(element.dofs[at(2 * k + 1)]);
      const Point2 step = rest * (vem.vertices()[at(k)] - centre);
      raw(u) += step.x();
      raw(v) += step.y();
      const Point2 relative = turn * (Point2(velocity(u), velocity(v)) - centre_velocity);
      velocity(u) = centre_velocity.x() + relative.x();
      velocity(v) = centre_velocity.y() + relative.y();
    }
  }
}

/// One NMM block's rigid part of the step: mass-weighted sums over its elements.
struct BlockMotion {
  bool turns = false;
  bool started = false;
  Point2 reference = Point2::Zero(); ///< of the first moments (accurate far from 0)
  double mass = 0.0;                 ///< ∫ρ t
  Point2 first = Point2::Zero();     ///< ∫ρ t (x - reference)
  double rotation = 0.0;             ///< Σ m_e r_e, r_e the element's rotation at its origin
  Point2 momentum = Point2::Zero();  ///< ∫ρ t v
};

/// The sums of BlockMotion for every block that has an NMM element of an `exact_rotation`
/// material; empty when there is none.
std::vector<BlockMotion>
block_motions(const Model& model, const Eigen::VectorXd& raw, const Eigen::VectorXd& velocity) {
  std::vector<BlockMotion> motions(model.blocks.size());
  bool any = false;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ModelElement& element = model.elements[at(e)];
    if (element.kind == ElementKind::nmm && model.material_of(e).exact_rotation)
      any = motions[at(element.block)].turns = true;
  }
  if (!any)
    return {};
  Eigen::VectorXd values;
  Eigen::VectorXd body_x;
  Eigen::VectorXd body_y;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ModelElement& element = model.elements[at(e)];
    BlockMotion& motion = motions[at(element.block)];
    if (element.kind != ElementKind::nmm || !motion.turns || element.polygons.empty())
      continue;
    if (!motion.started) {
      motion.started = true;
      motion.reference = element.polygons.front().outer.front();
    }
    // Mass per area; a material without density (a static analysis without gravity) by area.
    const ElasticMaterial& material = model.material_of(e);
    const double weight =
        material.thickness_factor() * (material.density > 0.0 ? material.density : 1.0);
    Moments2 moments(1, motion.reference);
    for (const Polygon& polygon : element.polygons)
      moments += polygon_moments(polygon, 1, motion.reference);
    const double mass = weight * moments.area();
    motion.mass += mass;
    motion.first += weight * Point2(moments(1, 0), moments(0, 1));
    const ElementShape shape = model.shape(e);
    model.element_values(e, raw, values);
    motion.rotation +=
        mass * shape.rotation({values.data(), static_cast<std::size_t>(values.size())});
    model.element_values(e, velocity, values);
    if (values.isZero())
      continue;
    // ∫ρ t v of the element's field: its body-force vectors of a unit force per volume.
    const ElementIntegrals integrals(shape, element.polygons);
    integrals.loads(Point2(1.0, 0.0), LinearField3{}, weight, body_x);
    integrals.loads(Point2(0.0, 1.0), LinearField3{}, weight, body_y);
    motion.momentum += Point2(body_x.dot(values), body_y.dot(values));
  }
  return motions;
}

/// The NMM blocks of `exact_rotation` materials turn by the mass-weighted mean rotation r of
/// their elements in the step about their centre of mass c, exactly: each NMM cover's
/// function gets the affine field (R(r) - I - r J)(x - c), which the cover functions
/// reproduce exactly (order 0: the barycentric weights are linear; order 1: value
/// (R - I - r J)(x_k - c) and gradient (R - I - r J) L), so that every point of a block moving
/// rigidly is turned by R(r) about c. The velocity field turns with the block about the
/// velocity of the centre of mass v_c: v <- v_c + R (v - v_c) at each cover, and an order-1
/// cover's velocity gradient G <- R G R^T (the field seen from the turned geometry).
void turn_nmm_blocks(const Model& model, Eigen::VectorXd& raw, Eigen::VectorXd& velocity) {
  const std::vector<BlockMotion> motions = block_motions(model, raw, velocity);
  if (motions.empty())
    return;
  struct Turn {
    bool turns = false;
    Point2 centre = Point2::Zero();
    Point2 centre_velocity = Point2::Zero();
    Eigen::Matrix2d turn = Eigen::Matrix2d::Identity();
    Eigen::Matrix2d rest = Eigen::Matrix2d::Zero();
  };
  std::vector<Turn> turns(motions.size());
  for (std::size_t b = 0; b < motions.size(); ++b) {
    const BlockMotion& m = motions[b];
    if (!m.turns || !(m.mass > 0.0) || m.rotation == 0.0)
      continue;
    const double r = m.rotation / m.mass;
    turns[b] = {true, m.reference + m.first / m.mass, m.momentum / m.mass,
                Eigen::Rotation2Dd(r).toRotationMatrix(), rotation_rest(r)};
  }
  for (int c = 0; c < model.n_covers(); ++c) {
    const ModelCover& cover = model.covers[at(c)];
    if (cover.kind != ElementKind::nmm || cover.block < 0 || !turns[at(cover.block)].turns)
      continue;
    const Turn& t = turns[at(cover.block)];
    const int d = cover.first_dof;
    const Point2 step = t.rest * (cover.position - t.centre);
    raw(d) += step.x();
    raw(d + 1) += step.y();
    const Point2 relative = t.turn * (Point2(velocity(d), velocity(d + 1)) - t.centre_velocity);
    velocity(d) = t.centre_velocity.x() + relative.x();
    velocity(d + 1) = t.centre_velocity.y() + relative.y();
    if (cover.n_dofs < 6)
      continue;
    // Order 1: unknowns 2, 3 are L d(u, v)/dx, unknowns 4, 5 are L d(u, v)/dy.
    raw(d + 2) += t.rest(0, 0) * model.scale;
    raw(d + 3) += t.rest(1, 0) * model.scale;
    raw(d + 4) += t.rest(0, 1) * model.scale;
    raw(d + 5) += t.rest(1, 1) * model.scale;
    Eigen::Matrix2d gradient;
    gradient << velocity(d + 2), velocity(d + 4), velocity(d + 3), velocity(d + 5);
    gradient = t.turn * gradient * t.turn.transpose();
    velocity(d + 2) = gradient(0, 0);
    velocity(d + 3) = gradient(1, 0);
    velocity(d + 4) = gradient(0, 1);
    velocity(d + 5) = gradient(1, 1);
  }
}

} // namespace

void Model::turn_exactly(Eigen::VectorXd& raw, Eigen::VectorXd& velocity) const {
  turn_vem_blocks(*this, raw, velocity);
  turn_nmm_blocks(*this, raw, velocity);
}

} // namespace nmm
