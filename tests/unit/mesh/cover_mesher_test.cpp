// SPDX-License-Identifier: MIT
#include "mesh/cover_mesher.hpp"
#include "mesh/error.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace nmm {
namespace {

MaterialRegion rectangle(const std::string& name, double x0, double y0, double x1, double y1) {
  return {name, {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}}}};
}

NamedCurve curve(const std::string& name, std::vector<Point2> points) {
  return {name, {std::move(points)}};
}

PhysicalMesh physical_of(std::vector<MaterialRegion> regions, std::vector<NamedCurve> curves = {}) {
  PhysicalMesh physical;
  physical.source = "test.geo";
  physical.regions = std::move(regions);
  physical.curves = std::move(curves);
  validate_physical_mesh(physical);
  return physical;
}

std::vector<int> all_curves(const PhysicalMesh& physical) {
  std::vector<int> result(physical.curves.size());
  for (std::size_t i = 0; i < result.size(); ++i)
    result[i] = static_cast<int>(i);
  return result;
}

/// The invariants of issue 3, checked on every cover system the tests build.
/// Tolerance 1e-12 relative on areas: vertices are exact rationals rounded once to double,
/// which moves each atom's area by about 1e-16 of its triangle.
void expect_invariants(const CoverSystem& cs, const MathMesh& math, const PhysicalMesh& physical) {
  const double material = material_area(physical);
  CompensatedSum total;
  for (int e = 0; e < cs.n_elements(); ++e) {
    const Element& element = cs.elements[static_cast<std::size_t>(e)];
    total += element.area;
    // Exactly positive; after rounding the vertices a sliver thinner than 1e-16 of its
    // triangle may come out as zero (it keeps its place in the topology).
    const auto& tri = math.triangles[static_cast<std::size_t>(element.triangle)];
    const double triangle_area = std::abs(signed_area(std::vector<Point2>{
        math.nodes[static_cast<std::size_t>(tri[0])], math.nodes[static_cast<std::size_t>(tri[1])],
        math.nodes[static_cast<std::size_t>(tri[2])]}));
    EXPECT_GE(element.area, -1e-15 * triangle_area) << "element " << e;
    std::set<int> distinct(element.covers.begin(), element.covers.end());
    EXPECT_EQ(distinct.size(), 3U) << "element " << e << " has repeated covers";
    for (int k = 0; k < 3; ++k) {
      const Cover& cover =
          cs.covers[static_cast<std::size_t>(element.covers[static_cast<std::size_t>(k)])];
      EXPECT_EQ(
          cover.node,
          math.triangles[static_cast<std::size_t>(element.triangle)][static_cast<std::size_t>(k)])
          << "element " << e << " cover " << k << " belongs to another node";
      EXPECT_EQ(cover.block, element.block) << "element " << e;
      EXPECT_NE(std::find(cover.elements.begin(), cover.elements.end(), e), cover.elements.end());
    }
  }
  EXPECT_NEAR(total.value(), material, 1e-12 * material);
  for (int c = 0; c < cs.n_covers(); ++c) {
    const Cover& cover = cs.covers[static_cast<std::size_t>(c)];
    EXPECT_FALSE(cover.elements.empty()) << "cover " << c;
    const auto& at_node = cs.node_covers[static_cast<std::size_t>(cover.node)];
    EXPECT_NE(std::find(at_node.begin(), at_node.end(), c), at_node.end());
    if (cover.extension_element >= 0) {
      const Element& root = cs.elements[static_cast<std::size_t>(cover.extension_element)];
      EXPECT_EQ(root.block, cover.block);
      for (const int other : root.covers)
        EXPECT_LT(cs.covers[static_cast<std::size_t>(other)].extension_element, 0);
    }
  }
  // Blocks: the area of the elements equals the area enclosed by the loops (outer
  // counter-clockwise, holes clockwise, crack slits zero): the loops bound the elements.
  double block_total = 0.0;
  for (int b = 0; b < cs.n_blocks(); ++b) {
    const Block& block = cs.blocks[static_cast<std::size_t>(b)];
    double enclosed = 0.0;
    for (const int l : block.loops)
      enclosed += signed_area(cs.loops[static_cast<std::size_t>(l)].vertices);
    EXPECT_NEAR(enclosed, block.area, 1e-12 * material) << "block " << b;
    block_total += block.area;
  }
  EXPECT_NEAR(block_total, material, 1e-12 * material);
  for (const BoundaryLoop& loop : cs.loops) {
    ASSERT_EQ(loop.vertices.size(), loop.edges.size());
    for (std::size_t k = 0; k < loop.edges.size(); ++k) {
      const BoundaryEdge& edge = loop.edges[k];
      ASSERT_GE(edge.element, 0);
      EXPECT_EQ(cs.elements[static_cast<std::size_t>(edge.element)].block, loop.block);
      EXPECT_NE(loop.vertices[k], loop.vertices[(k + 1) % loop.vertices.size()]);
      if (edge.twin_loop >= 0) {
        const BoundaryLoop& other = cs.loops[static_cast<std::size_t>(edge.twin_loop)];
        const std::size_t j = static_cast<std::size_t>(edge.twin_edge);
        EXPECT_EQ(other.vertices[j], loop.vertices[(k + 1) % loop.vertices.size()]);
        EXPECT_EQ(other.vertices[(j + 1) % other.vertices.size()], loop.vertices[k]);
      }
    }
  }
}

