// SPDX-License-Identifier: MIT
// The cover mesher. Overview (docs/cover-mesher.md has the rules and their reasons):
//  1. one exact arrangement of every physical segment (region loops, named curves): the
//     material on each side of every physical edge, blocks, and the boundary loops;
//  2. per math triangle touched by a physical edge, a local arrangement of its three edges
//     and those physical edges: the atoms, the pieces along each triangle edge, and the
//     pieces of every physical edge with the atom on its side;
//  3. union-find over (atom, triangle node) slots across non-cut adjacencies: covers;
//  4. elements, blocks, tiny covers, boundary loops split at math edges, curve pieces.
#include "mesh/cover_mesher.hpp"

#include "mesh/detail/cgal_types.hpp"
#include "mesh/error.hpp"
#include "mesh/union_find.hpp"

#include <CGAL/Arr_batched_point_location.h>

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace nmm {

namespace {

using detail::ExactPoint;
using detail::Kernel;
using detail::LocalArrangement;
using detail::LocalCurveData;
using detail::LocalTraits;
using detail::PhysicalArrangement;
using detail::PhysicalTraits;
using detail::SegmentTraits;

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::size_t to_index(int i) { return static_cast<std::size_t>(i); }

/// Rounds an exact coordinate to double, the same exact value always to the same double
/// (the exact rational is canonical), so a vertex computed in two local arrangements gets
/// bit-identical coordinates in both.
double rounded(const Kernel::FT& value) {
  const auto& approx = value.approx();
  if (approx.inf() == approx.sup())
    return approx.inf();
  return CGAL::to_double(value.exact());
}

Point2 to_point2(const ExactPoint& p) { return {rounded(p.x()), rounded(p.y())}; }

/// An input segment of the global arrangement.
struct SourceSegment {
  Point2 a;
  Point2 b;
  int region = -1; ///< region on the left of a -> b (a region loop edge), else -1
  int curve = -1;  ///< named curve, else -1
  bool joint = false;
};

/// An edge of the global arrangement with what the mesher derives from it.
struct GlobalEdge {
  PhysicalArrangement::Halfedge_handle halfedge; ///< the canonical halfedge (side 0)
  std::array<int, 2> face{-1, -1};               ///< face left of side 0 and of side 1
  bool left_to_right = true;                     ///< direction of the canonical halfedge
  int joint = -1;                                ///< joint curve lying on it, else -1
  bool cut = false;                              ///< separates covers and blocks
  bool needed = false;                           ///< borders NMM material
  std::vector<int> curves;                       ///< named curves lying on it
  ExactPoint source;
  ExactPoint target;
};

/// A piece of a global halfedge inside one triangle, with the atom on its left.
struct HalfedgePiece {
  ExactPoint exact_source;
  Point2 a;
  Point2 b;
  int atom = -1;
};

/// A piece of a triangle edge, walked counter-clockwise, with the atom on its inner side.
struct EdgePiece {
  int atom = -1;
  bool cut = false;
};

struct Atom {
  int triangle = -1;
  int material = -1; ///< -2 while waiting for point location
  int face = -1;     ///< global face
  Polygon polygon;
  double area = 0.0;
};

bool is_left_to_right(const Point2& a, const Point2& b) {
  return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
}

/// Vertices of one connected component of a face boundary, with dangling edges (joint ends
/// inside the face) cancelled: a halfedge followed by its twin is a spike and contributes
/// nothing to area integrals. Bridges to holes are kept (they integrate to zero too, and
/// keep the loop a single closed walk).
template <class Circulator> Loop loop_without_antennas(Circulator ccb) {
  using Handle = decltype(ccb->twin());
  std::vector<Handle> kept;
  Circulator current = ccb;
  do {
    const Handle h = current;
    if (!kept.empty() && kept.back()->twin() == h)
      kept.pop_back();
    else
      kept.push_back(h);
  } while (++current != ccb);
  std::size_t first = 0;
  while (kept.size() - first >= 2 && kept[first]->twin() == kept.back()) {
    ++first;
    kept.pop_back();
  }
  Loop loop;
  if (kept.size() - first < 3)
    return loop;
  loop.reserve(kept.size() - first);
  // Distinct exact vertices closer than rounding become one: no zero-length edges.
  for (std::size_t i = first; i < kept.size(); ++i) {
    const Point2 p = to_point2(kept[i]->source()->point());
    if (loop.empty() || p != loop.back())
      loop.push_back(p);
  }
  while (loop.size() > 1 && loop.front() == loop.back())
    loop.pop_back();
  if (loop.size() < 3)
    loop.clear();
  return loop;
}

/// Calls visit(halfedge) for every halfedge on the boundary of face @p f (outer and inner).
template <class FaceHandle, class Visit>
void for_each_boundary_halfedge(FaceHandle f, Visit visit) {
  if (f->has_outer_ccb()) {
    auto ccb = f->outer_ccb();
    auto current = ccb;
    do {
      visit(current);
    } while (++current != ccb);
  }
  for (auto inner = f->inner_ccbs_begin(); inner != f->inner_ccbs_end(); ++inner) {
    auto ccb = *inner;
    auto current = ccb;
    do {
      visit(current);
    } while (++current != ccb);
  }
}

/// A uniform grid of math triangles by bounding box, to find the triangles a segment meets.
class TriangleGrid {
public:
  explicit TriangleGrid(const MathMesh& math) {
    const BoundingBox box = bounding_box(math.nodes);
    min_ = box.min;
    double total_area = 0.0;
    for (const auto& t : math.triangles) {
      const Point2 e1 = math.nodes[to_index(t[1])] - math.nodes[to_index(t[0])];
      const Point2 e2 = math.nodes[to_index(t[2])] - math.nodes[to_index(t[0])];
      total_area += std::abs(0.5 * (e1.x() * e2.y() - e1.y() * e2.x()));
    }
    const double n = std::max(1, math.n_triangles());
    cell_ = std::sqrt(2.0 * total_area / n);
    const Point2 extent = box.size();
    if (!(cell_ > 0.0))
      cell_ = std::max({extent.x(), extent.y(), 1.0});
    nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_)));
    ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_)));
    // Cap the cell count at a few per triangle so that a mesh of very unequal triangles
    // cannot blow the grid up.
    while (static_cast<double>(nx_) * ny_ > 4.0 * n + 16.0) {
      cell_ *= 1.5;
      nx_ = std::max(1, static_cast<int>(std::ceil(extent.x() / cell_)));
      ny_ = std::max(1, static_cast<int>(std::ceil(extent.y() / cell_)));
    }
    start_.assign(to_index(nx_ * ny_ + 1), 0);
    auto for_cells = [&](int t, auto&& action) {
      const auto& tri = math.triangles[to_index(t)];
      BoundingBox tb;
      for (const int node : tri)
        tb.extend(math.nodes[to_index(node)]);
      const auto [x0, y0] = cell_of(tb.min);
      const auto [x1, y1] = cell_of(tb.max);
      for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x)
          action(y * nx_ + x);
      }
    };
    for (int t = 0; t < math.n_triangles(); ++t)
      for_cells(t, [&](int cell) { ++start_[to_index(cell + 1)]; });
    std::partial_sum(start_.begin(), start_.end(), start_.begin());
    triangles_.resize(to_index(start_.back()));
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (int t = 0; t < math.n_triangles(); ++t)
      for_cells(t, [&](int cell) { triangles_[to_index(fill[to_index(cell)]++)] = t; });
  }

  /// Calls visit(triangle) for every triangle whose box is near the segment a-b (a superset
  /// of the triangles it meets; may repeat triangles).
  template <class Visit>
  void for_triangles_near(const Point2& a, const Point2& b, Visit visit) const {
    const double length = (b - a).norm();
    const int steps = std::max(1, static_cast<int>(std::ceil(2.0 * length / cell_)));
    int last_x = -10;
    int last_y = -10;
    for (int i = 0; i <= steps; ++i) {
      const Point2 p = a + (b - a) * (static_cast<double>(i) / steps);
      const auto [cx, cy] = cell_of(p);
      if (cx == last_x && cy == last_y)
        continue;
      last_x = cx;
      last_y = cy;
      // Samples are half a cell apart: the segment between two samples stays within the
      // 3x3 block of cells around either sample.
      for (int y = std::max(0, cy - 1); y <= std::min(ny_ - 1, cy + 1); ++y) {
        for (int x = std::max(0, cx - 1); x <= std::min(nx_ - 1, cx + 1); ++x) {
          const int cell = y * nx_ + x;
          for (int k = start_[to_index(cell)]; k < start_[to_index(cell + 1)]; ++k)
            visit(triangles_[to_index(k)]);
        }
      }
    }
  }

