// SPDX-License-Identifier: MIT
// mesh/cover_system.hpp — physical covers, manifold elements, blocks and boundary loops
// (DESIGN.md "Concepts"; Shi 1997, chapters 1.4 and 4.1-4.2). Data only: built by
// build_cover_system() (mesh/cover_mesher.hpp), read by manifold/, contact/ and io/.
#pragma once

#include "mesh/geometry.hpp"

#include <array>
#include <string>
#include <vector>

namespace nmm {

/// A physical cover: one connected piece of (star of a math node ∩ material) after cutting
/// by joints and boundaries. Connectivity runs across math edges and bonded interfaces,
/// never across joints or boundaries.
struct Cover {
  /// The math node whose star this cover is part of.
  int node = -1;
  /// The block the cover lies in.
  int block = -1;
  /// Area of the cover's support (the sum of its elements' areas), m².
  double area = 0.0;
  /// -1 when the cover carries its own unknowns. Otherwise the cover is too small to carry
  /// them (its support is below CoverMesherOptions::min_cover_area_ratio of its math star):
  /// its cover function is the extension of the displacement field of this element, a
  /// well-posed element of the same block near the cover's node (docs/cover-mesher.md,
  /// "Tiny covers"). Extending the field, rather than tying the cover to a neighbour,
  /// keeps every polynomial the cover functions can represent, so patch tests stay exact.
  int extension_element = -1;
  /// Elements in which this cover is one of the three covers.
  std::vector<int> elements;
};

/// A manifold element: within one math triangle, the material where the same three physical
/// covers overlap, of one material (Shi 1997, chapter 4.2).
struct Element {
  /// The math triangle holding the element.
  int triangle = -1;
  /// The physical cover of each node of the triangle, in the triangle's node order. The three
  /// are distinct and belong to the same block. The weight function of covers[k] is the k-th
  /// barycentric coordinate of the element's triangle (Shi eq. 4.7-4.11).
  std::array<int, 3> covers{-1, -1, -1};
  /// Index of the material region (PhysicalMesh::regions).
  int material = -1;
  int block = -1;
  /// The integration domain: one polygon per atom (usually one), outer loops
  /// counter-clockwise, holes clockwise, without dangling joint ends (antennas).
  std::vector<Polygon> polygons;
  /// Material area of the element, m² (exact arrangement rounded to double).
  double area = 0.0;
};

/// One edge of a boundary loop: from loop.vertices[k] to loop.vertices[k + 1] (cyclically),
/// with the material on its left.
struct BoundaryEdge {
  /// The element whose displacement field holds along this edge; -1 on the boundary of a
  /// `dda`/`vem` block, where the block itself is the element.
  int element = -1;
  /// The named curve (PhysicalMesh::curves index) of the joint this edge is a face of, or
  /// -1 for a free boundary (material on one side only, not a joint).
  int joint = -1;
  /// Loop and edge index of the opposite face of the same joint piece (material on both
  /// sides), or -1 when the other side is void.
  int twin_loop = -1;
  int twin_edge = -1;
};

/// A closed boundary of a block, material on its left: the outer boundary (counter-
/// clockwise), a hole boundary (clockwise), or the two faces of a crack that ends inside the
/// material (a slit: out along one face, around the tip, back along the other). Vertices are
/// split where the boundary crosses a math edge, so that every edge lies in one element.
struct BoundaryLoop {
  int block = -1;
  std::vector<Point2> vertices;
  std::vector<BoundaryEdge> edges;
  [[nodiscard]] int n_vertices() const noexcept { return static_cast<int>(vertices.size()); }
};

/// A piece of a named curve inside one math triangle (or along one block edge), with what
/// lies on either side.
struct CurvePiece {
  Point2 a;
  Point2 b;
  /// Element on the left of a -> b and on the right; -1 if void or in a `dda`/`vem` block.
  int left_element = -1;
  int right_element = -1;
  /// Block on the left and on the right, -1 if void.
  int left_block = -1;
  int right_block = -1;
};

/// A block: a connected piece of material bounded by joints and boundaries (a partial joint
/// does not separate it; a bonded interface does not either). The unit of contact
/// bookkeeping and, for `dda`/`vem` regions, the unit of the special covers.
struct Block {
  std::vector<int> elements;
  std::vector<int> loops;
  /// Materials present in the block (several when it spans bonded interfaces).
  std::vector<int> materials;
  double area = 0.0;
  /// True when a joint ends inside the block (a crack tip in the material).
  bool has_crack_tip = false;
};

/// Counters and timings of one build_cover_system() call, for benchmarks and summary.json.
struct CoverMesherStats {
  int math_triangles = 0;
  int cut_triangles = 0;  ///< triangles that went through a local arrangement
  int physical_edges = 0; ///< edges of the global arrangement of physical lines
  int tiny_atoms = 0;     ///< atoms below 1e-12 of their triangle (kept; reported)
  int tiny_covers = 0;    ///< covers given an extension element
  double seconds_physical_arrangement = 0.0; ///< global arrangement + face labels
  double seconds_cut_triangles = 0.0;        ///< local arrangements of cut triangles
  double seconds_rest = 0.0;                 ///< covers, elements, blocks, loops
};

/// A block whose tiny covers found no well-posed element of their block (the tiny-cover rule,
/// docs/cover-mesher.md): it keeps its own unknowns, which may be poorly conditioned. io/
/// words the warning: where the block is, what cuts it and which change resolves it.
struct TinyBlock {
  int block = -1;
  /// Area of one of its tiny covers that has no well-posed element near it, m².
  double cover_area = 0.0;
};

/// The cover system of DESIGN.md: everything the manifold model needs about topology.
struct CoverSystem {
  std::vector<Cover> covers;
  std::vector<Element> elements;
  std::vector<Block> blocks;
  std::vector<BoundaryLoop> loops;
  /// For each named curve of the physical mesh, its pieces (empty if it misses the material).
  std::vector<std::vector<CurvePiece>> curve_pieces;
  /// For each math node, the physical covers of its star (0, 1 or more).
  std::vector<std::vector<int>> node_covers;
  /// Problems that do not stop the analysis (a joint outside the material, a joint ending
  /// inside a block region); blocks too small for the cover mesh are in tiny_blocks.
  std::vector<std::string> warnings;
  /// Blocks too small for the cover mesh, in block order.
  std::vector<TinyBlock> tiny_blocks;
  CoverMesherStats stats;

  [[nodiscard]] int n_covers() const noexcept { return static_cast<int>(covers.size()); }
  [[nodiscard]] int n_elements() const noexcept { return static_cast<int>(elements.size()); }
  [[nodiscard]] int n_blocks() const noexcept { return static_cast<int>(blocks.size()); }
  [[nodiscard]] int n_loops() const noexcept { return static_cast<int>(loops.size()); }
};

} // namespace nmm