/// Nodes with one cover, two covers, ... for a quick look at a cover system.
std::vector<int> covers_per_node(const CoverSystem& cs) {
  std::vector<int> counts;
  for (const auto& covers : cs.node_covers)
    counts.push_back(static_cast<int>(covers.size()));
  return counts;
}

std::vector<int> elements_per_triangle(const CoverSystem& cs, const MathMesh& math) {
  std::vector<int> counts(static_cast<std::size_t>(math.n_triangles()), 0);
  for (const Element& e : cs.elements)
    ++counts[static_cast<std::size_t>(e.triangle)];
  return counts;
}

// ---- Shi 1997, Figures 4.1 and 4.2 ---------------------------------------------------------

/// The six-node mesh of Shi's Figures 4.1 and 4.2 (nodes 1..6 become 0..5): node 1 at the
/// top, 2 and 3 below it, 4, 5, 6 at the bottom; triangles 1-2-3, 2-4-5, 2-5-3, 3-5-6.
MathMesh shi_figure_4_1_mesh() {
  MathMesh math;
  math.nodes = {{1.0, 2.0}, {0.5, 1.0}, {1.5, 1.0}, {0.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}};
  // Shi's node order, reordered only where needed to make each triangle counter-clockwise.
  math.triangles = {{0, 1, 2}, {1, 3, 4}, {1, 4, 2}, {2, 4, 5}};
  return math;
}

PhysicalMesh shi_big_triangle(std::vector<NamedCurve> joints) {
  return physical_of({{"rock", {{{{0.0, 0.0}, {2.0, 0.0}, {1.0, 2.0}}, {}}}}}, std::move(joints));
}

TEST(CoverMesher, ShiFigure41CompleteJointReproducesHisTables) {
  // The joint crosses the material completely at y = 0.5, through triangles 2-4-5, 2-5-3
  // and 3-5-6 but not 1-2-3 (Shi: "the only joint ... divided completely the material").
  const MathMesh math = shi_figure_4_1_mesh();
  const PhysicalMesh physical = shi_big_triangle({curve("joint", {{0.25, 0.5}, {1.75, 0.5}})});
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  // His table "mathematical covers and physical covers of Figure 4.1".
  EXPECT_EQ(covers_per_node(cs), (std::vector<int>{1, 2, 2, 2, 2, 2}));
  // His table "Physical covers or nodes of elements of Figure 4.1".
  EXPECT_EQ(elements_per_triangle(cs, math), (std::vector<int>{1, 2, 2, 2}));
  EXPECT_EQ(cs.n_blocks(), 2);
  // "any manifold element divided by this joint have completely different nodes".
  for (int t = 1; t < 4; ++t) {
    std::vector<const Element*> pair;
    for (const Element& e : cs.elements) {
      if (e.triangle == t)
        pair.push_back(&e);
    }
    ASSERT_EQ(pair.size(), 2U);
    for (int k = 0; k < 3; ++k)
      EXPECT_NE(pair[0]->covers[static_cast<std::size_t>(k)],
                pair[1]->covers[static_cast<std::size_t>(k)]);
    EXPECT_NE(pair[0]->block, pair[1]->block);
  }
}

