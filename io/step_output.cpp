// SPDX-License-Identifier: MIT
#include "io/step_output.hpp"

#include "io/cover_mesh_output.hpp"
#include "manifold/simplex_integration.hpp"
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <variant>

namespace nmm {
namespace {

/// `PREFIX_NNNNNN.EXTENSION`: the step number with at least 6 digits.
std::string numbered_file_name(const char* prefix, long step, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%06ld.%s", prefix, step, extension);
  return name;
}

} // namespace

double principal_angle(const PrincipalStress& principal) {
  double degrees =
      std::atan2(principal.direction.y(), principal.direction.x()) * 180.0 / std::numbers::pi;
  // The direction of an axis, not of an arrow: (-90, 90].
  if (degrees > 90.0)
    degrees -= 180.0;
  else if (degrees <= -90.0)
    degrees += 180.0;
  return degrees;
}

const char* contact_state_name(ContactMode mode) {
  switch (mode) {
  case ContactMode::open:
    return "open";
  case ContactMode::slide:
    return "sliding";
  case ContactMode::lock:
    return "locked";
  }
  return "unknown";
}

std::vector<std::string> step_part_names() { return {"elements", "contacts", "boundaries"}; }

PrincipalStress principal_stress(const Eigen::Vector3d& stress) {
  const double mean = 0.5 * (stress(0) + stress(1));
  const double half_difference = 0.5 * (stress(0) - stress(1));
  const double radius = std::hypot(half_difference, stress(2));
  PrincipalStress result;
  result.s1 = mean + radius;
  result.s2 = mean - radius;
  const double angle = 0.5 * std::atan2(stress(2), half_difference);
  result.direction = Point2(std::cos(angle), std::sin(angle));
  return result;
}

Point2 element_centroid(const ModelElement& element) {
  Point2 origin = Point2::Zero();
  std::size_t n = 0;
  for (const Polygon& polygon : element.polygons) {
    for (const Point2& p : polygon.outer) {
      origin += p;
      ++n;
    }
  }
  if (n == 0)
    return origin;
  origin /= static_cast<double>(n);
  // First moments about the vertices' mean (accurate far from 0); holes count negative
  // whatever the orientation of the loops.
  Moments2 moments(1, origin);
  for (const Polygon& polygon : element.polygons)
    moments += polygon_moments(polygon, 1, origin);
  return moments.area() > 0.0 ? moments.centroid() : origin;
}

std::vector<Point2> step_points(const Model& model) {
  std::vector<Point2> points;
  for (const ModelElement& element : model.elements) {
    for (const Polygon& polygon : element.polygons) {
      points.insert(points.end(), polygon.outer.begin(), polygon.outer.end());
      for (const Loop& hole : polygon.holes)
        points.insert(points.end(), hole.begin(), hole.end());
    }
  }
  return points;
}

PolygonMeshData make_step_data(const Model& model,
                               std::span<const Point2> initial_points,
                               const Eigen::VectorXd& velocity,
                               double time) {
  NMM_ASSERT(velocity.size() == model.n_dofs(), "one velocity per raw unknown");
  PolygonMeshData data;
  std::vector<Point2> point_velocity;
  std::vector<double> stress;
  std::vector<double> principal;
  std::vector<double> direction;
  std::vector<double> angle;
  std::vector<std::int32_t> element_id;
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> block;
  std::vector<std::int32_t> kind;

  // Where each point written is in initial_points (excavated elements are not written).
  std::vector<std::size_t> initial_of;
  std::size_t consumed = 0;
  for (int e = 0; e < model.n_elements(); ++e) {
    const ModelElement& element = model.elements[static_cast<std::size_t>(e)];
    if (element.excavated) {
      for (const Polygon& polygon : element.polygons) {
        consumed += polygon.outer.size();
        for (const Loop& hole : polygon.holes)
          consumed += hole.size();
      }
      continue;
    }
    const ElementShape shape = model.shape(e);
    const Eigen::VectorXd values = model.element_values(e, velocity);
    const std::span<const double> v(values.data(), static_cast<std::size_t>(values.size()));
    const auto add_loop = [&](const Loop& loop) {
      std::vector<int> indices;
      indices.reserve(loop.size());
      for (const Point2& p : loop) {
        indices.push_back(static_cast<int>(data.points.size()));
        data.points.push_back(p);
        initial_of.push_back(consumed++);
        point_velocity.push_back(shape.displacement_at(p, v));
      }
      return indices;
    };
    const Eigen::Vector3d s = element.stress.at(element_centroid(element));
    const PrincipalStress p = principal_stress(s);
    for (const Polygon& polygon : element.polygons) {
      PolygonCell cell;
      cell.outer = add_loop(polygon.outer);
      for (const Loop& hole : polygon.holes)
        cell.holes.push_back(add_loop(hole));
      data.cells.push_back(std::move(cell));
      stress.insert(stress.end(), {s(0), s(1), s(2)});
      principal.insert(principal.end(), {p.s1, p.s2});
      direction.insert(direction.end(), {p.direction.x(), p.direction.y(), 0.0});
      angle.push_back(principal_angle(p));
      element_id.push_back(e);
      material.push_back(element.material);
      block.push_back(element.block);
      kind.push_back(static_cast<std::int32_t>(element.kind));
    }
  }
  NMM_ASSERT(initial_points.size() == consumed,
             "the initial points must be step_points() of the same model");
  std::vector<Point2> displacement(data.points.size());
  for (std::size_t k = 0; k < displacement.size(); ++k)
    displacement[k] = data.points[k] - initial_points[initial_of[k]];

  data.point_data.add_vectors("displacement", displacement).add_vectors("velocity", point_velocity);
  data.cell_data.add("stress", std::move(stress), 3, {"sxx", "syy", "sxy"})
      .add("principal_stresses", std::move(principal), 2, {"s1", "s2"})
      .add("principal_direction", std::move(direction), 3, {"x", "y", "z"})
      .add("principal_angle", std::move(angle))
      .add("element", std::move(element_id))
      .add("material", std::move(material))
      .add("block", std::move(block))
      .add("kind", std::move(kind));
  data.field_data.add_value("TimeValue", time);
  return data;
}

PointCloudData make_contact_data(const ContactSystem& contact, const Model& model, double time) {
  PointCloudData data;
  const std::vector<ContactSystem::Place> places = contact.current_places(model);
  const std::vector<ContactPoint>& points = contact.points();
  std::vector<double> normal_force;
  std::vector<double> shear_force;
  std::vector<double> gap;
  std::vector<double> length;
  std::vector<double> pressure;
  std::vector<std::int32_t> state;
  std::vector<std::string> state_name;
  std::vector<std::int32_t> bonded;
  std::vector<Point2> normal;
  // `pressure`, force over tributary length: an angle's spring force over its length; for the
  // Gauss points of edge-to-edge pairs the force of the closed points of their slave edge
  // (of every pair the edge is in) over their lengths. Point by point the springs of a polygon
  // that stands for a curve carry its chords' sag (examples/17 at 1000 E: -13% to +27% of the
  // peak pressure along each chord), and normal_force is shared within a pair by stiffness.
  const auto own_force = [](const ContactPoint& p) {
    return p.mode != ContactMode::open ? p.stiffness * (p.offset - p.gap) : 0.0;
  };
  std::unordered_map<int, std::pair<double, double>> edge_load; // slave edge: force, length
  for (const ContactPoint& p : points) {
    if (is_edge_pair(p.key) && p.mode != ContactMode::open) {
      auto& [force, tributary] = edge_load[p.slave_edge];
      force += own_force(p);
      tributary += p.length;
    }
  }
  normal_force.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const ContactPoint& p = points[i];
    data.points.push_back(places[i].position);
    normal.push_back(places[i].normal);
    normal_force.push_back(p.normal_force);
    shear_force.push_back(p.shear_force);
    gap.push_back(p.gap);
    length.push_back(p.length);
    double mean = 0.0;
    if (p.mode != ContactMode::open) {
      const auto [force, tributary] =
          is_edge_pair(p.key) ? edge_load.at(p.slave_edge) : std::make_pair(own_force(p), p.length);
      mean = tributary > 0.0 ? force / tributary : 0.0;
    }
    pressure.push_back(mean);
    state.push_back(static_cast<std::int32_t>(p.mode));
    state_name.emplace_back(contact_state_name(p.mode));
    bonded.push_back(p.bonded ? 1 : 0);
  }
  data.point_data.add("normal_force", std::move(normal_force))
      .add("shear_force", std::move(shear_force))
      .add("state", std::move(state))
      .add("state_name", std::move(state_name))
      .add("gap", std::move(gap))
      .add_vectors("normal", normal)
      .add("bonded", std::move(bonded))
      .add("length", std::move(length))
      .add("pressure", std::move(pressure));
  std::vector<std::string> legend;
  for (const ContactMode mode : {ContactMode::open, ContactMode::slide, ContactMode::lock}) {
    legend.push_back(std::to_string(static_cast<int>(mode)) + " " + contact_state_name(mode));
  }
  data.field_data.add_value("TimeValue", time).add("state_legend", std::move(legend));
  return data;
}

