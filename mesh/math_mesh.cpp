// SPDX-License-Identifier: MIT
#include "mesh/math_mesh.hpp"

#include "mesh/error.hpp"

#include <cmath>
#include <sstream>

namespace nmm {

namespace {

struct RegularLayout {
  int columns = 0; // even rows have columns + 1 nodes, odd rows columns + 2
  int rows = 0;    // rows of triangles
  double row_height = 0.0;
};

RegularLayout regular_layout(const BoundingBox& box, double size) {
  RegularLayout layout;
  layout.row_height = size * std::sqrt(3.0) / 2.0;
  const Point2 extent = box.size();
  // At least one triangle row and column, so that a degenerate (flat) box is still covered.
  layout.columns = std::max(1, static_cast<int>(std::ceil(extent.x() / size)));
  layout.rows = std::max(1, static_cast<int>(std::ceil(extent.y() / layout.row_height)));
  return layout;
}

} // namespace

double regular_math_mesh_triangle_count(const BoundingBox& box, double size) {
  const Point2 extent = box.size();
  const double columns = std::max(1.0, std::ceil(extent.x() / size));
  const double rows = std::max(1.0, std::ceil(extent.y() / (size * std::sqrt(3.0) / 2.0)));
  return rows * (2.0 * columns + 1.0);
}

MathMesh make_regular_math_mesh(const BoundingBox& box, double size, double max_triangles) {
  if (!(size > 0.0) || !std::isfinite(size)) {
    std::ostringstream message;
    message << "cover mesh size must be a positive number of metres, got " << size;
    throw InputError(message.str());
  }
  NMM_ASSERT(!box.is_empty(), "make_regular_math_mesh needs a non-empty box");
  const double count = regular_math_mesh_triangle_count(box, size);
  if (count > max_triangles) {
    std::ostringstream message;
    message << "cover mesh size " << size << " m would make " << count
            << " math triangles for a material of " << box.size().x() << " m x " << box.size().y()
            << " m, more than the limit of " << max_triangles
            << "; increase [cover_mesh] size, or raise [cover_mesh] max_triangles if this "
               "is intended";
    throw InputError(message.str());
  }
  const RegularLayout layout = regular_layout(box, size);
  MathMesh mesh;
  // Node index of column i in row j: even rows hold columns + 1 nodes at x0 + i size, odd
  // rows columns + 2 nodes at x0 + (i - 1/2) size, so both ends of the box are covered.
  std::vector<int> row_start(static_cast<std::size_t>(layout.rows) + 2);
  for (int j = 0; j <= layout.rows; ++j) {
    row_start[static_cast<std::size_t>(j)] = mesh.n_nodes();
    const bool odd = (j % 2) == 1;
    const int count_in_row = layout.columns + (odd ? 2 : 1);
    const double y = box.min.y() + j * layout.row_height;
    for (int i = 0; i < count_in_row; ++i) {
      const double x = box.min.x() + (odd ? (i - 0.5) : i) * size;
      mesh.nodes.emplace_back(x, y);
    }
  }
  auto node = [&](int row, int column) {
    return row_start[static_cast<std::size_t>(row)] + column;
  };
  for (int j = 0; j < layout.rows; ++j) {
    if (j % 2 == 0) {
      // Even row below, odd row above: even node i lies between odd nodes i and i + 1.
      for (int i = 0; i <= layout.columns; ++i) {
        if (i < layout.columns) {
          mesh.triangles.push_back({node(j, i), node(j, i + 1), node(j + 1, i + 1)});
        }
        mesh.triangles.push_back({node(j, i), node(j + 1, i + 1), node(j + 1, i)});
      }
    } else {
      // Odd row below, even row above: even node i lies between odd nodes i and i + 1.
      for (int i = 0; i <= layout.columns; ++i) {
        mesh.triangles.push_back({node(j, i), node(j, i + 1), node(j + 1, i)});
        if (i < layout.columns) {
          mesh.triangles.push_back({node(j + 1, i), node(j, i + 1), node(j + 1, i + 1)});
        }
      }
    }
  }
  return mesh;
}

} // namespace nmm