TEST(CoverMesher, ShiFigure42PartialJointReproducesHisTables) {
  // The joint enters at the left boundary, crosses 2-4-5 and 2-5-3 and ends inside 3-5-6.
  const MathMesh math = shi_figure_4_1_mesh();
  const PhysicalMesh physical = shi_big_triangle({curve("joint", {{0.25, 0.5}, {1.5, 0.5}})});
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  // V2 and V4 are split, the others are not (his second cover table).
  EXPECT_EQ(covers_per_node(cs), (std::vector<int>{1, 2, 1, 2, 1, 1}));
  // 1-2-3: one element; 2-4-5: two sharing 5_1; 2-5-3: two sharing 5_1 and 3_1; 3-5-6: one.
  EXPECT_EQ(elements_per_triangle(cs, math), (std::vector<int>{1, 2, 2, 1}));
  EXPECT_EQ(cs.n_blocks(), 1);
  EXPECT_TRUE(cs.blocks[0].has_crack_tip);
  std::map<int, std::vector<std::array<int, 3>>> by_triangle;
  for (const Element& e : cs.elements)
    by_triangle[e.triangle].push_back(e.covers);
  // Triangle 2-4-5 (index 1, nodes 2, 4, 5): different covers at 2 and 4, same at 5.
  EXPECT_NE(by_triangle[1][0][0], by_triangle[1][1][0]);
  EXPECT_NE(by_triangle[1][0][1], by_triangle[1][1][1]);
  EXPECT_EQ(by_triangle[1][0][2], by_triangle[1][1][2]);
  // Triangle 2-5-3 (index 2, nodes 2, 5, 3): different at 2 only.
  EXPECT_NE(by_triangle[2][0][0], by_triangle[2][1][0]);
  EXPECT_EQ(by_triangle[2][0][1], by_triangle[2][1][1]);
  EXPECT_EQ(by_triangle[2][0][2], by_triangle[2][1][2]);
}

// ---- regular meshes and degenerate geometry ---------------------------------------------

MathMesh regular_over(const PhysicalMesh& physical, double size) {
  return make_regular_math_mesh(material_bounding_box(physical), size);
}

TEST(CoverMesher, SquareWithoutJointsIsOneBlockWithOneCoverPerNode) {
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 3.0, 2.0)});
  const MathMesh math = regular_over(physical, 0.37);
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1);
  EXPECT_FALSE(cs.blocks[0].has_crack_tip);
  for (const int n : covers_per_node(cs))
    EXPECT_LE(n, 1);
  for (const int n : elements_per_triangle(cs, math))
    EXPECT_LE(n, 1);
  ASSERT_EQ(cs.n_loops(), 1);
  EXPECT_GT(signed_area(cs.loops[0].vertices), 0.0); // outer loop counter-clockwise
}

TEST(CoverMesher, ConformingMeshWithoutJointsIsTheFemMesh) {
  // Boundary along math edges: every triangle is one element with its three node covers.
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 2.0, 1.0)});
  MathMesh math;
  for (int j = 0; j <= 4; ++j) {
    for (int i = 0; i <= 8; ++i)
      math.nodes.emplace_back(0.25 * i, 0.25 * j);
  }
  for (int j = 0; j < 4; ++j) {
    for (int i = 0; i < 8; ++i) {
      const int a = 9 * j + i;
      math.triangles.push_back({a, a + 1, a + 10});
      math.triangles.push_back({a, a + 10, a + 9});
    }
  }
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_covers(), math.n_nodes());
  EXPECT_EQ(cs.n_elements(), math.n_triangles());
  ASSERT_EQ(cs.n_loops(), 1);
  EXPECT_EQ(cs.loops[0].n_vertices(), 24); // split at every boundary node
}

