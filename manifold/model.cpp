// SPDX-License-Identifier: MIT
#include "manifold/model.hpp"

#include "manifold/simplex_integration.hpp"
#include "mesh/error.hpp"
#include "mesh/union_find.hpp"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <span>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Crossing-number test, with points on an edge counted inside.
bool contains(const Loop& loop, const Point2& p) {
  bool inside = false;
  for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
    const Point2& a = loop[i];
    const Point2& b = loop[j];
    if ((a.y() > p.y()) != (b.y() > p.y())) {
      const double x = a.x() + (p.y() - a.y()) * (b.x() - a.x()) / (b.y() - a.y());
      if (p.x() < x)
        inside = !inside;
    }
  }
  return inside;
}

double distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double distance_to_polygon(const Polygon& polygon, const Point2& p) {
  double best = std::numeric_limits<double>::infinity();
  auto visit = [&](const Loop& loop) {
    for (std::size_t i = 0; i < loop.size(); ++i)
      best = std::min(best, distance_to_segment(p, loop[i], loop[(i + 1) % loop.size()]));
  };
  visit(polygon.outer);
  for (const Loop& hole : polygon.holes)
    visit(hole);
  return best;
}

bool polygon_contains(const Polygon& polygon, const Point2& p) {
  if (polygon.outer.size() < 3 || !contains(polygon.outer, p))
    return false;
  for (const Loop& hole : polygon.holes) {
    if (contains(hole, p))
      return false;
  }
  return true;
}

/// J v: v turned by 90 degrees.
Point2 turned(const Point2& v) { return {-v.y(), v.x()}; }

} // namespace

std::array<Point2, 3> Model::triangle(int element) const {
  const auto& c = elements[at(element)].covers;
  NMM_ASSERT(c.size() == 3, "triangle() of an element that is not an NMM element");
  return {covers[at(c[0])].position, covers[at(c[1])].position, covers[at(c[2])].position};
}

NmmShape Model::nmm_shape(int element) const { return NmmShape(triangle(element), order, scale); }

ElementShape Model::shape(int element) const {
  const ModelElement& e = elements[at(element)];
  switch (e.kind) {
  case ElementKind::dda:
    return ElementShape(DdaShape(covers[at(e.covers.front())].position));
  case ElementKind::vem:
    return ElementShape(VemShape(e.polygons));
  case ElementKind::nmm:
    break;
  }
  return ElementShape(nmm_shape(element));
}

int Model::cover_of_dof(int dof) const {
  const auto it = std::upper_bound(covers.begin(), covers.end(), dof,
                                   [](int d, const ModelCover& c) { return d < c.first_dof; });
  NMM_ASSERT(it != covers.begin(), "dof index out of range");
  return static_cast<int>(it - covers.begin()) - 1;
}

void Model::number_dofs() {
  n_dofs_ = 0;
  for (ModelCover& cover : covers) {
    if (cover.n_dofs == 0)
      cover.n_dofs = cover.kind == ElementKind::dda   ? dda_block_dofs
                     : cover.kind == ElementKind::vem ? 2
                                                      : dofs_per_cover();
    cover.first_dof = n_dofs_;
    n_dofs_ += cover.n_dofs;
  }
  for (ModelElement& element : elements) {
    element.dofs.clear();
    for (const int c : element.covers) {
      for (int j = 0; j < covers[at(c)].n_dofs; ++j)
        element.dofs.push_back(dof(c, j));
    }
  }
}

Eigen::VectorXd Model::element_values(int element, const Eigen::VectorXd& raw) const {
  Eigen::VectorXd values;
  element_values(element, raw, values);
  return values;
}

void Model::element_values(int element, const Eigen::VectorXd& raw, Eigen::VectorXd& out) const {
  const std::span<const int> dofs = element_dofs(element);
  out.resize(static_cast<Eigen::Index>(dofs.size()));
  for (std::size_t i = 0; i < dofs.size(); ++i)
    out(static_cast<Eigen::Index>(i)) = raw(dofs[i]);
}

