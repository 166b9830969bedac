// SPDX-License-Identifier: MIT
#include "contact/detection.hpp"

#include "contact/key_set.hpp"
#include "mesh/error.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <tuple>
#include <utility>

namespace nmm {

namespace {

constexpr double two_pi = 2.0 * std::numbers::pi;

std::size_t at(int i) { return static_cast<std::size_t>(i); }

double cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// The unit normal to the right of the unit direction @p d: an edge's outward normal (the
/// material is on its left).
Point2 right_normal(const Point2& d) { return {d.y(), -d.x()}; }

/// Angle of @p d measured counter-clockwise from @p from, in [0, 2 pi).
double angle_from(const Point2& from, const Point2& d) {
  double a = std::atan2(cross(from, d), from.dot(d));
  if (a < 0.0)
    a += two_pi;
  return a;
}

/// A vertex's material wedge: directions from `start` counter-clockwise through `extent`.
struct Wedge {
  Point2 start;  ///< unit direction to the next vertex
  Point2 finish; ///< unit direction to the previous vertex
  double extent = 0.0;
  [[nodiscard]] bool contains(const Point2& d) const { return angle_from(start, d) <= extent; }
};

/// @param angle  b.angle(v)
Wedge wedge(const ContactBoundary& b, int v, double angle) {
  Wedge w;
  w.start = (b.position[at(b.next[at(v)])] - b.position[at(v)]).normalized();
  w.finish = (b.position[at(b.previous[at(v)])] - b.position[at(v)]).normalized();
  w.extent = angle;
  return w;
}

/// One key for an unordered pair of boundary indices.
std::uint64_t pair_key(int a, int b) {
  const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(a, b)));
  const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(a, b)));
  return lo << 32U | hi;
}

/// Length of the intersection of two arcs of the unit circle, each given by its start angle
/// and extent (both extents at most 2 pi).
double arc_overlap(double s1, double e1, double s2, double e2) {
  double total = 0.0;
  for (int k = -1; k <= 1; ++k) {
    const double lo = std::max(s1, s2 + k * two_pi);
    const double hi = std::min(s1 + e1, s2 + k * two_pi + e2);
    total += std::max(0.0, hi - lo);
  }
  return total;
}

double direction_angle(const Point2& d) {
  double a = std::atan2(d.y(), d.x());
  if (a < 0.0)
    a += two_pi;
  return a;
}

/// Shi's criterion [3]: translated onto the edge, the angle's wedge may dip into the edge's
/// material half-plane (the side opposite its outward normal) by less than `limit`.
/// @param sin_limit  std::sin(limit)
bool fits_against(const Wedge& w, const Point2& normal, double sin_limit) {
  if (w.contains(-normal))
    return false;
  const double lowest = std::min(w.start.dot(normal), w.finish.dot(normal));
  return lowest >= -sin_limit;
}

class Detector {
public:
  Detector(const ContactBoundary& boundary,
           const DetectionOptions& options,
           const std::vector<std::uint64_t>& keep)
      : b_(boundary), options_(options), keep_(keep.size()), rounding_(rounding_length(boundary)),
        cos_overlap_(std::cos(options.angle_overlap)),
        sin_overlap_(std::sin(options.angle_overlap)) {
    for (const std::uint64_t key : keep)
      keep_.insert(key);
    // Every vertex's angle (an atan2) and every edge's direction (a square root) once: the
    // tests ask for them many times.
    const int n = b_.n_vertices();
    for (KeySet* set : {&seen_, &edge_pairs_, &vertex_pairs_}) // about one key per vertex
      set->reserve(at(n));
    angle_.resize(at(n));
    flat_.resize(at(n));
    direction_.resize(at(n));
    for (int v = 0; v < n; ++v) {
      angle_[at(v)] = b_.angle(v);
      flat_[at(v)] = std::abs(angle_[at(v)] - std::numbers::pi) < options_.angle_overlap ? 1 : 0;
      direction_[at(v)] = b_.direction(v);
    }
  }