TEST(CoverMesher, CompleteJointCutsTheSquareIntoTwoBlocksWithIndependentCovers) {
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 2.0, 2.0)},
                                            {curve("bedding", {{0.0, 0.83}, {2.0, 1.21}})});
  const MathMesh math = regular_over(physical, 0.3);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  ASSERT_EQ(cs.n_blocks(), 2);
  EXPECT_NEAR(cs.blocks[0].area + cs.blocks[1].area, 4.0, 1e-12);
  // The lower block is a trapezoid of heights 0.83 and 1.21 over a width of 2.
  EXPECT_NEAR(std::max(cs.blocks[0].area, cs.blocks[1].area), 2.0 * (0.83 + 1.21) / 2.0, 1e-12);
  // No cover spans both blocks (checked by expect_invariants through cover.block), and
  // some nodes near the joint have one cover on each side.
  int split = 0;
  for (const int n : covers_per_node(cs))
    split += n == 2;
  EXPECT_GT(split, 0);
  // The joint faces are boundary edges with twins on the other block.
  int joint_edges = 0;
  for (const BoundaryLoop& loop : cs.loops) {
    for (const BoundaryEdge& edge : loop.edges) {
      if (edge.joint >= 0) {
        ++joint_edges;
        EXPECT_GE(edge.twin_loop, 0);
        EXPECT_NE(cs.loops[static_cast<std::size_t>(edge.twin_loop)].block, loop.block);
      }
    }
  }
  EXPECT_GT(joint_edges, 0);
}

TEST(CoverMesher, PartialJointEndingInsideATriangleKeepsOneBlock) {
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 2.0, 1.0)},
                                            {curve("crack", {{0.0, 0.52}, {1.13, 0.47}})});
  const MathMesh math = regular_over(physical, 0.25);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  ASSERT_EQ(cs.n_blocks(), 1);
  EXPECT_TRUE(cs.blocks[0].has_crack_tip);
  // The crack faces are on the outer loop (a slit from the left boundary): one loop only.
  ASSERT_EQ(cs.n_loops(), 1);
  int crack_edges = 0;
  for (const BoundaryEdge& edge : cs.loops[0].edges)
    crack_edges += edge.joint >= 0;
  EXPECT_GE(crack_edges, 2 * 5); // both faces, split by math edges
}

TEST(CoverMesher, CrackInsideTheMaterialMakesASlitLoop) {
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 2.0, 1.0)},
                                            {curve("crack", {{0.61, 0.43}, {1.37, 0.58}})});
  const MathMesh math = regular_over(physical, 0.2);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  ASSERT_EQ(cs.n_blocks(), 1);
  ASSERT_EQ(cs.n_loops(), 2);
  EXPECT_NEAR(signed_area(cs.loops[1].vertices), 0.0, 1e-15);
  // Nodes in the middle of the crack have two covers, nodes near the tips one.
  int split = 0;
  for (const int n : covers_per_node(cs))
    split += n == 2;
  EXPECT_GT(split, 2);
}

/// Index of the math node at (x, y) to 1e-12, for joints drawn exactly through nodes.
int node_at(const MathMesh& math, double x, double y) {
  for (int n = 0; n < math.n_nodes(); ++n) {
    const Point2& p = math.nodes[static_cast<std::size_t>(n)];
    if (std::abs(p.x() - x) < 1e-12 && std::abs(p.y() - y) < 1e-12)
      return n;
  }
  ADD_FAILURE() << "no node at " << x << ", " << y;
  return 0;
}

TEST(CoverMesher, JointThroughMathNodesAndAlongMathEdges) {
  // Regular mesh of size 0.5 (rows h apart). Both joints are polylines whose vertices ARE
  // math nodes, so they run exactly along math edges and through nodes: one along row 2,
  // one along the 60-degree edges from (0.5, 0) to (1.5, 4h), crossing at the node (1, 2h).
  const double h = 0.5 * std::sqrt(3.0) / 2.0;
  PhysicalMesh physical;
  physical.source = "test.geo";
  physical.regions = {rectangle("rock", 0.0, 0.0, 3.0, 4.0 * h)};
  const MathMesh math = make_regular_math_mesh(
      material_bounding_box(physical_of({rectangle("r", 0.0, 0.0, 3.0, 4.0 * h)})), 0.5);
  auto node = [&](double x, double row) {
    return math.nodes[static_cast<std::size_t>(node_at(math, x, row * h))];
  };
  physical.curves = {curve("along_row", {node(0.0, 2), node(3.0, 2)}),
                     curve("through_nodes", {node(0.5, 0), node(0.75, 1), node(1.0, 2),
                                             node(1.25, 3), node(1.5, 4)})};
  validate_physical_mesh(physical);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 4);
  EXPECT_EQ(cs.stats.tiny_covers, 0); // nothing passes near a node without hitting it
  // A node on the row joint has one cover per side; the crossing node one per quadrant.
  for (int n = 0; n < math.n_nodes(); ++n) {
    const Point2& p = math.nodes[static_cast<std::size_t>(n)];
    if (std::abs(p.y() - 2.0 * h) > 1e-12 || p.x() <= 0.0 || p.x() >= 3.0)
      continue;
    const std::size_t expected = std::abs(p.x() - 1.0) < 1e-12 ? 4U : 2U;
    EXPECT_EQ(cs.node_covers[static_cast<std::size_t>(n)].size(), expected) << "x=" << p.x();
  }
  // Every element lies on one side: no triangle is split (the joints follow math edges).
  for (const int count : elements_per_triangle(cs, math))
    EXPECT_LE(count, 1);
}