private:
  std::pair<int, int> cell_of(const Point2& p) const {
    const auto clamp = [](double v, int n) {
      return static_cast<int>(std::clamp(std::floor(v), 0.0, static_cast<double>(n - 1)));
    };
    return {clamp((p.x() - min_.x()) / cell_, nx_), clamp((p.y() - min_.y()) / cell_, ny_)};
  }

  Point2 min_ = Point2::Zero();
  double cell_ = 1.0;
  int nx_ = 1;
  int ny_ = 1;
  std::vector<int> start_;
  std::vector<int> triangles_;
};

/// All the state of one build_cover_system() call.
class CoverMesher {
public:
  CoverMesher(const MathMesh& math,
              const PhysicalMesh& physical,
              std::span<const int> joints,
              const CoverMesherOptions& options)
      : math_(math), physical_(physical), options_(options) {
    is_joint_curve_.assign(physical.curves.size(), 0);
    for (const int c : joints) {
      NMM_ASSERT(c >= 0 && to_index(c) < physical.curves.size(), "joint curve out of range");
      is_joint_curve_[to_index(c)] = 1;
    }
    is_block_region_.assign(physical.regions.size(), 0);
    for (const int r : options.block_regions) {
      NMM_ASSERT(r >= 0 && to_index(r) < physical.regions.size(), "block region out of range");
      is_block_region_[to_index(r)] = 1;
    }
  }

  CoverSystem run() {
    auto start = Clock::now();
    collect_segments();
    build_physical_arrangement();
    label_faces();
    remove_dangling_joints_in_block_regions();
    index_faces_and_edges();
    build_blocks();
    trace_global_loops();
    result_.stats.seconds_physical_arrangement = seconds_since(start);

    start = Clock::now();
    find_triangles_of_edges();
    for (int t = 0; t < math_.n_triangles(); ++t)
      process_triangle(t);
    locate_whole_triangles();
    result_.stats.seconds_cut_triangles = seconds_since(start);

    start = Clock::now();
    build_covers();
    build_elements();
    // Before the loops: material outside the math mesh leaves boundary edges without pieces.
    check_area();
    assign_extension_elements();
    build_block_records();
    build_loops();
    build_curve_pieces();
    report_unused_joints();
    result_.stats.seconds_rest = seconds_since(start);
    result_.stats.math_triangles = math_.n_triangles();
    result_.stats.physical_edges = static_cast<int>(edges_.size());
    return std::move(result_);
  }

private:
  // ---- 1. the global arrangement ----------------------------------------------------

  void collect_segments() {
    for (int r = 0; r < physical_.n_regions(); ++r) {
      for (const Polygon& polygon : physical_.regions[to_index(r)].polygons) {
        // validate_physical_mesh() made outer loops counter-clockwise and holes clockwise:
        // the region lies on the left of every loop edge.
        auto add_loop = [&](const Loop& loop) {
          for (std::size_t k = 0; k < loop.size(); ++k)
            segments_.push_back({loop[k], loop[(k + 1) % loop.size()], r, -1, false});
        };
        add_loop(polygon.outer);
        for (const Loop& hole : polygon.holes)
          add_loop(hole);
      }
    }
    for (std::size_t c = 0; c < physical_.curves.size(); ++c) {
      for (const auto& line : physical_.curves[c].polylines) {
        for (std::size_t k = 0; k + 1 < line.size(); ++k) {
          if (line[k] != line[k + 1]) {
            segments_.push_back(
                {line[k], line[k + 1], -1, static_cast<int>(c), is_joint_curve_[c] != 0});
          }
        }
      }
    }
  }

  void build_physical_arrangement() {
    std::vector<PhysicalTraits::Curve_2> curves;
    curves.reserve(segments_.size());
    for (std::size_t i = 0; i < segments_.size(); ++i) {
      const SourceSegment& s = segments_[i];
      curves.emplace_back(
          SegmentTraits::Curve_2(ExactPoint(s.a.x(), s.a.y()), ExactPoint(s.b.x(), s.b.y())),
          static_cast<int>(i));
    }
    CGAL::insert(arrangement_, curves.begin(), curves.end());
  }

  template <class Halfedge> bool has_region_segment(Halfedge h) const {
    for (const int id : h->curve().data()) {
      if (segments_[to_index(id)].region >= 0)
        return true;
    }
    return false;
  }

