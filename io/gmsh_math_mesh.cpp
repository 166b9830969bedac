// SPDX-License-Identifier: MIT
// The "gmsh" mathematical (cover) mesh: a .msh's own triangles, or gmsh's triangulation of the
// physical mesh's polygons (graded by the .geo's own mesh sizes when asked).
#include "io/gmsh_internal.hpp"
#include "io/gmsh_reader.hpp"
#include "io/text.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/error.hpp"
#include "mesh/geometry.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <utility>
#include <vector>

namespace nmm {

namespace {

using detail::check_geometry_file;
using detail::check_tolerance;
using detail::element_corners;
using detail::entity_tags;
using detail::GmshFileKind;
using detail::NodeTable;
using detail::open_model;
using detail::physical_groups;
using detail::PhysicalGroup;
using detail::planar;
using detail::run_gmsh;
using detail::throw_no_physical_surface;

// ----------------------------------------------------------------------------------------
// Math mesh

/// Triangles of 2D elements of @p surfaces (quads split, high-order nodes dropped), nodes
/// renumbered 0..n-1 in order of first use, every triangle counter-clockwise.
MathMesh collect_triangles(const std::string& file, const std::vector<int>& surfaces) {
  NodeTable nodes;
  MathMesh mesh;
  std::unordered_map<std::size_t, int> index_of;
  auto index = [&](std::size_t tag) {
    const auto [it, inserted] = index_of.try_emplace(tag, mesh.n_nodes());
    if (inserted)
      mesh.nodes.push_back(planar(nodes.at(tag)));
    return it->second;
  };
  auto add = [&](std::size_t a, std::size_t b, std::size_t c) {
    std::array<int, 3> triangle{index(a), index(b), index(c)};
    const Point2& p = mesh.nodes[static_cast<std::size_t>(triangle[0])];
    const Point2& q = mesh.nodes[static_cast<std::size_t>(triangle[1])];
    const Point2& r = mesh.nodes[static_cast<std::size_t>(triangle[2])];
    const double twice_area = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
    if (twice_area == 0.0)
      throw InputError(file + ": the mesh has a triangle of zero area near " + point_text(p) +
                       "; mesh the geometry again (or give a larger cover mesh size)");
    if (twice_area < 0.0)
      std::swap(triangle[1], triangle[2]);
    mesh.triangles.push_back(triangle);
  };
  for (const int surface : surfaces) {
    for (const std::vector<std::size_t>& element : element_corners(2, surface)) {
      if (element.size() == 3) {
        add(element[0], element[1], element[2]);
      } else if (element.size() == 4) {
        add(element[0], element[1], element[2]);
        add(element[0], element[2], element[3]);
      }
    }
  }
  return mesh;
}

[[noreturn]] void throw_too_many_triangles(const std::string& file,
                                           double size,
                                           double count,
                                           double area,
                                           double max_triangles,
                                           const char* how) {
  std::ostringstream message;
  message << file << ": cover mesh size " << size << " m would make " << how << count
          << " gmsh triangles for the " << area << " m^2 of material, more than the limit of "
          << max_triangles
          << "; increase [cover_mesh] size, or raise [cover_mesh] max_triangles if this is "
             "intended";
  throw InputError(message.str());
}

/// The size field of a graded math mesh (make_gmsh_math_mesh(), `sizes_from_geometry`): the
/// .geo's own model meshed as the file asks, with Mesh.MeshSizeMax at most @p size, as gmsh
/// list data "ST" (per triangle x1 x2 x3 y1 y2 y3 z1 z2 z3 and the sizes at its corners); the
/// size at a node is the mean length of its mesh edges, at most @p size.
std::vector<double>
geometry_size_field(const std::filesystem::path& file, double size, double max_triangles) {
  const std::string name = file.string();
  // gmsh's default, so that the file's own Mesh.MeshSizeMax (if any) is the one read back.
  gmsh::option::setNumber("Mesh.MeshSizeMax", 1e22);
  open_model(file, GmshFileKind::geo);
  MathMesh own;
  run_gmsh(name, "mesh the geometry with its own mesh sizes", [&] {
    double file_max = 0.0;
    gmsh::option::getNumber("Mesh.MeshSizeMax", file_max);
    gmsh::option::setNumber("Mesh.MeshSizeMax", std::min(file_max, size));
    gmsh::model::mesh::generate(2);
    const std::set<int> surfaces = entity_tags(2);
    own = collect_triangles(name, std::vector<int>(surfaces.begin(), surfaces.end()));
  });
  if (static_cast<double>(own.n_triangles()) > max_triangles) {
    throw InputError(
        name + ": the .geo's own mesh sizes ([cover_mesh] geometry_sizes = true) make " +
        std::to_string(own.n_triangles()) +
        " triangles, more than [cover_mesh] max_triangles = " + number_text(max_triangles, 10) +
        "; give its points and Fields larger sizes (in metres), or raise "
        "max_triangles if this is intended");
  }
  std::vector<double> length_sum(own.nodes.size(), 0.0);
  std::vector<int> edges(own.nodes.size(), 0);
  std::set<std::pair<int, int>> unique_edges;
  for (const auto& t : own.triangles)
    for (std::size_t i = 0; i < 3; ++i)
      unique_edges.insert(std::minmax(t[i], t[(i + 1) % 3]));
  for (const auto& [first, second] : unique_edges) {
    const auto a = static_cast<std::size_t>(first);
    const auto b = static_cast<std::size_t>(second);
    const double length = (own.nodes[a] - own.nodes[b]).norm();
    length_sum[a] += length;
    length_sum[b] += length;
    ++edges[a];
    ++edges[b];
  }
  std::vector<double> data;
  data.reserve(12 * own.triangles.size());
  for (const auto& t : own.triangles) {
    for (const int n : t)
      data.push_back(own.nodes[static_cast<std::size_t>(n)].x());
    for (const int n : t)
      data.push_back(own.nodes[static_cast<std::size_t>(n)].y());
    data.insert(data.end(), 3, 0.0);
    for (const int n : t) {
      const auto i = static_cast<std::size_t>(n);
      data.push_back(std::min(size, length_sum[i] / edges[i]));
    }
  }
  return data;
}

/// gmsh's triangulation of the polygons of @p physical, edges at most @p size, smaller where
/// the list data @p size_field (geometry_size_field(); empty: none) asks.
MathMesh triangulate_physical_mesh(const std::string& file,
                                   const PhysicalMesh& physical,
                                   double size,
                                   const std::vector<double>& size_field) {
  MathMesh mesh;
  run_gmsh(file, "triangulate the material", [&] {
    gmsh::clear();
    gmsh::model::add("nmm_math_mesh");
    // The .geo's own sizes and fields refer to entities that are not in this model: the
    // case file's size counts, and the .geo's sizes only through size_field.
    if (!size_field.empty()) {
      const int view = gmsh::view::add("nmm_geometry_sizes");
      gmsh::view::addListData(view, "ST", static_cast<int>(size_field.size() / 12), size_field);
      const int field = gmsh::model::mesh::field::add("PostView");
      gmsh::model::mesh::field::setNumber(field, "ViewTag", view);
      gmsh::model::mesh::field::setAsBackgroundMesh(field);
    }
    gmsh::option::setNumber("Geometry.AutoCoherence", 0);
    gmsh::option::setNumber("Mesh.MeshSizeMax", size);
    gmsh::option::setNumber("Mesh.MeshSizeMin", 0.0);
    gmsh::option::setNumber("Mesh.MeshSizeFactor", 1.0);
    gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
    gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
    gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
    gmsh::option::setNumber("Mesh.ElementOrder", 1);
    gmsh::option::setNumber("Mesh.RecombineAll", 0);
    gmsh::option::setNumber("Mesh.SubdivisionAlgorithm", 0);
    gmsh::option::setNumber("Mesh.Algorithm", 6);

    // Polygon vertices and edges shared between loops (interfaces between surfaces) become
    // one gmsh point and one gmsh line, so the mesh conforms across them.
    std::map<std::pair<double, double>, int> point_tag;
    std::map<std::pair<int, int>, int> line_tag;
    auto point = [&](const Point2& p) {
      const auto found = point_tag.find({p.x(), p.y()});
      if (found != point_tag.end())
        return found->second;
      const int tag = gmsh::model::geo::addPoint(p.x(), p.y(), 0.0, size);
      point_tag.emplace(std::make_pair(p.x(), p.y()), tag);
      return tag;
    };
    auto curve_loop = [&](const Loop& loop) {
      std::vector<int> lines;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const int a = point(loop[i]);
        const int b = point(loop[(i + 1) % loop.size()]);
        const auto found = line_tag.find({std::min(a, b), std::max(a, b)});
        if (found != line_tag.end()) {
          lines.push_back(a < b ? found->second : -found->second);
          continue;
        }
        const int tag = gmsh::model::geo::addLine(std::min(a, b), std::max(a, b));
        line_tag.emplace(std::make_pair(std::min(a, b), std::max(a, b)), tag);
        lines.push_back(a < b ? tag : -tag);
      }
      return gmsh::model::geo::addCurveLoop(lines);
    };
    for (const MaterialRegion& region : physical.regions) {
      for (const Polygon& polygon : region.polygons) {
        std::vector<int> loops{curve_loop(polygon.outer)};
        for (const Loop& hole : polygon.holes)
          loops.push_back(curve_loop(hole));
        gmsh::model::geo::addPlaneSurface(loops);
      }
    }
    gmsh::model::geo::synchronize();
    gmsh::model::mesh::generate(2);
    const std::set<int> surfaces = entity_tags(2);
    mesh = collect_triangles(file, std::vector<int>(surfaces.begin(), surfaces.end()));
  });
  // gmsh rounds the nodes it places along a slanted edge: some fall a hair inside the
  // material, which the math mesh must cover to its boundary.
  fit_math_mesh_to_boundary(mesh, physical);
  return mesh;
}

void check_math_mesh_size(const std::string& name, double size, double max_triangles) {
  if (!(size > 0.0) || !std::isfinite(size)) {
    throw InputError(name + ": cover mesh size must be a positive number of metres, got " +
                     number_text(size, 10));
  }
  if (!(max_triangles > 0.0)) {
    throw InputError(name + ": [cover_mesh] max_triangles must be positive, got " +
                     number_text(max_triangles, 10));
  }
}

} // namespace