Point2 Model::element_origin(int element) const {
  const ModelElement& e = elements[at(element)];
  switch (e.kind) {
  case ElementKind::dda:
    return covers[at(e.covers.front())].position;
  case ElementKind::vem:
    return shape(element).origin();
  case ElementKind::nmm:
    break;
  }
  const auto t = triangle(element);
  return (t[0] + t[1] + t[2]) / 3.0;
}

Point2 Model::displacement(int element, const Point2& x, const Eigen::VectorXd& raw) const {
  const Eigen::VectorXd values = element_values(element, raw);
  return shape(element).displacement_at(x,
                                        {values.data(), static_cast<std::size_t>(values.size())});
}

int Model::find_element(const Point2& x, double tolerance) const {
  int nearest = -1;
  double nearest_distance = tolerance;
  for (int e = 0; e < n_elements(); ++e) {
    for (const Polygon& polygon : elements[at(e)].polygons) {
      if (polygon_contains(polygon, x))
        return e;
      const double d = distance_to_polygon(polygon, x);
      if (d <= nearest_distance) {
        nearest_distance = d;
        nearest = e;
      }
    }
  }
  return nearest;
}

std::vector<LinearConstraint> Model::extension_relations() const {
  std::vector<LinearConstraint> relations;
  for (int c = 0; c < n_covers(); ++c) {
    const ModelCover& cover = covers[at(c)];
    if (cover.extension_element < 0)
      continue;
    const int root = cover.extension_element;
    const NmmShape root_shape = nmm_shape(root);
    const std::span<const int> root_dofs = element_dofs(root);
    const ShapeVector phi = root_shape.values_at(cover.position);
    const std::string origin = "tiny cover of math node " + std::to_string(cover.node);
    for (int component = 0; component < 2; ++component) {
      LinearConstraint value;
      value.origin = origin;
      value.preferred_slave = dof(c, component);
      value.terms.emplace_back(dof(c, component), 1.0);
      for (int a = 0; a < root_shape.n_shapes(); ++a)
        value.terms.emplace_back(root_dofs[at(2 * a + component)], -phi(a));
      relations.push_back(std::move(value));
    }
    if (order == 0)
      continue;
    // The gradient: the root's covers' gradients, affinely extrapolated to the tiny cover's
    // node with the barycentric coordinates of x_c in the root's math triangle. Gradients
    // that are affine in the node (a quadratic field's representation, a flex of the order-1
    // dependence) are continued exactly, so quadratics stay representable and the flexes
    // stay combinations of no displacement (docs/cover-mesher.md, "Tiny pieces").
    const std::vector<int>& root_covers = elements[at(root)].covers;
    const std::array<Point2, 3> node = triangle(root);
    Eigen::Matrix2d edges;
    edges << node[1] - node[0], node[2] - node[0];
    const Eigen::Vector2d tail = edges.partialPivLu().solve(cover.position - node[0]);
    const std::array<double, 3> barycentric{1.0 - tail.sum(), tail(0), tail(1)};
    for (int gradient = 2; gradient < 6; ++gradient) {
      LinearConstraint relation;
      relation.origin = origin;
      relation.preferred_slave = dof(c, gradient);
      relation.terms.emplace_back(dof(c, gradient), 1.0);
      for (int k = 0; k < 3; ++k)
        relation.terms.emplace_back(dof(root_covers[at(k)], gradient), -barycentric[at(k)]);
      relations.push_back(std::move(relation));
    }
  }
  return relations;
}