  /// Material of every face: a region loop edge names the region on its left; faces bounded
  /// by joints and named curves only inherit from their neighbours.
  void label_faces() {
    for (auto f = arrangement_.faces_begin(); f != arrangement_.faces_end(); ++f)
      f->data().material = -2;
    arrangement_.unbounded_face()->data().material = -1;
    for (auto h = arrangement_.halfedges_begin(); h != arrangement_.halfedges_end(); ++h) {
      const bool halfedge_left_to_right = h->direction() == CGAL::ARR_LEFT_TO_RIGHT;
      for (const int id : h->curve().data()) {
        const SourceSegment& s = segments_[to_index(id)];
        if (s.region < 0 || is_left_to_right(s.a, s.b) != halfedge_left_to_right)
          continue;
        int& material = h->face()->data().material;
        if (material == -2) {
          material = s.region;
        } else if (material != s.region) {
          const std::string other = material >= 0
                                        ? "\"" + physical_.regions[to_index(material)].name + "\""
                                        : std::string("the outside");
          throw InputError(physical_.source + ": material regions \"" +
                           physical_.regions[to_index(s.region)].name + "\" and " + other +
                           " overlap near " + point_text(to_point2(h->source()->point())) +
                           "; every point may belong to one Physical Surface only: make "
                           "touching surfaces share their boundary curve (gmsh: Coherence or "
                           "BooleanFragments) instead of overlapping");
        }
      }
    }
    std::deque<PhysicalArrangement::Face_handle> queue;
    for (auto f = arrangement_.faces_begin(); f != arrangement_.faces_end(); ++f) {
      if (f->data().material != -2)
        queue.push_back(f);
    }
    while (!queue.empty()) {
      const auto f = queue.front();
      queue.pop_front();
      for_each_boundary_halfedge(f, [&](auto h) {
        const auto neighbour = h->twin()->face();
        if (neighbour->data().material == -2 && !has_region_segment(h)) {
          neighbour->data().material = f->data().material;
          queue.push_back(neighbour);
        }
      });
    }
    // A face still unlabelled is bounded only by region loop edges whose region lies on
    // their other side (a hole with nothing inside): it is outside every region.
    for (auto f = arrangement_.faces_begin(); f != arrangement_.faces_end(); ++f) {
      if (f->data().material == -2)
        f->data().material = -1;
    }
  }

  bool is_block_material(int material) const {
    return material >= 0 && is_block_region_[to_index(material)] != 0;
  }
  bool is_nmm_material(int material) const {
    return material >= 0 && is_block_region_[to_index(material)] == 0;
  }

  /// A `dda`/`vem` block is one piece cut out completely: the dangling part of a joint
  /// inside it cannot be represented and is removed (DESIGN.md, "Geometry").
  void remove_dangling_joints_in_block_regions() {
    if (options_.block_regions.empty())
      return;
    std::map<int, Point2> reported;
    for (;;) {
      std::vector<PhysicalArrangement::Halfedge_handle> dangling;
      for (auto e = arrangement_.edges_begin(); e != arrangement_.edges_end(); ++e) {
        if (e->face() != e->twin()->face() || !is_block_material(e->face()->data().material))
          continue;
        int joint = -1;
        for (const int id : e->curve().data()) {
          const SourceSegment& s = segments_[to_index(id)];
          if (s.joint)
            joint = joint < 0 ? s.curve : std::min(joint, s.curve);
        }
        if (joint >= 0) {
          dangling.push_back(e);
          reported.emplace(joint, to_point2(e->source()->point()));
        }
      }
      if (dangling.empty())
        break;
      for (const auto e : dangling)
        arrangement_.remove_edge(e);
    }
    for (const auto& [curve, where] : reported) {
      result_.warnings.push_back(
          "joint \"" + physical_.curves[to_index(curve)].name +
          "\" ends inside a dda/vem region near " + point_text(where) +
          "; a block there is a piece cut out completely, so the dangling part is ignored");
    }
  }

  void index_faces_and_edges() {
    int face_count = 0;
    for (auto f = arrangement_.faces_begin(); f != arrangement_.faces_end(); ++f) {
      f->data().index = face_count++;
      face_material_.push_back(f->data().material);
    }
    for (auto e = arrangement_.edges_begin(); e != arrangement_.edges_end(); ++e) {
      const int g = static_cast<int>(edges_.size());
      e->set_data(g);
      e->twin()->set_data(g);
      GlobalEdge edge;
      edge.halfedge = e;
      edge.left_to_right = e->direction() == CGAL::ARR_LEFT_TO_RIGHT;
      edge.face = {e->face()->data().index, e->twin()->face()->data().index};
      edge.source = e->source()->point();
      edge.target = e->target()->point();
      for (const int id : e->curve().data()) {
        const SourceSegment& s = segments_[to_index(id)];
        if (s.curve >= 0 &&
            std::find(edge.curves.begin(), edge.curves.end(), s.curve) == edge.curves.end()) {
          edge.curves.push_back(s.curve);
        }
        if (s.joint)
          edge.joint = edge.joint < 0 ? s.curve : std::min(edge.joint, s.curve);
      }
      std::sort(edge.curves.begin(), edge.curves.end());
      const int left = face_material_[to_index(edge.face[0])];
      const int right = face_material_[to_index(edge.face[1])];
      const bool material_left = left >= 0;
      const bool material_right = right >= 0;
      // Cuts: joints inside material, the boundary between material and void, and any
      // boundary of a dda/vem region (its blocks are separate bodies, never bonded).
      edge.cut = (material_left != material_right) ||
                 (material_left && material_right &&
                  (edge.joint >= 0 ||
                   (left != right && (is_block_material(left) || is_block_material(right)))));
      edge.needed = is_nmm_material(left) || is_nmm_material(right);
      edges_.push_back(std::move(edge));
    }
  }

  /// Blocks: material faces joined across edges that are not cuts (bonded interfaces and
  /// named curves), so a partial joint, an antenna of its face, does not separate.
  void build_blocks() {
    UnionFind faces(face_material_.size());
    for (const GlobalEdge& e : edges_) {
      if (!e.cut && face_material_[to_index(e.face[0])] >= 0 &&
          face_material_[to_index(e.face[1])] >= 0) {
        faces.unite(e.face[0], e.face[1]);
      }
    }
    face_block_.assign(face_material_.size(), -1);
    std::vector<int> root_block(face_material_.size(), -1);
    for (std::size_t f = 0; f < face_material_.size(); ++f) {
      if (face_material_[f] < 0)
        continue;
      const int root = faces.find(static_cast<int>(f));
      if (root_block[to_index(root)] < 0) {
        root_block[to_index(root)] = static_cast<int>(result_.blocks.size());
        result_.blocks.emplace_back();
      }
      face_block_[f] = root_block[to_index(root)];
      Block& block = result_.blocks[to_index(face_block_[f])];
      if (std::find(block.materials.begin(), block.materials.end(), face_material_[f]) ==
          block.materials.end()) {
        block.materials.push_back(face_material_[f]);
      }
    }
    for (Block& block : result_.blocks)
      std::sort(block.materials.begin(), block.materials.end());
    for (const GlobalEdge& e : edges_) {
      if (e.cut && e.joint >= 0 && face_block_[to_index(e.face[0])] >= 0 &&
          face_block_[to_index(e.face[0])] == face_block_[to_index(e.face[1])]) {
        result_.blocks[to_index(face_block_[to_index(e.face[0])])].has_crack_tip = true;
      }
    }
  }

  int halfedge_id(PhysicalArrangement::Halfedge_const_handle h) const {
    const int g = h->data();
    return 2 * g +
           (h == PhysicalArrangement::Halfedge_const_handle(edges_[to_index(g)].halfedge) ? 0 : 1);
  }
  int face_of_halfedge(int id) const { return edges_[to_index(id / 2)].face[to_index(id % 2)]; }

