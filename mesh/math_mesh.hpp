// SPDX-License-Identifier: MIT
// mesh/math_mesh.hpp — the mathematical mesh: triangles covering the material (Shi 1997,
// chapter 4.1: the math cover of a node is its star, the triangles sharing it).
#pragma once

#include "mesh/geometry.hpp"

#include <array>
#include <vector>

namespace nmm {

/// Triangles that cover the whole material; they need not follow boundaries or joints.
struct MathMesh {
  /// Node coordinates in metres.
  std::vector<Point2> nodes;
  /// Node indices of each triangle, counter-clockwise.
  std::vector<std::array<int, 3>> triangles;

  [[nodiscard]] int n_nodes() const noexcept { return static_cast<int>(nodes.size()); }
  [[nodiscard]] int n_triangles() const noexcept { return static_cast<int>(triangles.size()); }
};

/// Default cap on the number of math triangles: a cover size so small that it would make
/// more is almost always a unit mistake, and would need tens of GB downstream.
inline constexpr double default_max_math_triangles = 5.0e6;

/// Number of triangles make_regular_math_mesh() would make for @p box and @p size, as a
/// double so that absurd sizes do not overflow. @pre size > 0, box not empty.
[[nodiscard]] double regular_math_mesh_triangle_count(const BoundingBox& box, double size);

/// A regular mesh of equilateral triangles of edge @p size covering @p box (DESIGN.md,
/// "Contracts users see"): a node at the lower-left corner of the box, rows along x,
/// odd rows shifted by size/2 and extended by half a triangle on both sides.
/// @throws InputError when size <= 0 or not finite, or when the mesh would have more than
///         @p max_triangles triangles (the message says how to override the cap).
[[nodiscard]] MathMesh make_regular_math_mesh(const BoundingBox& box,
                                              double size,
                                              double max_triangles = default_max_math_triangles);

} // namespace nmm