  std::vector<ContactCandidate> run(DetectionStats* stats) {
    const std::vector<std::pair<int, int>> pairs = broad_phase();
    // Edge-to-edge first: they cover the angle contacts of their own vertices.
    for (const auto& [e, f] : pairs)
      test_edge_edge(e, f);
    for (const auto& [e, f] : pairs) {
      for (const int v : {e, b_.next[at(e)]})
        test_vertex_edge(v, f);
      for (const int v : {f, b_.next[at(f)]})
        test_vertex_edge(v, e);
      for (const int v : {e, b_.next[at(e)]}) {
        for (const int w : {f, b_.next[at(f)]})
          test_vertex_vertex(v, w);
      }
    }
    if (stats != nullptr) {
      stats->edge_pairs += static_cast<long>(pairs.size());
      stats->vertex_edge += vertex_edge_;
      stats->vertex_vertex += vertex_vertex_;
      stats->edge_edge += edge_edge_;
    }
    return std::move(result_);
  }

private:
  /// Pairs of non-adjacent edges whose boxes, grown by the contact distance, overlap: a
  /// uniform grid of cells about the size of a mean box, each box listed in the cells it
  /// overlaps, each pair reported only by the cell that holds the lower-left corner of the
  /// two boxes' overlap (so once). O(n + pairs) whatever the model's shape; a sort and sweep
  /// along x cost O(n m) with m the edges stacked above each other (docs/benchmarks.md).
  std::vector<std::pair<int, int>> broad_phase() const {
    const int n = b_.n_vertices();
    if (n == 0)
      return {};
    std::vector<BoundingBox> boxes(at(n));
    BoundingBox all;
    double mean_size = 0.0;
    for (int e = 0; e < n; ++e) {
      BoundingBox& box = boxes[at(e)];
      box.extend(b_.position[at(e)]);
      box.extend(b_.position[at(b_.next[at(e)])]);
      box.min.array() -= options_.distance;
      box.max.array() += options_.distance;
      all.extend(box.min);
      all.extend(box.max);
      mean_size += std::max(box.size().x(), box.size().y()) / n;
    }
    // Cells of the mean box size, but no more than about 4 per edge (a few huge edges).
    const Point2 extent = all.size();
    double cell = std::max(mean_size, 1e-300);
    const double wanted = (extent.x() / cell + 1.0) * (extent.y() / cell + 1.0);
    if (wanted > 4.0 * n)
      cell *= std::sqrt(wanted / (4.0 * n));
    const int nx = static_cast<int>(extent.x() / cell) + 1;
    const int ny = static_cast<int>(extent.y() / cell) + 1;
    auto index = [&](double v, double lo, int count) {
      return std::clamp(static_cast<int>((v - lo) / cell), 0, count - 1);
    };
    auto cells_of = [&](const BoundingBox& box, auto&& visit) {
      const int x1 = index(box.max.x(), all.min.x(), nx);
      const int y1 = index(box.max.y(), all.min.y(), ny);
      for (int y = index(box.min.y(), all.min.y(), ny); y <= y1; ++y) {
        for (int x = index(box.min.x(), all.min.x(), nx); x <= x1; ++x)
          visit(static_cast<std::size_t>(y) * static_cast<std::size_t>(nx) +
                static_cast<std::size_t>(x));
      }
    };
    // Counting sort of (cell, edge): start[c] .. start[c + 1] are cell c's edges.
    std::vector<int> start(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny) + 1, 0);
    for (int e = 0; e < n; ++e)
      cells_of(boxes[at(e)], [&](std::size_t c) { ++start[c + 1]; });
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<int> members(at(start.back()));
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int e = 0; e < n; ++e)
      cells_of(boxes[at(e)], [&](std::size_t c) { members[at(fill[c]++)] = e; });
    std::vector<std::pair<int, int>> pairs;
    for (std::size_t c = 0; c + 1 < start.size(); ++c) {
      for (int i = start[c]; i < start[c + 1]; ++i) {
        const int e = members[at(i)];
        const BoundingBox& box = boxes[at(e)];
        for (int j = i + 1; j < start[c + 1]; ++j) {
          const int f = members[at(j)];
          const BoundingBox& other = boxes[at(f)];
          if (other.max.x() < box.min.x() || other.min.x() > box.max.x() ||
              other.max.y() < box.min.y() || other.min.y() > box.max.y() || b_.adjacent(e, f))
            continue;
          const std::size_t owner =
              static_cast<std::size_t>(
                  index(std::max(box.min.y(), other.min.y()), all.min.y(), ny)) *
                  static_cast<std::size_t>(nx) +
              static_cast<std::size_t>(
                  index(std::max(box.min.x(), other.min.x()), all.min.x(), nx));
          if (owner == c)
            pairs.emplace_back(std::min(e, f), std::max(e, f));
        }
      }
    }
    return pairs;
  }

  bool kept(const ContactCandidate& c) const { return keep_.contains(c.key()); }

  /// A vertex on a straight boundary (a point where the boundary crosses a math edge, or a
  /// vertex of a gently curved outline): part of its edges, not an angle. Its contacts are
  /// its edges' edge-to-edge contacts, or the corners of what touches it.
  bool flat(int v) const { return flat_[at(v)] != 0; }

  Wedge wedge(int v) const { return nmm::wedge(b_, v, angle_[at(v)]); }

  /// ContactBoundary::outward_normal(e) from the stored direction.
  Point2 outward_normal(int e) const { return right_normal(direction_[at(e)]); }

  void add(const ContactCandidate& c) {
    if (seen_.insert(c.key()))
      result_.push_back(c);
  }

  /// Two facing parallel edges (antiparallel within the angle criterion) whose projections
  /// overlap and whose gap can close in the step.
  void test_edge_edge(int e, int f) {
    const Point2& de = direction_[at(e)];
    const Point2& df = direction_[at(f)];
    if (de.dot(df) > -cos_overlap_)
      return;
    // Slave e against master f: the overlap of e's projection on f.
    const Point2& c = b_.position[at(f)];
    const double length = (b_.position[at(b_.next[at(f)])] - c).norm();
    const Point2& a = b_.position[at(e)];
    const Point2& d = b_.position[at(b_.next[at(e)])];
    const double ta = (a - c).dot(df);
    const double td = (d - c).dot(df);
    const double lo = std::max(0.0, std::min(ta, td));
    const double hi = std::min(length, std::max(ta, td));
    if (hi - lo <= touching_end * length) // a touching end: the neighbouring pairs hold it
      return;
    const Point2 n = outward_normal(f);
    const double ga = n.dot(a - c);
    const double gd = n.dot(d - c);
    // Gap at the ends of the overlap (linear in between).
    const double gap_lo = ga + (gd - ga) * ((lo - ta) / (td - ta));
    const double gap_hi = ga + (gd - ga) * ((hi - ta) / (td - ta));
    const double low = std::min(gap_lo, gap_hi);
    // The master is the edge of the larger block: it moves and turns less, and the gap is
    // linearised in the master's motion (exact for a master that stays put).
    ContactCandidate candidate;
    candidate.kind = ContactKind::edge_edge;
    candidate.slave = std::min(e, f);
    candidate.master = std::max(e, f);
    if (!b_.block_area.empty()) {
      const double area_e = b_.block_area[at(b_.block[at(e)])];
      const double area_f = b_.block_area[at(b_.block[at(f)])];
      if (std::abs(area_e - area_f) > 1e-9 * std::max(area_e, area_f)) {
        candidate.slave = area_e < area_f ? e : f;
        candidate.master = area_e < area_f ? f : e;
      }
    }
    if (std::max(gap_lo, gap_hi) > options_.distance && low > options_.distance)
      return;
    if (low < -options_.penetration && !kept(candidate))
      return;
    if (!behind_inside(e, f, lo, hi) || !behind_inside(f, e, lo_on(f, e), hi_on(f, e)))
      return;
    if (edge_pairs_.insert(pair_key(e, f))) {
      ++edge_edge_;
      add(candidate);
    }
  }

  /// The overlap of edge e's projection on edge f, as parameters along f from its start (m):
  /// [lo_on(e, f), hi_on(e, f)].
  double lo_on(int e, int f) const {
    const Point2& c = b_.position[at(f)];
    const Point2& df = direction_[at(f)];
    return std::max(0.0, std::min((b_.position[at(e)] - c).dot(df),
                                  (b_.position[at(b_.next[at(e)])] - c).dot(df)));
  }
  double hi_on(int e, int f) const {
    const Point2& c = b_.position[at(f)];
    const Point2& df = direction_[at(f)];
    return std::min(edge_length(f), std::max((b_.position[at(e)] - c).dot(df),
                                             (b_.position[at(b_.next[at(e)])] - c).dot(df)));
  }

  /// The faces next to an edge at its convex ends, by a point of each and its outward
  /// normal (no allocation: the detection asks for them for every pair it tests).
  struct EndFaces {
    std::array<std::pair<Point2, Point2>, 2> face;
    int n = 0;
    [[nodiscard]] const std::pair<Point2, Point2>* begin() const { return face.data(); }
    [[nodiscard]] const std::pair<Point2, Point2>* end() const { return face.data() + n; }
    [[nodiscard]] bool empty() const { return n == 0; }
  };

  /// The faces next to edge f at its convex ends: behind f is inside f's body only up to
  /// them.
  EndFaces convex_end_faces(int f) const {
    EndFaces faces;
    for (const int end : {f, b_.next[at(f)]}) {
      if (angle_[at(end)] < std::numbers::pi - options_.angle_overlap)
        faces.face[at(faces.n++)] = {
            b_.position[at(end)], outward_normal(end == f ? b_.previous[at(f)] : b_.next[at(f)])};
    }
    return faces;
  }

  /// Whether point x, behind edge f by @p gap (< 0), entered f's body through f: behind each
  /// face next to f at a convex end by no less than behind f (Shi's entrance line is the one
  /// passed by the least, as in ContactSystem::choose_entrance_line()). A point behind f but
  /// in front of such a face, or behind it by less, came in through that face or is outside
  /// the body. So it is where two joints cross: the crack faces of the crossing joint on
  /// either side of a sliding one lie on one line, and once one side slid, its corner at the
  /// crossing lies behind the other side's crack face, laterally by the slide, and so does
  /// part of its crack face; taken as contacts, they held a sliding wedge by a penetration it
  /// never had (issue 42, item 2). The corners that slid past each other enter by the sliding
  /// joint's faces instead.
  bool entered(const EndFaces& faces, const Point2& x, double gap) const {
    return std::ranges::all_of(faces, [&](const std::pair<Point2, Point2>& face) {
      return face.second.dot(x - face.first) <= gap + rounding_;
    });
  }

  /// Whether more than a touching end of slave edge e's part over master f, [lo, hi] along
  /// f, lies in front of f or entered f's body through f (entered()).
  bool behind_inside(int e, int f, double lo, double hi) const {
    const EndFaces faces = convex_end_faces(f);
    if (faces.empty())
      return true;
    const Point2& c = b_.position[at(f)];
    const Point2& df = direction_[at(f)];
    const Point2 a = b_.position[at(e)];
    const Point2 d = b_.position[at(b_.next[at(e)])];
    const double ta = (a - c).dot(df);
    const double td = (d - c).dot(df);
    if (std::abs(td - ta) <= rounding_)
      return true;
    auto point = [&](double t) { return a + (d - a) * ((t - ta) / (td - ta)); };
    const Point2 n = outward_normal(f);
    // The gap and the distances beyond the faces are linear along the part: split [lo, hi]
    // where one changes sign and judge each piece at its middle.
    std::vector<double> cuts{lo, hi};
    auto add_root = [&](double f0, double f1) {
      if ((f0 < 0.0) != (f1 < 0.0))
        cuts.push_back(lo + (hi - lo) * f0 / (f0 - f1));
    };
    add_root(n.dot(point(lo) - c) + rounding_, n.dot(point(hi) - c) + rounding_);
    for (const auto& [x, m] : faces)
      add_root(m.dot(point(lo) - x) - n.dot(point(lo) - c) - rounding_,
               m.dot(point(hi) - x) - n.dot(point(hi) - c) - rounding_);
    std::sort(cuts.begin(), cuts.end());
    double inside = 0.0;
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
      const Point2 x = point(0.5 * (cuts[k] + cuts[k + 1]));
      const double gap = n.dot(x - c);
      if (gap >= -rounding_ || entered(faces, x, gap))
        inside += cuts[k + 1] - cuts[k];
    }
    return inside > touching_end * edge_length(f);
  }

  /// Whether vertex v's contact against edge m is part of an edge-to-edge contact.
  bool covered(int v, int m) const {
    for (const int s : {v, b_.previous[at(v)]}) {
      if (edge_pairs_.contains(pair_key(s, m)))
        return true;
    }
    return false;
  }

  /// When vertex v, at parameter @p t of edge m, lies at a straight end of m (or inside m by
  /// no more than the touching end, which test_edge_edge() measures on either edge of a pair:
  /// here on the longer of m and v's edge) and one of v's edges is in edge-to-edge contact
  /// with the edge beyond that end: that edge of v and the edge beyond, else {-1, -1}. It is
  /// a block's corner where its face on a joint ends, against the free surface that
  /// continues the joint. The pair represents the face; the corner's spring stays (a block
  /// pivoting on that corner needs it, the pair's springs on a short pressed part being
  /// soft: examples/10, whose pivot lies exactly so at a split of the foundation's top) and
  /// represents no length of its own: half of the corner's edges added to the length in
  /// contact made a 1.2 m joint 2.8 m long (ContactCandidate::end_face; docs/formulation.md,
  /// "Joint strength").
  std::pair<int, int> ends_edge_pair(int v, int m, double t) const {
    const double length = edge_length(m);
    for (const bool at_start : {true, false}) {
      const int end = at_start ? m : b_.next[at(m)];
      const int beyond = at_start ? b_.previous[at(m)] : b_.next[at(m)];
      const double inside = (at_start ? t : 1.0 - t) * length; // how far v lies from the end
      if (!flat(end))
        continue;
      for (const int s : {v, b_.previous[at(v)]}) {
        if (inside <= touching_end * std::max(length, edge_length(s)) &&
            edge_pairs_.contains(pair_key(s, beyond)))
          return {s, beyond};
      }
    }
    return {-1, -1};
  }

  double edge_length(int e) const {
    return (b_.position[at(b_.next[at(e)])] - b_.position[at(e)]).norm();
  }

  bool covered_pair(int v, int w) const {
    for (const int s : {v, b_.previous[at(v)]}) {
      for (const int f : {w, b_.previous[at(w)]}) {
        if (edge_pairs_.contains(pair_key(s, f)))
          return true;
      }
    }
    return false;
  }

  /// Angle-to-edge (Shi 3.1 [1] and [3]): the vertex projects inside the edge, is close to
  /// it on its void side, and its wedge fits against the edge.
  void test_vertex_edge(int v, int m) {
    if (v == m || v == b_.next[at(m)] || flat(v))
      return;
    const Point2& p = b_.position[at(v)];
    const Point2& c = b_.position[at(m)];
    const Point2 edge = b_.position[at(b_.next[at(m)])] - c;
    const double t = (p - c).dot(edge) / edge.squaredNorm();
    // The ends are angle-to-angle contacts, and so is a vertex at a corner end to rounding:
    // where joints cross, the corners of the four sides meet at one point, and an
    // angle-to-edge contact of a corner against each edge leaving that point (their ends off
    // by a unit in the last place) doubled the one spring of the angle-to-angle contact: four
    // springs held two corners, and the friction on each changed the normal force of the
    // others from one solve to the next (examples/02_jointed_slope: normal forces alternating
    // between 4 and 17 kN for 50 solves). An end that is a straight point (a side split where
    // a math edge crosses it) is no corner: a vertex there presses on the side, and keeps its
    // angle-to-edge contact against the piece it projects into (examples/10: the block's
    // pivot, point 7, on a split of the foundation's top one unit in the last place away; the
    // paper's Table 1 contact).
    const double length = std::sqrt(edge.squaredNorm());
    if (t <= 0.0 || t >= 1.0 || (t * length <= rounding_ && !flat(m)) ||
        ((1.0 - t) * length <= rounding_ && !flat(b_.next[at(m)])))
      return;
    const Point2 n = outward_normal(m);
    const double gap = n.dot(p - c);
    if (std::abs(gap) > options_.distance || covered(v, m)) // (the look-up after the arithmetic)
      return;
    add_vertex_edge(v, m, t, gap, n);
  }

  /// The angle-to-edge contact of vertex v against edge m (at parameter t along it, @p gap
  /// from it along its outward normal n), if a new contact may start that deep (or it was
  /// closed in the last step), the angle fits against the edge, and the vertex behind the
  /// edge entered through it (entered()).
  void add_vertex_edge(int v, int m, double t, double gap, const Point2& n) {
    ContactCandidate candidate;
    candidate.slave = v;
    candidate.master = m;
    std::tie(candidate.end_face, candidate.end_beyond) = ends_edge_pair(v, m, t);
    if (gap < -options_.penetration && !kept(candidate))
      return;
    if (!fits_against(wedge(v), n, sin_overlap_))
      return;
    if (gap < -rounding_ && !entered(convex_end_faces(m), b_.position[at(v)], gap))
      return;
    ++vertex_edge_;
    add(candidate);
  }

  /// Whether two vertices of one block can meet: each lies outside the other's material
  /// wedge (its rays included). Two corners of one block joined by a straight side, or
  /// across its inside, are no contact however close they are (with a large contact
  /// distance a foundation's two corners 0.5 m apart got a spring through the whole block,
  /// examples/10). Vertices at one point (the two faces of a joint's mouth) can meet.
  bool faces_void(int v, int w) const {
    const Point2 d = b_.position[at(w)] - b_.position[at(v)];
    if (d.norm() <= 1e-12 * (b_.position[at(v)].norm() + 1.0))
      return true;
    constexpr double tolerance = 1e-9; // rad: a ray of the wedge counts as inside
    auto inside = [&](int vertex, const Point2& direction) {
      const double a = angle_from(wedge(vertex).start, direction);
      return a <= angle_[at(vertex)] + tolerance || a >= two_pi - tolerance;
    };
    return !inside(v, d) && !inside(w, Point2(-d));
  }

  /// Whether vertex w lies along a side of angle v, beyond that side's far end: its
  /// projection on the side's direction is at least the side's length, and it lies within
  /// the angle criterion of the side's line. The two angles are then no angle-to-angle
  /// contact: w meets the side's far corner, or the side itself, before it could reach v.
  /// Criteria [2] and [4] alone pair them: within the contact distance, and translated onto
  /// each other their wedges do not overlap, when both lie on one straight joint (the ends
  /// of its two faces, or the corners where it meets another joint and a free surface). With
  /// a contact distance of 1.6 m such pairs were 0.1 to 1.3 m apart, and each put a spring
  /// on an entrance line the vertex was not near: touching (zero gap on the joint's line),
  /// so locked from the start, or a line rotating with a 0.07 m edge at 11 times its length
  /// (examples/02_jointed_slope: gaps of -0.67 m within a step, a reported penetration of
  /// 0.91 m, and open-close iterations that never converged).
  bool lies_along_side(int v, int w) const {
    const Point2 d = b_.position[at(w)] - b_.position[at(v)];
    for (const int end : {b_.next[at(v)], b_.previous[at(v)]}) {
      const Point2 side = b_.position[at(end)] - b_.position[at(v)];
      const double length = side.norm();
      if (d.dot(side) >= length * length &&
          std::abs(std::atan2(cross(side, d), side.dot(d))) <= options_.angle_overlap)
        return true;
    }
    return false;
  }

  /// Angle-to-angle (Shi 3.1 [2] and [4], entrance lines 3.2): reduced to angle-to-edge
  /// contacts against the entrance lines.
  void test_vertex_vertex(int v, int w) {
    if (v == w || b_.next[at(v)] == w || b_.next[at(w)] == v)
      return;
    const Point2& p = b_.position[at(v)];
    const Point2& q = b_.position[at(w)];
    // A pair is tested once (up to four edge pairs hold it); what follows depends on the
    // two vertices alone.
    if ((p - q).norm() > options_.distance || !vertex_pairs_.insert(pair_key(v, w)))
      return;
    if (covered_pair(v, w))
      return;
    if (b_.block[at(v)] == b_.block[at(w)] && !faces_void(v, w))
      return;
    if (flat(v) && flat(w))
      return; // straight against straight: edge-to-edge contacts, if facing
    if (flat(v) || flat(w)) {
      // A corner against a straight point: the corner against the straight side's edge it
      // projects onto (the more central one if it sits right at the point).
      const int corner = flat(v) ? w : v;
      const int straight = flat(v) ? v : w;
      int best = -1;
      double best_centrality = -1.0;
      for (const int e : {straight, b_.previous[at(straight)]}) {
        const Point2& c0 = b_.position[at(e)];
        const Point2 edge = b_.position[at(b_.next[at(e)])] - c0;
        const double t = (b_.position[at(corner)] - c0).dot(edge) / edge.squaredNorm();
        // Not at the edge's far end (to rounding) when that end is a corner: a corner there
        // meets the corner at that end (the angle-to-angle contact of the two), as in
        // test_vertex_edge().
        const bool forward = e == straight;
        const double far = forward ? 1.0 - t : t;
        const int far_end = forward ? b_.next[at(e)] : e;
        if (t < 0.0 || t > 1.0 ||
            (far * std::sqrt(edge.squaredNorm()) <= rounding_ && !flat(far_end)))
          continue;
        if (std::min(t, 1.0 - t) > best_centrality) {
          best_centrality = std::min(t, 1.0 - t);
          best = e;
        }
      }
      if (best < 0 || covered(corner, best))
        return;
      const Point2& c0 = b_.position[at(best)];
      const Point2 edge = b_.position[at(b_.next[at(best)])] - c0;
      const double t = (b_.position[at(corner)] - c0).dot(edge) / edge.squaredNorm();
      const Point2 n = outward_normal(best);
      const double gap = n.dot(b_.position[at(corner)] - b_.position[at(best)]);
      if (gap <= options_.distance)
        add_vertex_edge(corner, best, t, gap, n);
      return;
    }
    if (lies_along_side(v, w) || lies_along_side(w, v))
      return;
    const Wedge a = wedge(v);
    const Wedge c = wedge(w);
    const double sa = direction_angle(a.start);
    const double sc = direction_angle(c.start);
    if (arc_overlap(sa, a.extent, sc, c.extent) >= options_.angle_overlap)
      return;
    ++vertex_vertex_;
    const double straight = std::numbers::pi + 1e-12;
    auto against = [&](int vertex, int edge) {
      ContactCandidate candidate;
      candidate.slave = vertex;
      candidate.master = edge;
      return candidate;
    };
    if (c.extent > straight && a.extent <= straight) {
      // The reflex angle's two edges are the entrance lines (3.2 [2]).
      add_if_entering(against(v, w), signed_distance(v, w));
      add_if_entering(against(v, b_.previous[at(w)]), signed_distance(v, b_.previous[at(w)]));
      return;
    }
    if (a.extent > straight && c.extent <= straight) {
      add_if_entering(against(w, v), signed_distance(w, v));
      add_if_entering(against(w, b_.previous[at(v)]), signed_distance(w, b_.previous[at(v)]));
      return;
    }
    if (a.extent > straight && c.extent > straight)
      return; // two reflex angles cannot touch without overlapping
    // Two convex angles (3.2 [1]): the entrance lines bound the narrower of the two gaps
    // between the translated wedges; one spring, on the line passed first.
    const double gap_after_a = std::fmod(sc - (sa + a.extent) + 2.0 * two_pi, two_pi);
    const double gap_after_c = std::fmod(sa - (sc + c.extent) + 2.0 * two_pi, two_pi);
    ContactCandidate candidate;
    if (gap_after_a <= gap_after_c) {
      // a's finishing ray (edge previous[v]) faces c's starting ray (edge w).
      candidate = against(v, w);
      candidate.alternative_slave = w;
      candidate.alternative_master = b_.previous[at(v)];
    } else {
      candidate = against(v, b_.previous[at(w)]);
      candidate.alternative_slave = w;
      candidate.alternative_master = v;
    }
    // The spring goes on the line passed by the least (ContactSystem::choose_entrance_line()).
    add_if_entering(candidate, std::max(signed_distance(candidate.slave, candidate.master),
                                        signed_distance(candidate.alternative_slave,
                                                        candidate.alternative_master)));
  }

  /// Adds the angle-to-angle candidate @p c whose spring starts @p gap from its line, if a new
  /// contact may start that deep (as in add_vertex_edge()) or it was closed in the last step.
  /// A vertex behind its entrance line by more did not come in through that angle within a
  /// step: it lies on a face of the other block elsewhere. Where a joint meets a free face
  /// next to another joint's crossing, the crossing's corner of one block paired with the
  /// reflex corners of the other block's face 0.2 m away, behind their lines, and the springs
  /// they got (locked, a new contact taking its penetration as its zero) pushed the blocks
  /// apart with meganewtons once they moved (a tunnel's crown jacked 6 mm up).
  void add_if_entering(const ContactCandidate& c, double gap) {
    if (gap < -options_.penetration && !kept(c))
      return;
    add(c);
  }

  /// The distance of vertex @p v from the line of edge @p e, positive on its void side.
  double signed_distance(int v, int e) const {
    return outward_normal(e).dot(b_.position[at(v)] - b_.position[at(e)]);
  }

  const ContactBoundary& b_;
  const DetectionOptions& options_;
  KeySet keep_;
  double rounding_ = 0.0;    ///< rounding_length() of the boundary
  double cos_overlap_ = 0.0; ///< std::cos(options_.angle_overlap)
  double sin_overlap_ = 0.0; ///< std::sin(options_.angle_overlap)
  KeySet seen_;
  std::vector<double> angle_;       ///< b_.angle(v) of every vertex
  std::vector<unsigned char> flat_; ///< flat(v) of every vertex
  std::vector<Point2> direction_;   ///< b_.direction(e) of every edge
  KeySet edge_pairs_;               ///< pair_key() of the edge-to-edge contacts
  KeySet vertex_pairs_;             ///< pair_key() of the angle pairs tested
  std::vector<ContactCandidate> result_;
  long vertex_edge_ = 0;
  long vertex_vertex_ = 0;
  long edge_edge_ = 0;
};

} // namespace