std::vector<LinearConstraint> Model::dependency_relations() const {
  std::vector<LinearConstraint> relations;
  if (order == 0)
    return relations;
  // NMM elements of each block (DDA and VEM blocks have no dependency).
  std::map<int, std::vector<int>> block_elements;
  for (int e = 0; e < n_elements(); ++e) {
    if (elements[at(e)].kind == ElementKind::nmm && !elements[at(e)].excavated)
      block_elements[elements[at(e)].block].push_back(e);
  }
  for (const auto& [block, members] : block_elements) {
    // Rigid clusters: elements sharing two covers (a side of their triangles).
    UnionFind clusters(members.size());
    std::map<std::pair<int, int>, int> first_with_side;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const auto& c = elements[at(members[i])].covers;
      for (int k = 0; k < 3; ++k) {
        const int a = c[at(k)];
        const int b = c[at((k + 1) % 3)];
        const auto [it, fresh] = first_with_side.emplace(
            std::make_pair(std::min(a, b), std::max(a, b)), static_cast<int>(i));
        if (!fresh)
          clusters.unite(it->second, static_cast<int>(i));
      }
    }
    std::map<int, int> cluster_index;
    std::vector<Point2> cluster_reference;
    std::map<int, std::vector<int>> clusters_of_cover;
    for (std::size_t i = 0; i < members.size(); ++i) {
      const int root = clusters.find(static_cast<int>(i));
      auto [it, fresh] = cluster_index.emplace(root, static_cast<int>(cluster_reference.size()));
      if (fresh)
        cluster_reference.push_back(covers[at(elements[at(members[i])].covers[0])].position);
      for (const int c : elements[at(members[i])].covers) {
        auto& list = clusters_of_cover[c];
        if (std::find(list.begin(), list.end(), it->second) == list.end())
          list.push_back(it->second);
      }
    }
    // Gradient g_c of the flex at cover c seen from cluster k: g0 + s J (x_c - ref_k) / L.
    const int n_clusters = static_cast<int>(cluster_reference.size());
    auto gradient_row = [&](int c, int k, int axis) {
      Eigen::RowVectorXd row = Eigen::RowVectorXd::Zero(3 * n_clusters);
      const Point2 j = turned((covers[at(c)].position - cluster_reference[at(k)]) / scale);
      row(3 * k + axis) = 1.0;
      row(3 * k + 2) = axis == 0 ? j.x() : j.y();
      return row;
    };
    std::vector<Eigen::RowVectorXd> rows;
    for (const auto& [c, list] : clusters_of_cover) {
      for (int axis = 0; axis < 2; ++axis) {
        for (std::size_t k = 1; k < list.size(); ++k)
          rows.push_back(gradient_row(c, list[0], axis) - gradient_row(c, list[k], axis));
      }
    }
    // Null space of the cluster equations: the flexes.
    Eigen::MatrixXd flexes;
    if (rows.empty()) {
      flexes = Eigen::MatrixXd::Identity(3 * n_clusters, 3 * n_clusters);
    } else {
      Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), 3 * n_clusters);
      for (std::size_t r = 0; r < rows.size(); ++r)
        a.row(static_cast<Eigen::Index>(r)) = rows[r];
      const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullV);
      const Eigen::VectorXd& sigma = svd.singularValues();
      const double largest = sigma.size() > 0 ? sigma(0) : 0.0;
      int rank = 0;
      for (Eigen::Index i = 0; i < sigma.size(); ++i)
        rank += sigma(i) > 1e-10 * largest;
      flexes = svd.matrixV().rightCols(3 * n_clusters - rank);
    }
    if (flexes.cols() == 0)
      continue;
    // The flexes as gradients at the free covers, and the unknowns that pin them down.
    std::vector<int> free_covers;
    for (const auto& [c, list] : clusters_of_cover) {
      if (covers[at(c)].extension_element < 0)
        free_covers.push_back(c);
    }
    Eigen::MatrixXd g(flexes.cols(), static_cast<Eigen::Index>(2 * free_covers.size()));
    for (std::size_t i = 0; i < free_covers.size(); ++i) {
      const int c = free_covers[i];
      const int k = clusters_of_cover.at(c)[0];
      for (int axis = 0; axis < 2; ++axis)
        g.col(static_cast<Eigen::Index>(2 * i) + axis) =
            (gradient_row(c, k, axis) * flexes).transpose();
    }
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(g);
    for (Eigen::Index f = 0; f < qr.rank(); ++f) {
      const Eigen::Index column = qr.colsPermutation().indices()(f);
      const int c = free_covers[at(static_cast<int>(column / 2))];
      const int axis = static_cast<int>(column % 2);
      for (int component = 0; component < 2; ++component) {
        LinearConstraint fix;
        fix.origin = "order-1 dependency in block " + std::to_string(block);
        fix.terms.emplace_back(dof(c, 2 + 2 * axis + component), 1.0);
        fix.preferred_slave = fix.terms.front().first;
        relations.push_back(std::move(fix));
      }
    }
  }
  return relations;
}