TEST(CoverMesher, JointMissingANodeByRoundingIsExactAndHarmless) {
  // The straight joint from (0.5, 0) to (1.5, 4h) misses the node (1.25, 3h) by about
  // 1e-16 because 3h is rounded: the exact arrangement cuts a sliver of ~1e-33 m² off the
  // star of a node. The result must stay consistent, and the sliver covers must get
  // extension elements instead of unknowns of their own.
  const double h = 0.5 * std::sqrt(3.0) / 2.0;
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 3.0, 4.0 * h)},
                                            {curve("along_row", {{0.0, 2.0 * h}, {3.0, 2.0 * h}}),
                                             curve("near_nodes", {{0.5, 0.0}, {1.5, 4.0 * h}})});
  const MathMesh math = regular_over(physical, 0.5);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 4);
  EXPECT_GT(cs.stats.tiny_covers, 0);
  for (const Cover& cover : cs.covers) {
    if (cover.area < 1e-20) {
      EXPECT_GE(cover.extension_element, 0);
    }
  }
}

TEST(CoverMesher, JointsEndingExactlyOnNodeOnEdgeAndOnBoundary) {
  const double h = 0.5 * std::sqrt(3.0) / 2.0;
  const PhysicalMesh physical = physical_of(
      {rectangle("rock", 0.0, 0.0, 3.0, 6.0 * h)},
      {curve("ends_on_node", {{0.3, 0.1}, {1.0, 2.0 * h}}),
       curve("ends_on_edge", {{2.9, 0.1}, {2.5, 3.0 * h}}), // between nodes 2.25 and 2.75
       curve("ends_on_boundary", {{1.2, 5.0 * h}, {0.0, 5.5 * h}})});
  const MathMesh math = regular_over(physical, 0.5);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1);
  EXPECT_TRUE(cs.blocks[0].has_crack_tip);
}

TEST(CoverMesher, CrossingJointsAndTJunctionsMakeFiveBlocks) {
  const PhysicalMesh physical =
      physical_of({rectangle("rock", 0.0, 0.0, 2.0, 2.0)},
                  {curve("set_a", {{0.0, 0.75}, {2.0, 1.25}}),    // crosses completely
                   curve("set_b", {{1.03, 0.0}, {0.98, 2.0}}),    // crosses set_a (X)
                   curve("set_c", {{1.5, 1.125}, {1.52, 0.0}})}); // starts exactly on set_a (T)
  const MathMesh math = regular_over(physical, 0.23);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 5);
  EXPECT_FALSE(cs.blocks[0].has_crack_tip);
}

TEST(CoverMesher, CoincidentOverlappingJointsActAsOne) {
  const PhysicalMesh physical = physical_of(
      {rectangle("rock", 0.0, 0.0, 2.0, 1.0)},
      {curve("first", {{0.0, 0.41}, {1.4, 0.41}}), curve("second", {{0.7, 0.41}, {2.0, 0.41}})});
  const MathMesh math = regular_over(physical, 0.2);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 2); // together they cross the material completely
  EXPECT_NEAR(std::min(cs.blocks[0].area, cs.blocks[1].area), 0.82, 1e-12);
}