  /// Boundary loops of the blocks as sequences of global halfedges with material on their
  /// left: from a cut halfedge, the next one is found by rotating around its target across
  /// edges that are not cuts (Shi 1997, chapter 6.1: the contact edges are block
  /// boundaries and both sides of joints).
  void trace_global_loops() {
    std::vector<char> visited(2 * edges_.size(), 0);
    for (std::size_t g = 0; g < edges_.size(); ++g) {
      if (!edges_[g].cut)
        continue;
      for (int side = 0; side < 2; ++side) {
        const int id = 2 * static_cast<int>(g) + side;
        if (visited[to_index(id)] || face_material_[to_index(face_of_halfedge(id))] < 0)
          continue;
        PhysicalArrangement::Halfedge_const_handle start = edges_[g].halfedge;
        if (side == 1)
          start = start->twin();
        std::vector<int> loop;
        auto current = start;
        do {
          const int current_id = halfedge_id(current);
          NMM_ASSERT(!visited[to_index(current_id)], "boundary loop revisits a halfedge");
          visited[to_index(current_id)] = 1;
          loop.push_back(current_id);
          auto next = current->next();
          while (!edges_[to_index(next->data())].cut)
            next = next->twin()->next();
          current = next;
        } while (current != start && loop.size() <= 2 * edges_.size());
        global_loops_.push_back(std::move(loop));
      }
    }
  }

  // ---- 2. the triangles ---------------------------------------------------------------

  void find_triangles_of_edges() {
    triangle_edges_.assign(to_index(math_.n_triangles()), {});
    const TriangleGrid grid(math_);
    std::vector<int> stamp(to_index(math_.n_triangles()), -1);
    for (std::size_t g = 0; g < edges_.size(); ++g) {
      const GlobalEdge& e = edges_[g];
      if (!e.needed)
        continue;
      const Kernel::Segment_2 segment(e.source, e.target);
      grid.for_triangles_near(to_point2(e.source), to_point2(e.target), [&](int t) {
        if (stamp[to_index(t)] == static_cast<int>(g))
          return;
        stamp[to_index(t)] = static_cast<int>(g);
        const auto& tri = math_.triangles[to_index(t)];
        const Kernel::Triangle_2 triangle(corner(tri[0]), corner(tri[1]), corner(tri[2]));
        if (CGAL::do_intersect(segment, triangle))
          triangle_edges_[to_index(t)].push_back(static_cast<int>(g));
      });
    }
  }

  ExactPoint corner(int node) const {
    const Point2& p = math_.nodes[to_index(node)];
    return {p.x(), p.y()};
  }

  Polygon triangle_polygon(int t) const {
    const auto& tri = math_.triangles[to_index(t)];
    return {{math_.nodes[to_index(tri[0])], math_.nodes[to_index(tri[1])],
             math_.nodes[to_index(tri[2])]},
            {}};
  }

  int new_atom(int t, int material, int face, Polygon polygon) {
    Atom atom;
    atom.triangle = t;
    atom.material = material;
    atom.face = face;
    atom.area = area(polygon);
    atom.polygon = std::move(polygon);
    atoms_.push_back(std::move(atom));
    return static_cast<int>(atoms_.size()) - 1;
  }

  void process_triangle(int t) {
    const auto& tri = math_.triangles[to_index(t)];
    triangle_first_atom_.push_back(static_cast<int>(atoms_.size()));
    if (triangle_edges_[to_index(t)].empty()) {
      // Untouched by any physical edge: one atom, the whole triangle; material by location.
      const int atom = new_atom(t, -2, -1, triangle_polygon(t));
      pending_location_.push_back(atom);
      triangle_cut_index_.push_back(-1);
      return;
    }
    ++result_.stats.cut_triangles;
    local_.clear();
    std::array<ExactPoint, 3> corners{corner(tri[0]), corner(tri[1]), corner(tri[2])};
    std::vector<LocalTraits::Curve_2> curves;
    curves.reserve(3 + triangle_edges_[to_index(t)].size());
    std::array<bool, 3> edge_left_to_right{};
    for (unsigned k = 0; k < 3; ++k) {
      const ExactPoint& a = corners[k];
      const ExactPoint& b = corners[(k + 1) % 3];
      edge_left_to_right[k] = CGAL::compare_xy(a, b) == CGAL::SMALLER;
      curves.emplace_back(SegmentTraits::Curve_2(a, b), LocalCurveData{1U << k, -1});
    }
    for (const int g : triangle_edges_[to_index(t)]) {
      curves.emplace_back(
          SegmentTraits::Curve_2(edges_[to_index(g)].source, edges_[to_index(g)].target),
          LocalCurveData{0U, g});
    }
    // A handful of curves: incremental (zone) insertion beats the aggregated sweep, whose
    // per-call allocations dominate the cost for so few (bench_cover_mesher speed).
    for (const auto& c : curves)
      CGAL::insert(local_, c);

    // Inner faces: left of the triangle edges walked counter-clockwise, and everything
    // reachable from there without crossing a triangle edge.
    for (auto f = local_.faces_begin(); f != local_.faces_end(); ++f)
      f->set_data(-2);
    std::vector<LocalArrangement::Face_handle> inner;
    LocalArrangement::Halfedge_handle start;
    bool have_start = false;
    for (auto h = local_.halfedges_begin(); h != local_.halfedges_end(); ++h) {
      const unsigned bits = h->curve().data().triangle_edges;
      if (bits == 0)
        continue;
      const int k = std::countr_zero(bits);
      NMM_ASSERT(std::popcount(bits) == 1, "degenerate math triangle");
      if ((h->direction() == CGAL::ARR_LEFT_TO_RIGHT) != edge_left_to_right[to_index(k)])
        continue;
      if (h->face()->data() == -2) {
        h->face()->set_data(-1);
        inner.push_back(h->face());
      }
      if (k == 0 && h->source()->point() == corners[0]) {
        start = h;
        have_start = true;
      }
    }
    NMM_ASSERT(have_start, "no halfedge leaves the first corner of a cut triangle");
    for (std::size_t i = 0; i < inner.size(); ++i) {
      for_each_boundary_halfedge(inner[i], [&](auto h) {
        if (h->curve().data().triangle_edges != 0)
          return;
        const auto neighbour = h->twin()->face();
        if (neighbour->data() == -2) {
          neighbour->set_data(-1);
          inner.push_back(neighbour);
        }
      });
    }

    // Atoms: the inner faces holding NMM material.
    for (const auto f : inner) {
      int global_face = -1;
      for_each_boundary_halfedge(f, [&](auto h) {
        const int g = h->curve().data().physical_edge;
        if (global_face < 0 && g >= 0)
          global_face = edges_[to_index(g)].face[side_of(h, g)];
      });
      if (global_face < 0) {
        // No physical edge on its boundary: the triangle is only touched at its corners,
        // so this is its only inner face, the whole triangle; locate it like an uncut one.
        NMM_ASSERT(inner.size() == 1, "an inner face without physical edges is not alone");
        const int atom = new_atom(t, -2, -1, triangle_polygon(t));
        pending_location_.push_back(atom);
        f->set_data(atom);
        continue;
      }
      const int material = face_material_[to_index(global_face)];
      if (!is_nmm_material(material))
        continue;
      Polygon polygon;
      polygon.outer = loop_without_antennas(f->outer_ccb());
      for (auto hole = f->inner_ccbs_begin(); hole != f->inner_ccbs_end(); ++hole) {
        Loop loop = loop_without_antennas(*hole);
        if (!loop.empty())
          polygon.holes.push_back(std::move(loop));
      }
      // An atom thinner than rounding keeps its place in the topology (covers, loops) but
      // has no polygon: its exact area is below 1e-16 of the triangle's.
      if (polygon.outer.empty())
        polygon.holes.clear();
      const int atom = new_atom(t, material, global_face, std::move(polygon));
      f->set_data(atom);
    }

    // Physical pieces with the atom on their left (for loops and curve pieces), and bonds
    // between atoms of this triangle across edges that are not cuts.
    for (const auto f : inner) {
      const int atom = f->data();
      if (atom < 0 || atoms_[to_index(atom)].material == -2)
        continue;
      for_each_boundary_halfedge(f, [&](auto h) {
        const int g = h->curve().data().physical_edge;
        if (g < 0)
          return;
        const GlobalEdge& edge = edges_[to_index(g)];
        if (edge.cut || !edge.curves.empty()) {
          halfedge_pieces_[2 * g + side_of(h, g)].push_back(
              {h->source()->point(), to_point2(h->source()->point()),
               to_point2(h->target()->point()), atom});
        }
        if (!edge.cut && h->curve().data().triangle_edges == 0) {
          const int other = h->twin()->face()->data();
          if (other >= 0 && other != atom)
            bonds_.emplace_back(atom, other);
        }
      });
    }

    // The triangle boundary, counter-clockwise from node 0, split at every vertex on it.
    std::array<std::vector<EdgePiece>, 3> pieces;
    auto current = start;
    do {
      const int k = std::countr_zero(current->curve().data().triangle_edges);
      const int g = current->curve().data().physical_edge;
      pieces[to_index(k)].push_back({current->face()->data(), g >= 0 && edges_[to_index(g)].cut});
      auto next = current->next();
      while (next->curve().data().triangle_edges == 0)
        next = next->twin()->next();
      current = next;
    } while (current != start);
    triangle_cut_index_.push_back(static_cast<int>(cut_pieces_.size()));
    cut_pieces_.push_back(std::move(pieces));
  }