namespace {

/// Rotates every coefficient tensor of a linear stress field by the angle @p omega, and the
/// field's spatial argument with it (sigma'(x') = R sigma(R^T x') R^T).
LinearField3 rotated(const LinearField3& field, double omega) {
  const double c = std::cos(omega);
  const double s = std::sin(omega);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  auto tensor = [](const Eigen::Vector3d& v) {
    Eigen::Matrix2d t;
    t << v(0), v(2), v(2), v(1);
    return t;
  };
  auto vector = [](const Eigen::Matrix2d& t) { return Eigen::Vector3d(t(0, 0), t(1, 1), t(0, 1)); };
  LinearField3 result;
  result.origin = field.origin;
  result.coefficients.col(0) = vector(r * tensor(field.coefficients.col(0)) * r.transpose());
  for (int j = 0; j < 2; ++j) {
    const Eigen::Matrix2d mixed =
        r(j, 0) * tensor(field.coefficients.col(1)) + r(j, 1) * tensor(field.coefficients.col(2));
    result.coefficients.col(1 + j) = vector(r * mixed * r.transpose());
  }
  return result;
}

} // namespace

void Model::accumulate_stress(const Eigen::VectorXd& raw) {
  Eigen::VectorXd values;
  for (int e = 0; e < n_elements(); ++e) {
    ModelElement& element = elements[at(e)];
    if (element.excavated)
      continue;
    const ElementShape s = shape(e);
    element_values(e, raw, values);
    const std::span<const double> d(values.data(), static_cast<std::size_t>(values.size()));
    const LinearField3 strain = s.strain(d);
    const double rotation = s.rotation(d);
    const Eigen::Matrix3d elasticity = elasticity_matrix(material_of(e));
    LinearField3 stress = rotated(element.stress.about(s.origin()), rotation);
    stress.coefficients += elasticity * strain.coefficients;
    element.stress = stress;
    if (const VemShape* vem = s.vem()) {
      // The stabilisation force is carried like the stress (docs/formulation.md, "VEM
      // block"): its vertex forces turn with the block's rigid rotation of the step, the
      // same angle as the stress, then the step's eta_E (I - P_u)^T (I - P_u) d (VEM-DDA
      // paper eq. 49) is added, with the shape of the start of the step, as in the stiffness
      // the step was solved with.
      Eigen::VectorXd& force = element.stabilisation_force;
      if (force.size() == 0) {
        force = Eigen::VectorXd::Zero(vem->n_dofs());
      } else if (rotation != 0.0) {
        Eigen::Map<Eigen::Matrix2Xd> vertex_forces(force.data(), 2, force.size() / 2);
        vertex_forces = Eigen::Rotation2Dd(rotation).toRotationMatrix() * vertex_forces;
      }
      force += vem->stabilisation_force(elasticity, material_of(e).thickness_factor(), d);
    }
  }
}

void Model::move(const Eigen::VectorXd& raw, std::vector<MaterialPoint>& points) {
  NMM_ASSERT(raw.size() == n_dofs(), "wrong size of the displacement vector");
  // Everything is evaluated with the shapes of the start of the step, so covers move last.
  // Consecutive boundary points mostly share an element: its shape is built once for them.
  int cached = -1;
  std::optional<ElementShape> cached_shape;
  Eigen::VectorXd cached_values;
  auto moved = [&](int e, const Point2& x) {
    if (e != cached) {
      cached = e;
      cached_shape.emplace(shape(e));
      element_values(e, raw, cached_values);
    }
    return cached_shape->moved(
        x, {cached_values.data(), static_cast<std::size_t>(cached_values.size())});
  };
  for (BoundaryLoop& loop : loops) {
    for (std::size_t k = 0; k < loop.vertices.size(); ++k) {
      const int e = loop.edges[k].element;
      if (e >= 0)
        loop.vertices[k] = moved(e, loop.vertices[k]);
    }
  }
  for (auto& pieces : curve_pieces) {
    for (CurvePiece& piece : pieces) {
      const int e = piece.left_element >= 0 ? piece.left_element : piece.right_element;
      if (e >= 0) {
        piece.a = moved(e, piece.a);
        piece.b = moved(e, piece.b);
      }
    }
  }
  for (MaterialPoint& point : points) {
    if (point.element >= 0)
      point.position = moved(point.element, point.position);
  }
  // Element polygons last: a VEM block's shape is built from them.
  for (int e = 0; e < n_elements(); ++e) {
    ModelElement& element = elements[at(e)];
    CompensatedSum area_sum;
    for (Polygon& polygon : element.polygons) {
      for (Point2& p : polygon.outer)
        p = moved(e, p);
      for (Loop& hole : polygon.holes) {
        for (Point2& p : hole)
          p = moved(e, p);
      }
      area_sum += area(polygon);
    }
    element.area = area_sum.value();
  }
  // A cover moves with its cover function at its own position: its first two unknowns (for
  // a DDA block, whose position is its centroid, the same as its exact update).
  for (int c = 0; c < n_covers(); ++c)
    covers[at(c)].position += Point2(raw(dof(c, 0)), raw(dof(c, 1)));
  // The stress field is attached to the material: its origin (the shape's origin, see
  // accumulate_stress()) moves with the element, its coefficients stay.
  for (int e = 0; e < n_elements(); ++e)
    elements[at(e)].stress.origin = element_origin(e);
}