TEST(CoverMesher, JointsOutsideOrPartlyOutsideTheMaterial) {
  const PhysicalMesh physical = physical_of(
      {rectangle("rock", 0.0, 0.0, 1.0, 1.0)},
      {curve("outside", {{2.0, 0.0}, {3.0, 1.0}}), curve("partly", {{-1.0, 0.31}, {0.62, 0.31}})});
  const MathMesh math = regular_over(physical, 0.2);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1);
  ASSERT_EQ(cs.warnings.size(), 1U);
  EXPECT_NE(cs.warnings[0].find("\"outside\""), std::string::npos);
}

TEST(CoverMesher, TwoMaterialsSharingACurveAreBondedAndSplitOnlyElements) {
  const PhysicalMesh physical =
      physical_of({rectangle("soft", 0.0, 0.0, 2.0, 0.77), rectangle("hard", 0.0, 0.77, 2.0, 2.0)},
                  {curve("interface", {{0.0, 0.77}, {2.0, 0.77}})});
  const MathMesh math = regular_over(physical, 0.3);
  // The interface is a named curve but not a joint: it must not cut.
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1);
  EXPECT_EQ(cs.blocks[0].materials, (std::vector<int>{0, 1}));
  for (const int n : covers_per_node(cs))
    EXPECT_LE(n, 1);
  // Triangles on the interface hold one element per material with the same covers.
  int shared = 0;
  for (std::size_t i = 0; i < cs.elements.size(); ++i) {
    for (std::size_t j = i + 1; j < cs.elements.size(); ++j) {
      if (cs.elements[i].triangle == cs.elements[j].triangle) {
        EXPECT_EQ(cs.elements[i].covers, cs.elements[j].covers);
        EXPECT_NE(cs.elements[i].material, cs.elements[j].material);
        ++shared;
      }
    }
  }
  EXPECT_GT(shared, 5);
  // The interface curve has pieces with elements on both sides.
  ASSERT_FALSE(cs.curve_pieces[0].empty());
  double length = 0.0;
  for (const CurvePiece& piece : cs.curve_pieces[0]) {
    EXPECT_GE(piece.left_element, 0);
    EXPECT_GE(piece.right_element, 0);
    length += (piece.b - piece.a).norm();
  }
  EXPECT_NEAR(length, 2.0, 1e-12);
}

TEST(CoverMesher, TheSameInterfaceAsAJointSeparatesTheMaterials) {
  const PhysicalMesh physical =
      physical_of({rectangle("soft", 0.0, 0.0, 2.0, 0.77), rectangle("hard", 0.0, 0.77, 2.0, 2.0)},
                  {curve("interface", {{0.0, 0.77}, {2.0, 0.77}})});
  const MathMesh math = regular_over(physical, 0.3);
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 2);
}

TEST(CoverMesher, HolesAndBoundaryAlongMathEdges) {
  // The outer boundary y = 0 and y = 4h lies on math rows; the hole is a hexagon.
  const double h = 0.5 * std::sqrt(3.0) / 2.0;
  MaterialRegion plate = rectangle("plate", 0.0, 0.0, 4.0, 8.0 * h);
  Loop hole;
  for (int k = 0; k < 6; ++k) {
    const double a = 2.0 * std::acos(-1.0) * k / 6.0 + 0.1;
    hole.emplace_back(2.0 + 0.61 * std::cos(a), 4.0 * h + 0.61 * std::sin(a));
  }
  plate.polygons[0].holes.push_back(hole);
  const PhysicalMesh physical = physical_of({plate});
  const MathMesh math = regular_over(physical, 0.5);
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1);
  ASSERT_EQ(cs.n_loops(), 2);
  EXPECT_LT(signed_area(cs.loops[1].vertices), 0.0); // the hole loop is clockwise
}

TEST(CoverMesher, SmallHoleInsideOneTriangleGivesAnElementWithAHole) {
  MaterialRegion plate = rectangle("plate", 0.0, 0.0, 1.0, 1.0);
  plate.polygons[0].holes.push_back({{0.30, 0.10}, {0.33, 0.10}, {0.33, 0.12}, {0.30, 0.12}});
  const PhysicalMesh physical = physical_of({plate});
  const MathMesh math = regular_over(physical, 0.5);
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  int with_hole = 0;
  for (const Element& e : cs.elements) {
    for (const Polygon& p : e.polygons)
      with_hole += !p.holes.empty();
  }
  EXPECT_EQ(with_hole, 1);
}