namespace {

std::vector<std::int32_t> integers_of(const DataArrays& arrays, std::string_view name) {
  const DataArray* array = arrays.find(name);
  NMM_ASSERT(array != nullptr && array->is_integer(), "the boundary's integer cell arrays");
  return std::get<std::vector<std::int32_t>>(array->values);
}

/// Appends a line per bar of @p bolts to the boundary's polylines, and the cell arrays
/// `bolt` (its index, -1 on the loops), `axial_force` (N, tension positive; 0 on the loops)
/// and `bolt_state` (0 elastic, 1 yielding, 2 ruptured; -1 on the loops).
void add_bolt_lines(std::span<const Bolt> bolts, PolylineData& data) {
  std::vector<std::int32_t> block = integers_of(data.cell_data, "block");
  std::vector<std::int32_t> joint = integers_of(data.cell_data, "joint");
  std::vector<std::int32_t> loop = integers_of(data.cell_data, "loop");
  const std::size_t loops = data.lines.size();
  std::vector<std::int32_t> bolt(loops, -1);
  std::vector<std::int32_t> state(loops, -1);
  std::vector<double> force(loops, 0.0);
  std::vector<std::string> names;
  for (std::size_t b = 0; b < bolts.size(); ++b) {
    names.push_back(std::to_string(b) + " " + bolts[b].name);
    for (const BoltBar& bar : bolts[b].bars) {
      const auto first = static_cast<int>(data.points.size());
      data.points.push_back(bar.a.position);
      data.points.push_back(bar.b.position);
      data.lines.push_back({first, first + 1});
      block.push_back(-1);
      joint.push_back(-1);
      loop.push_back(-1);
      bolt.push_back(static_cast<std::int32_t>(b));
      state.push_back(static_cast<std::int32_t>(bar.state));
      force.push_back(bar.force);
    }
  }
  DataArrays cells;
  cells.add("block", std::move(block))
      .add("joint", std::move(joint))
      .add("loop", std::move(loop))
      .add("bolt", std::move(bolt))
      .add("axial_force", std::move(force))
      .add("bolt_state", std::move(state));
  data.cell_data = std::move(cells);
  std::vector<std::string> legend;
  for (const BoltState s : {BoltState::elastic, BoltState::yielding, BoltState::ruptured})
    legend.push_back(std::to_string(static_cast<int>(s)) + " " + bolt_state_name(s));
  data.field_data.add("bolt_names", std::move(names)).add("bolt_state_legend", std::move(legend));
}

} // namespace

PolylineData make_boundary_step_data(const Model& model, std::span<const Bolt> bolts, double time) {
  PolylineData data = make_boundary_data(model.loops);
  if (!bolts.empty())
    add_bolt_lines(bolts, data);
  data.field_data.add_value("TimeValue", time);
  return data;
}

std::string contact_file_name(long step) { return numbered_file_name("contacts", step, "vtp"); }

std::string boundary_file_name(long step) { return numbered_file_name("boundary", step, "vtp"); }

std::string step_file_name(long step) { return numbered_file_name("step", step, "vtu"); }

} // namespace nmm