MathMesh make_gmsh_math_mesh(const std::filesystem::path& file,
                             double size,
                             double max_triangles,
                             const GeometryReadOptions& options) {
  const std::string name = file.string();
  check_math_mesh_size(name, size, max_triangles);
  check_tolerance(name, options);
  const GmshFileKind kind = check_geometry_file(file);
  if (kind != GmshFileKind::msh)
    return make_gmsh_math_mesh(file, read_physical_mesh(file, options), size, max_triangles);

  // The file's own elements: the physical mesh read from the same file has these
  // triangles' boundary edges as its loops, so they cover the material exactly.
  std::optional<GmshSession> own_session;
  if (!GmshSession::is_alive())
    own_session.emplace();
  open_model(file, kind);
  const std::vector<PhysicalGroup> groups = physical_groups(2, "surface");
  if (groups.empty())
    throw_no_physical_surface(name);
  std::set<int> surfaces;
  for (const PhysicalGroup& group : groups)
    surfaces.insert(group.entities.begin(), group.entities.end());
  MathMesh mesh = collect_triangles(name, std::vector<int>(surfaces.begin(), surfaces.end()));
  if (mesh.triangles.empty())
    throw InputError(name + ": the Physical Surfaces have no triangles or quadrangles; mesh "
                            "the geometry in 2D (gmsh -2) before saving the .msh");
  if (static_cast<double>(mesh.n_triangles()) > max_triangles) {
    double area = 0.0;
    for (const auto& t : mesh.triangles) {
      area += std::abs(signed_area(std::array<Point2, 3>{
          mesh.nodes[static_cast<std::size_t>(t[0])], mesh.nodes[static_cast<std::size_t>(t[1])],
          mesh.nodes[static_cast<std::size_t>(t[2])]}));
    }
    throw_too_many_triangles(name, size, mesh.n_triangles(), area, max_triangles, "");
  }
  return mesh;
}