  template <class Halfedge> int side_of(Halfedge h, int g) const {
    return (h->direction() == CGAL::ARR_LEFT_TO_RIGHT) == edges_[to_index(g)].left_to_right ? 0 : 1;
  }

  /// Material of the atoms that are whole triangles, by one batched exact point location
  /// of their centroids (no physical edge meets their interior, so a centroid lies inside a
  /// face of the global arrangement).
  void locate_whole_triangles() {
    if (pending_location_.empty())
      return;
    std::vector<std::pair<ExactPoint, int>> queries;
    queries.reserve(pending_location_.size());
    for (const int atom : pending_location_) {
      const auto& tri = math_.triangles[to_index(atoms_[to_index(atom)].triangle)];
      queries.emplace_back(CGAL::centroid(corner(tri[0]), corner(tri[1]), corner(tri[2])), atom);
    }
    std::sort(queries.begin(), queries.end(), [](const auto& a, const auto& b) {
      return CGAL::compare_xy(a.first, b.first) == CGAL::SMALLER;
    });
    std::vector<ExactPoint> points;
    points.reserve(queries.size());
    for (const auto& q : queries)
      points.push_back(q.first);
    using Result = CGAL::Arr_point_location_result<PhysicalArrangement>::Type;
    std::vector<std::pair<ExactPoint, Result>> located;
    located.reserve(points.size());
    CGAL::locate(arrangement_, points.begin(), points.end(), std::back_inserter(located));
    for (const auto& [point, where] : located) {
      const auto it = std::lower_bound(queries.begin(), queries.end(), point,
                                       [](const auto& q, const ExactPoint& p) {
                                         return CGAL::compare_xy(q.first, p) == CGAL::SMALLER;
                                       });
      NMM_ASSERT(it != queries.end() && it->first == point, "located point not found");
      const auto* face = boost::get<PhysicalArrangement::Face_const_handle>(&where);
      Atom& atom = atoms_[to_index(it->second)];
      if (face == nullptr) {
        // Only edges bordering NMM material cut triangles, so the centroid may lie on any
        // other edge or vertex (a joint inside a dda/vem region, its boundary with void).
        NMM_ASSERT(!borders_nmm_material(where), "a whole-triangle centroid lies on an edge "
                                                 "bordering NMM material");
        atom.material = -1;
        continue;
      }
      const int material = (*face)->data().material;
      atom.material = is_nmm_material(material) ? material : -1;
      atom.face = (*face)->data().index;
    }
  }

  /// Whether a located edge or vertex of the global arrangement borders NMM material.
  template <class Location> bool borders_nmm_material(const Location& where) const {
    if (const auto* h = boost::get<PhysicalArrangement::Halfedge_const_handle>(&where)) {
      return is_nmm_material((*h)->face()->data().material) ||
             is_nmm_material((*h)->twin()->face()->data().material);
    }
    if (const auto* v = boost::get<PhysicalArrangement::Vertex_const_handle>(&where)) {
      if ((*v)->is_isolated())
        return is_nmm_material((*v)->face()->data().material);
      auto h = (*v)->incident_halfedges();
      const auto first = h;
      do {
        if (is_nmm_material(h->face()->data().material) ||
            is_nmm_material(h->twin()->face()->data().material))
          return true;
      } while (++h != first);
    }
    return false;
  }

  // ---- 3. covers and elements ---------------------------------------------------------

  bool is_alive(int atom) const { return atom >= 0 && atoms_[to_index(atom)].material >= 0; }

  /// The pieces of edge k of triangle t, counter-clockwise.
  std::vector<EdgePiece> edge_pieces(int t, int k) const {
    const int cut = triangle_cut_index_[to_index(t)];
    if (cut >= 0)
      return cut_pieces_[to_index(cut)][to_index(k)];
    return {{triangle_first_atom_[to_index(t)], false}};
  }