double Model::largest_displacement(const Eigen::VectorXd& raw) const {
  double largest = 0.0;
  for (int c = 0; c < n_covers(); ++c)
    largest = std::max(largest, Point2(raw(dof(c, 0)), raw(dof(c, 1))).norm());
  // A DDA block's vertices also turn about its centroid.
  for (int e = 0; e < n_elements(); ++e) {
    const ModelElement& element = elements[at(e)];
    if (element.kind != ElementKind::dda)
      continue;
    const double r = std::abs(raw(dof(element.covers.front(), 2)));
    if (r == 0.0)
      continue;
    const DdaShape s(covers[at(element.covers.front())].position);
    const Eigen::VectorXd values = element_values(e, raw);
    const std::span<const double> d(values.data(), static_cast<std::size_t>(values.size()));
    for (const Polygon& polygon : element.polygons) {
      for (const Point2& p : polygon.outer)
        largest = std::max(largest, (s.moved(p, d) - p).norm());
    }
  }
  return largest;
}

void Model::set_rigid_motion(
    int cover, const Point2& v0, double omega, const Point2& c, Eigen::VectorXd& raw) const {
  const ModelCover& mc = covers[at(cover)];
  const Point2 r = mc.position - c;
  raw(dof(cover, 0)) = v0.x() - omega * r.y();
  raw(dof(cover, 1)) = v0.y() + omega * r.x();
  if (mc.kind == ElementKind::dda) {
    raw(dof(cover, 2)) = omega;
    for (int j = 3; j < dda_block_dofs; ++j)
      raw(dof(cover, j)) = 0.0;
  } else if (mc.kind == ElementKind::nmm && order > 0) {
    raw(dof(cover, 2)) = 0.0;
    raw(dof(cover, 3)) = omega * scale;  // dv/dx L
    raw(dof(cover, 4)) = -omega * scale; // du/dy L
    raw(dof(cover, 5)) = 0.0;
  }
}

