// SPDX-License-Identifier: MIT
#include "io/cover_mesh_output.hpp"

#include "mesh/error.hpp"

#include <cstdint>
#include <utility>
#include <vector>

namespace nmm {

PolygonMeshData make_cover_mesh_data(const CoverSystem& covers) {
  PolygonMeshData data;
  std::vector<std::int32_t> element;
  std::vector<std::int32_t> triangle;
  std::vector<std::int32_t> cover_ids;
  std::vector<std::int32_t> material;
  std::vector<std::int32_t> block;
  std::vector<std::int32_t> n_atoms;
  std::vector<double> area;

  const auto add_loop = [&](const Loop& loop) {
    std::vector<int> indices;
    indices.reserve(loop.size());
    for (const Point2& p : loop) {
      indices.push_back(static_cast<int>(data.points.size()));
      data.points.push_back(p);
    }
    return indices;
  };
  for (int e = 0; e < covers.n_elements(); ++e) {
    const Element& el = covers.elements[static_cast<std::size_t>(e)];
    for (const Polygon& polygon : el.polygons) {
      PolygonCell cell;
      cell.outer = add_loop(polygon.outer);
      for (const Loop& hole : polygon.holes)
        cell.holes.push_back(add_loop(hole));
      data.cells.push_back(std::move(cell));
      element.push_back(e);
      triangle.push_back(el.triangle);
      cover_ids.insert(cover_ids.end(), el.covers.begin(), el.covers.end());
      material.push_back(el.material);
      block.push_back(el.block);
      n_atoms.push_back(static_cast<std::int32_t>(el.polygons.size()));
      area.push_back(el.area);
    }
  }
  data.cell_data.add("element", std::move(element))
      .add("triangle", std::move(triangle))
      .add("covers", std::move(cover_ids), 3, {"node0", "node1", "node2"})
      .add("material", std::move(material))
      .add("block", std::move(block))
      .add("n_atoms", std::move(n_atoms))
      .add("area", std::move(area));
  return data;
}

void write_cover_mesh_vtu(const std::filesystem::path& file, const CoverSystem& covers) {
  write_vtu(file, make_cover_mesh_data(covers));
}

PolygonMeshData make_math_mesh_data(const MathMesh& mesh, const CoverSystem* covers) {
  NMM_ASSERT(covers == nullptr || covers->node_covers.size() == mesh.nodes.size(),
             "node_covers needs one entry per math node");
  PolygonMeshData data;
  data.points = mesh.nodes;
  data.cells.reserve(mesh.triangles.size());
  std::vector<std::int32_t> triangle;
  triangle.reserve(mesh.triangles.size());
  for (int t = 0; t < mesh.n_triangles(); ++t) {
    const auto& nodes = mesh.triangles[static_cast<std::size_t>(t)];
    data.cells.push_back(PolygonCell{{nodes[0], nodes[1], nodes[2]}, {}});
    triangle.push_back(t);
  }
  std::vector<std::int32_t> node(mesh.nodes.size());
  for (std::size_t n = 0; n < node.size(); ++n)
    node[n] = static_cast<std::int32_t>(n);
  data.cell_data.add("triangle", std::move(triangle));
  data.point_data.add("node", std::move(node));
  if (covers != nullptr) {
    std::vector<std::int32_t> n_covers;
    n_covers.reserve(covers->node_covers.size());
    for (const auto& list : covers->node_covers)
      n_covers.push_back(static_cast<std::int32_t>(list.size()));
    data.point_data.add("n_covers", std::move(n_covers));
  }
  return data;
}

void write_math_mesh_vtu(const std::filesystem::path& file,
                         const MathMesh& mesh,
                         const CoverSystem* covers) {
  write_vtu(file, make_math_mesh_data(mesh, covers));
}

PolylineData make_boundary_data(std::span<const BoundaryLoop> loops) {
  PolylineData data;
  std::vector<std::int32_t> block;
  std::vector<std::int32_t> joint;
  std::vector<std::int32_t> loop_id;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const BoundaryLoop& loop = loops[l];
    const int n = loop.n_vertices();
    if (n < 2)
      continue;
    NMM_ASSERT(loop.edges.size() == loop.vertices.size(), "one edge per loop vertex");
    const int first = static_cast<int>(data.points.size());
    data.points.insert(data.points.end(), loop.vertices.begin(), loop.vertices.end());
    const auto joint_of = [&](int k) {
      return loop.edges.at(static_cast<std::size_t>(k % n)).joint;
    };
    // Start at a change of joint, so that no run wraps around the loop's first vertex.
    int start = 0;
    while (start < n && joint_of(start) == joint_of(start + n - 1))
      ++start;
    const bool one_run = start == n;
    if (one_run)
      start = 0;
    for (int k = 0; k < n;) {
      std::vector<int> line{first + (start + k) % n};
      const int run_joint = joint_of(start + k);
      while (k < n && joint_of(start + k) == run_joint) {
        line.push_back(first + (start + k + 1) % n);
        ++k;
      }
      data.lines.push_back(std::move(line));
      block.push_back(loop.block);
      joint.push_back(run_joint);
      loop_id.push_back(static_cast<std::int32_t>(l));
    }
  }
  data.cell_data.add("block", std::move(block))
      .add("joint", std::move(joint))
      .add("loop", std::move(loop_id));
  return data;
}

void write_boundary_vtp(const std::filesystem::path& file, const CoverSystem& covers) {
  write_vtp_lines(file, make_boundary_data(covers.loops));
}

} // namespace nmm