  void build_covers() {
    UnionFind slots(3 * atoms_.size());
    for (const auto& [a, b] : bonds_) {
      if (!is_alive(a) || !is_alive(b))
        continue;
      for (int k = 0; k < 3; ++k)
        slots.unite(3 * a + k, 3 * b + k);
    }
    // Triangle edges shared by two triangles, found by sorting (node, node) keys.
    std::vector<std::pair<std::uint64_t, int>> keys;
    keys.reserve(3 * to_index(math_.n_triangles()));
    for (int t = 0; t < math_.n_triangles(); ++t) {
      const auto& tri = math_.triangles[to_index(t)];
      for (int k = 0; k < 3; ++k) {
        const auto a = static_cast<std::uint64_t>(tri[to_index(k)]);
        const auto b = static_cast<std::uint64_t>(tri[to_index((k + 1) % 3)]);
        keys.emplace_back(std::min(a, b) << 32 | std::max(a, b), 3 * t + k);
      }
    }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      if (keys[i].first != keys[i + 1].first)
        continue;
      NMM_ASSERT(i + 2 >= keys.size() || keys[i + 2].first != keys[i].first,
                 "a math edge is shared by more than two triangles");
      const int t1 = keys[i].second / 3;
      const int k1 = keys[i].second % 3;
      const int t2 = keys[i + 1].second / 3;
      const int k2 = keys[i + 1].second % 3;
      const std::vector<EdgePiece> p1 = edge_pieces(t1, k1);
      std::vector<EdgePiece> p2 = edge_pieces(t2, k2);
      std::reverse(p2.begin(), p2.end());
      if (p1.size() != p2.size()) {
        throw std::logic_error("cover mesher: the two sides of a math edge are split "
                               "differently (triangles " +
                               std::to_string(t1) + " and " + std::to_string(t2) + ")");
      }
      // Node tri1[k1] is tri2[k2 + 1] and tri1[k1 + 1] is tri2[k2].
      for (std::size_t j = 0; j < p1.size(); ++j) {
        if (p1[j].cut || !is_alive(p1[j].atom) || !is_alive(p2[j].atom))
          continue;
        slots.unite(3 * p1[j].atom + k1, 3 * p2[j].atom + (k2 + 1) % 3);
        slots.unite(3 * p1[j].atom + (k1 + 1) % 3, 3 * p2[j].atom + k2);
      }
    }
    atom_cover_.assign(3 * atoms_.size(), -1);
    std::vector<int> root_cover(3 * atoms_.size(), -1);
    result_.node_covers.assign(to_index(math_.n_nodes()), {});
    for (std::size_t a = 0; a < atoms_.size(); ++a) {
      if (!is_alive(static_cast<int>(a)))
        continue;
      const Atom& atom = atoms_[a];
      for (int k = 0; k < 3; ++k) {
        const int root = slots.find(3 * static_cast<int>(a) + k);
        if (root_cover[to_index(root)] < 0) {
          root_cover[to_index(root)] = result_.n_covers();
          Cover cover;
          cover.node = math_.triangles[to_index(atom.triangle)][to_index(k)];
          cover.block = face_block_[to_index(atom.face)];
          result_.node_covers[to_index(cover.node)].push_back(result_.n_covers());
          result_.covers.push_back(std::move(cover));
        }
        atom_cover_[3 * a + to_index(k)] = root_cover[to_index(root)];
      }
    }
  }

  void build_elements() {
    atom_element_.assign(atoms_.size(), -1);
    for (int t = 0; t < math_.n_triangles(); ++t) {
      const int first = triangle_first_atom_[to_index(t)];
      const int last = t + 1 < math_.n_triangles() ? triangle_first_atom_[to_index(t + 1)]
                                                   : static_cast<int>(atoms_.size());
      const int first_element = result_.n_elements();
      for (int a = first; a < last; ++a) {
        if (!is_alive(a))
          continue;
        Atom& atom = atoms_[to_index(a)];
        const std::array<int, 3> covers{atom_cover_[to_index(3 * a)],
                                        atom_cover_[to_index(3 * a + 1)],
                                        atom_cover_[to_index(3 * a + 2)]};
        int element = -1;
        for (int e = first_element; e < result_.n_elements(); ++e) {
          if (result_.elements[to_index(e)].covers == covers &&
              result_.elements[to_index(e)].material == atom.material) {
            element = e;
            break;
          }
        }
        if (element < 0) {
          element = result_.n_elements();
          Element fresh;
          fresh.triangle = t;
          fresh.covers = covers;
          fresh.material = atom.material;
          fresh.block = face_block_[to_index(atom.face)];
          result_.elements.push_back(std::move(fresh));
        }
        Element& target = result_.elements[to_index(element)];
        NMM_ASSERT(target.block == face_block_[to_index(atom.face)],
                   "atoms of one element lie in different blocks");
        target.area += atom.area;
        if (!atom.polygon.outer.empty())
          target.polygons.push_back(std::move(atom.polygon));
        atom_element_[to_index(a)] = element;
        const double triangle_area = std::abs(signed_area(triangle_polygon(t).outer));
        if (atom.area < 1.0e-12 * triangle_area)
          ++result_.stats.tiny_atoms;
      }
    }
    for (int e = 0; e < result_.n_elements(); ++e) {
      const Element& element = result_.elements[to_index(e)];
      for (const int c : element.covers) {
        result_.covers[to_index(c)].elements.push_back(e);
        result_.covers[to_index(c)].area += element.area;
      }
    }
  }

  /// The tiny-cover rule (docs/cover-mesher.md): a cover with too little support takes its
  /// cover function from the nearest well-posed element of its block (all three covers of
  /// normal size), found among the elements of the covers that share an element with it,
  /// widening the search ring by ring.
  void assign_extension_elements() {
    std::vector<double> star_area(to_index(math_.n_nodes()), 0.0);
    for (int t = 0; t < math_.n_triangles(); ++t) {
      const double a = std::abs(signed_area(triangle_polygon(t).outer));
      for (const int node : math_.triangles[to_index(t)])
        star_area[to_index(node)] += a;
    }
    std::vector<char> tiny(result_.covers.size(), 0);
    for (std::size_t c = 0; c < result_.covers.size(); ++c) {
      const Cover& cover = result_.covers[c];
      tiny[c] = cover.area < options_.min_cover_area_ratio * star_area[to_index(cover.node)];
    }
    auto well_posed = [&](int e) {
      for (const int c : result_.elements[to_index(e)].covers) {
        if (tiny[to_index(c)])
          return false;
      }
      return true;
    };
    std::map<int, double> tiny_blocks;
    for (std::size_t c = 0; c < result_.covers.size(); ++c) {
      if (!tiny[c])
        continue;
      Cover& cover = result_.covers[c];
      const Point2& node = math_.nodes[to_index(cover.node)];
      std::vector<int> frontier = cover.elements;
      std::vector<char> seen_cover(result_.covers.size(), 0);
      seen_cover[c] = 1;
      int best = -1;
      double best_distance = std::numeric_limits<double>::infinity();
      for (int ring = 0; ring < 6 && best < 0 && !frontier.empty(); ++ring) {
        std::vector<int> next;
        for (const int e : frontier) {
          for (const int other : result_.elements[to_index(e)].covers) {
            if (seen_cover[to_index(other)])
              continue;
            seen_cover[to_index(other)] = 1;
            for (const int candidate : result_.covers[to_index(other)].elements) {
              next.push_back(candidate);
              if (!well_posed(candidate))
                continue;
              const auto& tri =
                  math_.triangles[to_index(result_.elements[to_index(candidate)].triangle)];
              const Point2 centroid =
                  (math_.nodes[to_index(tri[0])] + math_.nodes[to_index(tri[1])] +
                   math_.nodes[to_index(tri[2])]) /
                  3.0;
              const double distance = (centroid - node).norm();
              if (distance < best_distance) {
                best_distance = distance;
                best = candidate;
              }
            }
          }
        }
        frontier = std::move(next);
      }
      if (best >= 0) {
        cover.extension_element = best;
        ++result_.stats.tiny_covers;
      } else {
        tiny_blocks[cover.block] = cover.area;
      }
    }
    for (const auto& [block, cover_area] : tiny_blocks)
      result_.tiny_blocks.push_back({block, cover_area});
  }

  // ---- 4. blocks, loops, curve pieces ---------------------------------------------------

  void build_block_records() {
    for (int e = 0; e < result_.n_elements(); ++e) {
      Block& block = result_.blocks[to_index(result_.elements[to_index(e)].block)];
      block.elements.push_back(e);
      block.area += result_.elements[to_index(e)].area;
    }
  }

  /// Pieces of global halfedge @p id ordered from its source, each with its element.
  struct SidePiece {
    Point2 a;
    Point2 b;
    int element = -1;
    int block = -1;
  };

  std::vector<SidePiece> side_pieces(int id) {
    const int face = face_of_halfedge(id);
    const int material = face_material_[to_index(face)];
    std::vector<SidePiece> result;
    if (material < 0)
      return result;
    const GlobalEdge& edge = edges_[to_index(id / 2)];
    const ExactPoint& source = id % 2 == 0 ? edge.source : edge.target;
    if (is_block_material(material)) {
      const ExactPoint& target = id % 2 == 0 ? edge.target : edge.source;
      result.push_back({to_point2(source), to_point2(target), -1, face_block_[to_index(face)]});
      return result;
    }
    auto& pieces = halfedge_pieces_[id];
    std::sort(pieces.begin(), pieces.end(), [&](const HalfedgePiece& p, const HalfedgePiece& q) {
      return CGAL::compare_distance_to_point(source, p.exact_source, q.exact_source) ==
             CGAL::SMALLER;
    });
    result.reserve(pieces.size());
    for (const HalfedgePiece& p : pieces) {
      result.push_back({p.a, p.b, atom_element_[to_index(p.atom)],
                        face_block_[to_index(atoms_[to_index(p.atom)].face)]});
    }
    return result;
  }

  void build_loops() {
    // (halfedge id, from, to) -> (loop, edge): the twin of a joint face is the edge of the
    // opposite halfedge between the same two points, walked the other way.
    using Key = std::tuple<int, double, double, double, double>;
    std::map<Key, std::pair<int, int>> where;
    for (const std::vector<int>& global : global_loops_) {
      BoundaryLoop loop;
      loop.block = face_block_[to_index(face_of_halfedge(global.front()))];
      const int index = result_.n_loops();
      // End of the last piece kept: the next piece must start there.
      std::optional<Point2> previous_end;
      for (const int id : global) {
        const std::vector<SidePiece> pieces = side_pieces(id);
        const GlobalEdge& edge = edges_[to_index(id / 2)];
        if (pieces.empty())
          throw_uncovered_boundary(to_point2(id % 2 == 0 ? edge.source : edge.target));
        for (const SidePiece& piece : pieces) {
          // Pieces between exact points closer than rounding vanish: no zero-length edges.
          if (piece.a == piece.b)
            continue;
          if (previous_end && piece.a != *previous_end)
            throw_uncovered_boundary(*previous_end);
          previous_end = piece.b;
          where[{id, piece.a.x(), piece.a.y(), piece.b.x(), piece.b.y()}] = {index,
                                                                             loop.n_vertices()};
          loop.vertices.push_back(piece.a);
          BoundaryEdge boundary;
          boundary.element = piece.element;
          boundary.joint = edge.joint;
          loop.edges.push_back(boundary);
        }
      }
      if (loop.vertices.size() < 2)
        continue; // a loop thinner than rounding (a crack of zero rounded length)
      if (previous_end != loop.vertices.front())
        throw_uncovered_boundary(*previous_end);
      result_.blocks[to_index(loop.block)].loops.push_back(index);
      result_.loops.push_back(std::move(loop));
    }
    for (const auto& [key, position] : where) {
      const auto& [id, ax, ay, bx, by] = key;
      const auto other = where.find({id ^ 1, bx, by, ax, ay});
      if (other == where.end() || position.first >= result_.n_loops())
        continue;
      BoundaryEdge& edge = result_.loops[to_index(position.first)].edges[to_index(position.second)];
      edge.twin_loop = other->second.first;
      edge.twin_edge = other->second.second;
    }
    // A dda/vem block has no elements: its area is that of its loops (outer counter-
    // clockwise positive, holes clockwise negative, slits zero).
    for (Block& block : result_.blocks) {
      if (!block.elements.empty())
        continue;
      for (const int l : block.loops)
        block.area += signed_area(result_.loops[to_index(l)].vertices);
    }
  }

  /// The pieces of a boundary edge leave a gap: no math triangle covers the material there.
  [[noreturn]] void throw_uncovered_boundary(const Point2& near) const {
    throw InputError(physical_.source +
                     ": the mathematical mesh leaves the material's boundary "
                     "uncovered after " +
                     point_text(near) +
                     ": every part of the material must lie in a math triangle; with a "
                     "triangulation of your own, put its boundary nodes on the material's "
                     "boundary or outside it, or use [cover_mesh] kind = \"regular\"");
  }

  void build_curve_pieces() {
    result_.curve_pieces.assign(physical_.curves.size(), {});
    for (std::size_t g = 0; g < edges_.size(); ++g) {
      if (edges_[g].curves.empty())
        continue;
      const std::vector<SidePiece> left = side_pieces(2 * static_cast<int>(g));
      std::vector<SidePiece> right = side_pieces(2 * static_cast<int>(g) + 1);
      std::reverse(right.begin(), right.end());
      for (SidePiece& p : right)
        std::swap(p.a, p.b);
      std::vector<CurvePiece> pieces;
      if (!left.empty() && left.size() == right.size()) {
        for (std::size_t i = 0; i < left.size(); ++i) {
          pieces.push_back({left[i].a, left[i].b, left[i].element, right[i].element, left[i].block,
                            right[i].block});
        }
      } else {
        const bool use_left = left.size() >= right.size();
        const std::vector<SidePiece>& main = use_left ? left : right;
        const int other_block = use_left ? (right.empty() ? -1 : right.front().block)
                                         : (left.empty() ? -1 : left.front().block);
        for (const SidePiece& p : main) {
          CurvePiece piece{p.a, p.b, -1, -1, -1, -1};
          if (use_left) {
            piece.left_element = p.element;
            piece.left_block = p.block;
            piece.right_block = other_block;
          } else {
            piece.right_element = p.element;
            piece.right_block = p.block;
            piece.left_block = other_block;
          }
          pieces.push_back(piece);
        }
      }
      for (const int c : edges_[g].curves) {
        auto& target = result_.curve_pieces[to_index(c)];
        target.insert(target.end(), pieces.begin(), pieces.end());
      }
    }
  }

  void check_area() {
    CompensatedSum expected_sum;
    for (int r = 0; r < physical_.n_regions(); ++r) {
      if (is_block_region_[to_index(r)])
        continue;
      for (const Polygon& polygon : physical_.regions[to_index(r)].polygons)
        expected_sum += area(polygon);
    }
    CompensatedSum covered_sum;
    for (const Element& e : result_.elements)
      covered_sum += e.area;
    const double expected = expected_sum.value();
    const double covered = covered_sum.value();
    // Rounding the exact vertices to double changes areas by about 1e-16 of each triangle.
    if (std::abs(covered - expected) > 1.0e-9 * std::max(expected, 1e-300)) {
      std::ostringstream message;
      message.precision(12);
      message << physical_.source << ": the mathematical mesh covers " << covered << " m² of "
              << expected
              << " m² of material; every material region must lie inside the math mesh "
                 "(with [cover_mesh] kind = \"gmsh\" the mesh comes from the same geometry, "
                 "so check that every Physical Surface is meshed)";
      throw InputError(message.str());
    }
  }

  void report_unused_joints() {
    std::vector<char> used(physical_.curves.size(), 0);
    for (const GlobalEdge& e : edges_) {
      if (e.cut && e.joint >= 0)
        used[to_index(e.joint)] = 1;
    }
    for (std::size_t c = 0; c < physical_.curves.size(); ++c) {
      if (is_joint_curve_[c] && !used[c]) {
        result_.warnings.push_back("joint \"" + physical_.curves[c].name +
                                   "\" does not cut any material (it lies outside the "
                                   "material regions or only along their boundary)");
      }
    }
  }

  const MathMesh& math_;
  const PhysicalMesh& physical_;
  const CoverMesherOptions& options_;
  std::vector<char> is_joint_curve_;
  std::vector<char> is_block_region_;

  std::vector<SourceSegment> segments_;
  PhysicalArrangement arrangement_;
  std::vector<int> face_material_;
  std::vector<int> face_block_;
  std::vector<GlobalEdge> edges_;
  std::vector<std::vector<int>> global_loops_;

  std::vector<std::vector<int>> triangle_edges_;
  LocalArrangement local_;
  std::vector<Atom> atoms_;
  std::vector<int> triangle_first_atom_;
  std::vector<int> triangle_cut_index_;
  std::vector<std::array<std::vector<EdgePiece>, 3>> cut_pieces_;
  std::map<int, std::vector<HalfedgePiece>> halfedge_pieces_;
  std::vector<std::pair<int, int>> bonds_;
  std::vector<int> pending_location_;
  std::vector<int> atom_cover_;
  std::vector<int> atom_element_;

  CoverSystem result_;
};

} // namespace