TEST(CoverMesher, JointsCloseToNodesGiveTinyCoversExtensionElements) {
  // A joint passing 1e-9 from a row of nodes leaves covers whose support is a sliver.
  const double h = 0.5 * std::sqrt(3.0) / 2.0;
  for (const double gap : {1e-6, 1e-9, 1e-12}) {
    const PhysicalMesh physical =
        physical_of({rectangle("rock", 0.0, 0.0, 3.0, 4.0 * h)},
                    {curve("joint", {{0.0, 2.0 * h + gap}, {3.0, 2.0 * h + gap}})});
    const MathMesh math = regular_over(physical, 0.5);
    const CoverSystem cs = build_cover_system(math, physical, all_curves(physical));
    expect_invariants(cs, math, physical);
    EXPECT_EQ(cs.n_blocks(), 2);
    EXPECT_GT(cs.stats.tiny_covers, 0) << "gap " << gap;
    // Every cover with unknowns of its own has at least 1e-3 of its star, and every
    // tiny one has an extension element.
    const double triangle_area = std::sqrt(3.0) / 4.0 * 0.5 * 0.5;
    std::vector<double> star(static_cast<std::size_t>(math.n_nodes()), 0.0);
    for (const auto& t : math.triangles) {
      for (const int n : t)
        star[static_cast<std::size_t>(n)] += triangle_area;
    }
    for (const Cover& cover : cs.covers) {
      const bool tiny = cover.area < 1e-3 * star[static_cast<std::size_t>(cover.node)];
      EXPECT_EQ(tiny, cover.extension_element >= 0) << "gap " << gap;
    }
  }
}

TEST(CoverMesher, OverlappingRegionsAreAnInputErrorNamingBoth) {
  const PhysicalMesh physical = physical_of(
      {rectangle("granite", 0.0, 0.0, 2.0, 1.0), rectangle("clay", 1.0, 0.5, 3.0, 2.0)});
  const MathMesh math = regular_over(physical, 0.3);
  try {
    (void)build_cover_system(math, physical, {});
    FAIL() << "overlap not detected";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("test.geo"), std::string::npos) << message;
    EXPECT_NE(message.find("granite"), std::string::npos) << message;
    EXPECT_NE(message.find("clay"), std::string::npos) << message;
  }
}

TEST(CoverMesher, MathMeshNotCoveringTheMaterialIsAnInputError) {
  const PhysicalMesh physical = physical_of({rectangle("rock", 0.0, 0.0, 2.0, 1.0)});
  BoundingBox half;
  half.extend({0.0, 0.0});
  half.extend({1.0, 1.0});
  const MathMesh math = make_regular_math_mesh(half, 0.25);
  EXPECT_THROW((void)build_cover_system(math, physical, {}), InputError);
}

TEST(CoverMesher, BoundaryNodesAHairInsideTheMaterialAreAnErrorUntilTheMeshIsFitted) {
  // The top edge runs from (1, 1 - u) to (0, 1), u one unit in the last place below 1:
  // what gmsh's own rounding made of a quarter circle's end. A mesh generator puts the node
  // at x = 0.5 at y = 1 - u, below the edge's exact 1 - u/2, so a sliver of material above
  // it is in no triangle and the top edge has no elements from x = 0.5 on: a pressure there
  // acted on half the edge (before 2026-11-26, silently).
  const double below_one = std::nextafter(1.0, 0.0);
  PhysicalMesh physical;
  physical.source = "test.geo";
  physical.regions = {{"rock", {{{{0.0, 0.0}, {1.0, 0.0}, {1.0, below_one}, {0.0, 1.0}}, {}}}}};
  physical.curves = {curve("top", {{1.0, below_one}, {0.0, 1.0}})};
  validate_physical_mesh(physical);
  MathMesh math;
  math.nodes = {{0.0, 0.0}, {1.0, 0.0}, {1.0, below_one}, {0.5, below_one}, {0.0, 1.0}};
  math.triangles = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  try {
    (void)build_cover_system(math, physical, {});
    ADD_FAILURE() << "no InputError for a math mesh that misses a sliver of the material";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("test.geo"), std::string::npos) << message;
    EXPECT_NE(message.find("uncovered"), std::string::npos) << message;
  }

  EXPECT_EQ(fit_math_mesh_to_boundary(math, physical), 1);
  // Moved outward (up) by units in the last place, nothing else touched.
  EXPECT_GT(math.nodes[3].y(), below_one);
  EXPECT_LT(math.nodes[3].y() - below_one, 1e-15);
  EXPECT_EQ(math.nodes[3].x(), 0.5);
  EXPECT_EQ(math.nodes[4], Point2(0.0, 1.0));
  EXPECT_EQ(fit_math_mesh_to_boundary(math, physical), 0) << "fitting twice moves nothing";
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  double length = 0.0;
  for (const CurvePiece& piece : cs.curve_pieces[0]) {
    EXPECT_TRUE(piece.left_element >= 0 || piece.right_element >= 0)
        << "a piece of the top edge without its element";
    length += (piece.b - piece.a).norm();
  }
  // The top edge's whole length, to rounding of the piece ends (1e-15 of 1 m).
  EXPECT_NEAR(length, 1.0, 1e-15);
}

