// SPDX-License-Identifier: MIT
// manifold/regular_shapes.hpp — the regular polygons and solids of Shi's simplex-integration
// tables (second paper, Figures 3 and 4), for the demo, the tests and the benchmarks.
#pragma once

#include "manifold/simplex_integration.hpp"
#include "mesh/geometry.hpp"

namespace nmm {

/// The regular n-gon inscribed in the unit circle with Shi's vertex formula
/// x_i = sin(360 i / n), y_i = cos(360 i / n), i = 1..n (clockwise). @pre n >= 3.
[[nodiscard]] Loop regular_polygon(int n_vertices);

/// The Platonic solids of Shi's Figure 4, inscribed in the unit sphere.
enum class RegularSolid { tetrahedron, cube, dodecahedron };

/// The solid with outward-oriented faces (counter-clockwise seen from outside).
[[nodiscard]] Polyhedron regular_solid(RegularSolid kind);

} // namespace nmm