namespace {

/// The material's initial stress as an element's stress field about @p origin: the constant
/// part at the origin's height, the linear part -d sigma / d depth along y (an `[in_situ]`
/// field growing with depth, ElasticMaterial::initial_stress_gradient). Exact in every
/// element kind: each integrates the field's linear part in its initial-stress load.
LinearField3 initial_stress_field(const ElasticMaterial& material, const Point2& origin) {
  LinearField3 field;
  field.origin = origin;
  field.coefficients.col(0) = material.initial_stress_at(origin.y());
  if (!material.initial_stress_gradient.isZero())
    field.coefficients.col(2) = -material.initial_stress_gradient;
  return field;
}

/// One DDA or VEM element per block of a special region (the blocks without NMM elements),
/// with its cover(s); the block's loop edges and curve pieces point at it.
void add_block_elements(Model& model, const std::vector<ElementKind>& region_kinds) {
  std::vector<int> element_of_block(model.blocks.size(), -1);
  for (std::size_t b = 0; b < model.blocks.size(); ++b) {
    const Block& block = model.blocks[b];
    if (!block.elements.empty() || block.materials.empty())
      continue;
    const int material = block.materials.front();
    const ElementKind kind =
        at(material) < region_kinds.size() ? region_kinds[at(material)] : ElementKind::nmm;
    if (kind == ElementKind::nmm)
      continue;
    // The block's polygon: its counter-clockwise loop is the outer boundary, the others holes.
    Polygon polygon;
    for (const int l : block.loops) {
      const Loop& loop = model.loops[at(l)].vertices;
      if (signed_area(loop) > 0.0 && polygon.outer.empty())
        polygon.outer = loop;
      else
        polygon.holes.push_back(loop);
    }
    const ElasticMaterial& m = model.materials[at(material)];
    const Point2 somewhere = block.loops.empty()
                                 ? Point2::Zero()
                                 : model.loops[at(block.loops.front())].vertices.front();
    const double block_area = polygon.outer.size() >= 3 ? area(polygon) : 0.0;
    if (polygon.outer.size() < 3 || !(block_area > 0.0)) {
      // No loop with a positive area: name the vertices of the block's first loop.
      const std::size_t n_vertices = !polygon.outer.empty() || block.loops.empty()
                                         ? polygon.outer.size()
                                         : model.loops[at(block.loops.front())].vertices.size();
      std::ostringstream area_text;
      area_text.precision(3);
      area_text << block_area;
      throw InputError("a block of the " + std::string(kind == ElementKind::dda ? "dda" : "vem") +
                       " material \"" + m.name + "\" near " + point_text(somewhere, 6) + " has " +
                       std::to_string(n_vertices) + " vertices and an area of " + area_text.str() +
                       " m² after cutting: a block needs three vertices and an area; check the "
                       "joints that cut it out (two joints nearly on top of each other leave "
                       "such slivers)");
    }
    ModelElement element;
    element.kind = kind;
    element.material = material;
    element.block = static_cast<int>(b);
    element.area = block_area;
    element.polygons = {polygon};
    ModelCover cover;
    cover.kind = kind;
    cover.block = static_cast<int>(b);
    if (kind == ElementKind::dda) {
      cover.position = centroid(element.polygons);
      element.covers.push_back(model.n_covers());
      model.covers.push_back(cover);
    } else {
      auto add_vertices = [&](const Loop& loop) {
        for (const Point2& p : loop) {
          cover.position = p;
          element.covers.push_back(model.n_covers());
          model.covers.push_back(cover);
        }
      };
      add_vertices(polygon.outer);
      for (const Loop& hole : polygon.holes)
        add_vertices(hole);
    }
    element_of_block[b] = model.n_elements();
    model.elements.push_back(std::move(element));
    model.blocks[b].elements.push_back(element_of_block[b]);
  }
  for (int e = 0; e < model.n_elements(); ++e) {
    if (model.elements[at(e)].kind != ElementKind::nmm)
      model.elements[at(e)].stress =
          initial_stress_field(model.material_of(e), model.element_origin(e));
  }
  for (BoundaryLoop& loop : model.loops) {
    const int e = element_of_block[at(loop.block)];
    if (e < 0)
      continue;
    for (BoundaryEdge& edge : loop.edges)
      edge.element = e;
  }
  for (auto& pieces : model.curve_pieces) {
    for (CurvePiece& piece : pieces) {
      if (piece.left_block >= 0 && element_of_block[at(piece.left_block)] >= 0)
        piece.left_element = element_of_block[at(piece.left_block)];
      if (piece.right_block >= 0 && element_of_block[at(piece.right_block)] >= 0)
        piece.right_element = element_of_block[at(piece.right_block)];
    }
  }
}

} // namespace