TEST(CoverMesher, NamedBoundaryCurveHasPiecesAlongItsWholeLength) {
  const PhysicalMesh physical = physical_of(
      {rectangle("rock", 0.0, 0.0, 2.0, 1.0)},
      {curve("base", {{0.0, 0.0}, {2.0, 0.0}}), curve("monitor_line", {{0.1, 0.5}, {1.9, 0.55}})});
  const MathMesh math = regular_over(physical, 0.3);
  const CoverSystem cs = build_cover_system(math, physical, {});
  expect_invariants(cs, math, physical);
  EXPECT_EQ(cs.n_blocks(), 1); // named curves that are not joints never cut
  for (int c = 0; c < 2; ++c) {
    double length = 0.0;
    for (const CurvePiece& piece : cs.curve_pieces[static_cast<std::size_t>(c)]) {
      length += (piece.b - piece.a).norm();
      EXPECT_TRUE(piece.left_element >= 0 || piece.right_element >= 0);
      if (c == 1) {
        EXPECT_GE(piece.left_element, 0);
        EXPECT_GE(piece.right_element, 0);
      }
    }
    EXPECT_NEAR(length, c == 0 ? 2.0 : std::hypot(1.8, 0.05), 1e-12);
  }
}

TEST(CoverMesher, BlockRegionsGetBlocksAndLoopsButNoElements) {
  const PhysicalMesh physical = physical_of(
      {rectangle("foundation", 0.0, 0.0, 4.0, 1.0), rectangle("blocks", 1.0, 1.0, 3.0, 2.0)},
      {curve("vertical", {{2.0, 1.0}, {2.0, 2.0}}), curve("dangling", {{1.2, 1.5}, {1.6, 1.5}})});
  const MathMesh math = regular_over(physical, 0.3);
  CoverMesherOptions options;
  options.block_regions = {1};
  const CoverSystem cs = build_cover_system(math, physical, all_curves(physical), options);
  // Elements cover the NMM foundation only.
  double nmm = 0.0;
  for (const Element& e : cs.elements) {
    EXPECT_EQ(e.material, 0);
    nmm += e.area;
  }
  EXPECT_NEAR(nmm, 4.0, 1e-12);
  // Two dda/vem blocks of 1 m² each (the dangling joint is ignored with a warning), and
  // the foundation, not bonded to them.
  ASSERT_EQ(cs.n_blocks(), 3);
  int special = 0;
  for (const Block& b : cs.blocks) {
    if (b.elements.empty()) {
      ++special;
      EXPECT_NEAR(b.area, 1.0, 1e-12);
      EXPECT_FALSE(b.has_crack_tip);
      ASSERT_EQ(b.loops.size(), 1U);
      EXPECT_EQ(cs.loops[static_cast<std::size_t>(b.loops[0])].n_vertices(), 4);
    }
  }
  EXPECT_EQ(special, 2);
  bool warned = false;
  for (const std::string& w : cs.warnings)
    warned = warned || w.find("\"dangling\"") != std::string::npos;
  EXPECT_TRUE(warned);
}

} // namespace
} // namespace nmm