double rounding_length(const ContactBoundary& boundary) {
  double extent = 0.0;
  for (const Point2& x : boundary.position)
    extent = std::max(extent, x.cwiseAbs().maxCoeff());
  return 512.0 * std::numeric_limits<double>::epsilon() * extent;
}

double ContactBoundary::angle(int v) const {
  const Point2 out = position[at(next[at(v)])] - position[at(v)];
  const Point2 in = position[at(previous[at(v)])] - position[at(v)];
  double a = std::atan2(cross(out, in), out.dot(in));
  if (a <= 0.0)
    a += two_pi;
  return a;
}

Point2 ContactBoundary::direction(int e) const {
  return (position[at(next[at(e)])] - position[at(e)]).normalized();
}

Point2 ContactBoundary::outward_normal(int e) const { return right_normal(direction(e)); }

bool ContactBoundary::adjacent(int e, int f) const {
  return e == f || next[at(e)] == f || next[at(f)] == e;
}

std::vector<ContactCandidate> detect_contacts(const ContactBoundary& boundary,
                                              const DetectionOptions& options,
                                              const std::vector<std::uint64_t>& keep,
                                              DetectionStats* stats) {
  NMM_ASSERT(options.distance >= 0.0 && options.penetration >= 0.0, "negative contact distance");
  Detector detector(boundary, options, keep);
  return detector.run(stats);
}

} // namespace nmm