Model make_model(const CoverSystem& cover_system,
                 const MathMesh& math,
                 std::vector<ElasticMaterial> materials,
                 const ModelOptions& options) {
  NMM_ASSERT(options.order >= 0 && options.order <= max_cover_order, "unsupported cover order");
  Model model;
  model.order = options.order;
  model.materials = std::move(materials);
  for (const ElasticMaterial& m : model.materials)
    validate_material(m);
  if (options.scale > 0.0) {
    model.scale = options.scale;
  } else {
    CompensatedSum length;
    for (const auto& t : math.triangles) {
      for (int k = 0; k < 3; ++k)
        length += (math.nodes[at(t[at(k)])] - math.nodes[at(t[at((k + 1) % 3)])]).norm();
    }
    model.scale = math.triangles.empty()
                      ? 1.0
                      : length.value() / (3.0 * static_cast<double>(math.triangles.size()));
  }
  model.covers.reserve(cover_system.covers.size());
  for (const Cover& c : cover_system.covers) {
    ModelCover cover;
    cover.node = c.node;
    cover.block = c.block;
    cover.extension_element = c.extension_element;
    cover.position = math.nodes[at(c.node)];
    model.covers.push_back(cover);
  }
  model.elements.reserve(cover_system.elements.size());
  for (const Element& e : cover_system.elements) {
    ModelElement element;
    element.triangle = e.triangle;
    element.material = e.material;
    element.block = e.block;
    element.covers.assign(e.covers.begin(), e.covers.end());
    element.polygons = e.polygons;
    element.area = e.area;
    NMM_ASSERT(e.material >= 0 && at(e.material) < model.materials.size(),
               "element material out of range");
    Point2 centroid = Point2::Zero();
    for (const int c : e.covers)
      centroid += model.covers[at(c)].position / 3.0;
    element.stress = initial_stress_field(model.materials[at(e.material)], centroid);
    model.elements.push_back(std::move(element));
  }
  model.blocks = cover_system.blocks;
  model.loops = cover_system.loops;
  model.curve_pieces = cover_system.curve_pieces;
  add_block_elements(model, options.region_kinds);
  model.number_dofs();
  return model;
}

void Model::save_state(StateWriter& out) const {
  out.section("MODL");
  out.put_count(covers.size());
  for (const ModelCover& c : covers)
    out.put(c.position);
  out.put_count(elements.size());
  for (const ModelElement& e : elements) {
    out.put_count(e.polygons.size());
    for (const Polygon& p : e.polygons) {
      out.put(p.outer);
      out.put_count(p.holes.size());
      for (const Loop& hole : p.holes)
        out.put(hole);
    }
    out.put(e.area);
    out.put(e.stress.origin);
    out.put(e.stress.coefficients);
    out.put(e.stabilisation_force);
  }
  out.put_count(loops.size());
  for (const BoundaryLoop& loop : loops)
    out.put(loop.vertices);
  out.put_count(curve_pieces.size());
  for (const auto& pieces : curve_pieces) {
    out.put_count(pieces.size());
    for (const CurvePiece& piece : pieces) {
      out.put(piece.a);
      out.put(piece.b);
    }
  }
}

void Model::load_state(StateReader& in) {
  in.section("MODL");
  in.expect_count(covers.size(), "covers");
  for (ModelCover& c : covers)
    c.position = in.point();
  in.expect_count(elements.size(), "elements");
  for (ModelElement& e : elements) {
    in.expect_count(e.polygons.size(), "polygons in an element");
    for (Polygon& p : e.polygons) {
      in.points_into(p.outer, "polygon vertices");
      in.expect_count(p.holes.size(), "holes in a polygon");
      for (Loop& hole : p.holes)
        in.points_into(hole, "hole vertices");
    }
    e.area = in.real();
    e.stress.origin = in.point();
    e.stress.coefficients = in.matrix3();
    e.stabilisation_force = in.vector();
    if (e.stabilisation_force.size() != 0 &&
        e.stabilisation_force.size() != static_cast<Eigen::Index>(e.dofs.size()))
      in.fail("a VEM block's stabilisation force has " +
              std::to_string(e.stabilisation_force.size()) + " values for " +
              std::to_string(e.dofs.size()) + " unknowns");
  }
  in.expect_count(loops.size(), "boundary loops");
  for (BoundaryLoop& loop : loops)
    in.points_into(loop.vertices, "loop vertices");
  in.expect_count(curve_pieces.size(), "named curves");
  for (auto& pieces : curve_pieces) {
    in.expect_count(pieces.size(), "curve pieces");
    for (CurvePiece& piece : pieces) {
      piece.a = in.point();
      piece.b = in.point();
    }
  }
}

} // namespace nmm