MathMesh make_gmsh_math_mesh(const std::filesystem::path& file,
                             const PhysicalMesh& physical,
                             double size,
                             double max_triangles,
                             bool sizes_from_geometry) {
  const std::string name = file.string();
  check_math_mesh_size(name, size, max_triangles);
  if (check_geometry_file(file) == GmshFileKind::msh)
    return make_gmsh_math_mesh(file, size, max_triangles);
  const double area = material_area(physical);
  // Triangles of edge `size` have area sqrt(3)/4 size^2; gmsh's are a little smaller, so this
  // underestimates and refuses only meshes that would clearly be too large.
  const double estimate = area / (std::sqrt(3.0) / 4.0 * size * size);
  if (estimate > max_triangles)
    throw_too_many_triangles(name, size, std::round(estimate), area, max_triangles, "about ");
  std::optional<GmshSession> own_session;
  if (!GmshSession::is_alive())
    own_session.emplace();
  const std::vector<double> size_field =
      sizes_from_geometry ? geometry_size_field(file, size, max_triangles) : std::vector<double>();
  MathMesh mesh = triangulate_physical_mesh(name, physical, size, size_field);
  if (static_cast<double>(mesh.n_triangles()) > max_triangles)
    throw_too_many_triangles(name, size, mesh.n_triangles(), area, max_triangles, "");
  return mesh;
}

} // namespace nmm