int fit_math_mesh_to_boundary(MathMesh& math, const PhysicalMesh& physical) {
  // Edges of region loops with material on their left; an edge walked the other way by a
  // loop too (an interface between two regions) has material on both sides and is skipped.
  std::set<std::array<double, 4>> directed;
  for (const MaterialRegion& region : physical.regions) {
    for (const Polygon& polygon : region.polygons) {
      auto add_loop = [&](const Loop& loop) {
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const Point2& a = loop[k];
          const Point2& b = loop[(k + 1) % loop.size()];
          directed.insert({a.x(), a.y(), b.x(), b.y()});
        }
      };
      add_loop(polygon.outer);
      for (const Loop& hole : polygon.holes)
        add_loop(hole);
    }
  }
  const TriangleGrid grid(math);
  std::vector<int> stamp(to_index(math.n_nodes()), -1);
  int edge_index = 0;
  int moved = 0;
  for (const auto& [ax, ay, bx, by] : directed) {
    ++edge_index;
    if (directed.count({bx, by, ax, ay}) != 0)
      continue;
    const Point2 a(ax, ay);
    const Point2 b(bx, by);
    const Point2 along = b - a;
    const double length = along.norm();
    if (!(length > 0.0))
      continue;
    // "Within rounding": a mesh generator's boundary nodes are off the segment by a few
    // units in the last place of the coordinates; 1e-12 of the edge's size and position
    // is far above that and far below any distance a mesh means.
    const double reach =
        1.0e-12 * std::max({length, a.lpNorm<Eigen::Infinity>(), b.lpNorm<Eigen::Infinity>()});
    const Point2 outward = Point2(along.y(), -along.x()) / length; // right of a -> b
    const ExactPoint ea(ax, ay);
    const ExactPoint eb(bx, by);
    grid.for_triangles_near(a, b, [&](int t) {
      for (const int node : math.triangles[to_index(t)]) {
        if (stamp[to_index(node)] == edge_index)
          continue;
        stamp[to_index(node)] = edge_index;
        Point2& p = math.nodes[to_index(node)];
        const double s = (p - a).dot(along) / (length * length);
        if (!(s > 0.0 && s < 1.0) || std::abs((p - a).dot(outward)) > reach)
          continue;
        if (CGAL::orientation(ea, eb, ExactPoint(p.x(), p.y())) != CGAL::LEFT_TURN)
          continue; // on the edge or outside the material already
        // Step outward by a growing multiple of the coordinates' last place until the node
        // is on the edge or outside: a few steps, a few units in the last place.
        double step =
            std::numeric_limits<double>::epsilon() * std::max(p.lpNorm<Eigen::Infinity>(), length);
        Point2 q = p;
        for (int k = 0;
             k < 64 && CGAL::orientation(ea, eb, ExactPoint(q.x(), q.y())) == CGAL::LEFT_TURN;
             ++k) {
          q = p + step * outward;
          step *= 2.0;
        }
        p = q;
        ++moved;
      }
    });
  }
  return moved;
}

CoverSystem build_cover_system(const MathMesh& math,
                               const PhysicalMesh& physical,
                               std::span<const int> joints,
                               const CoverMesherOptions& options) {
  for (const auto& t : math.triangles) {
    for (const int node : t) {
      NMM_ASSERT(node >= 0 && node < math.n_nodes(), "math triangle node out of range");
    }
    const Point2 e1 = math.nodes[to_index(t[1])] - math.nodes[to_index(t[0])];
    const Point2 e2 = math.nodes[to_index(t[2])] - math.nodes[to_index(t[0])];
    if (!(e1.x() * e2.y() - e1.y() * e2.x() > 0.0)) {
      throw InputError("the mathematical mesh has a triangle that is not counter-clockwise "
                       "or has zero area, at (" +
                       std::to_string(math.nodes[to_index(t[0])].x()) + ", " +
                       std::to_string(math.nodes[to_index(t[0])].y()) + ")");
    }
  }
  CoverMesher mesher(math, physical, joints, options);
  return mesher.run();
}

} // namespace nmm
