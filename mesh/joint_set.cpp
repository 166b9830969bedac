// SPDX-License-Identifier: MIT
// mesh/joint_set.cpp — joint sets to joint segments: lines, traces and gaps, clipping to the
// material, snapping and dropping near other lines (the rules are in joint_set.hpp).
#include "mesh/joint_set.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

namespace nmm {
namespace {

double cross(const Point2& u, const Point2& v) { return u.x() * v.y() - u.y() * v.x(); }

double distance_to_segment(const Point2& p, const Point2& a, const Point2& b) {
  const Point2 ab = b - a;
  const double length2 = ab.squaredNorm();
  const double s = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (p - (a + s * ab)).norm();
}

/// Where two segments cross (end points included), if they do and are not parallel.
bool segment_crossing(const JointSegment& s, const JointSegment& q, Point2& where) {
  const Point2 d = s.b - s.a;
  const Point2 e = q.b - q.a;
  const double denominator = cross(d, e);
  if (std::abs(denominator) <= 1e-14 * d.norm() * e.norm())
    return false;
  const double u = cross(q.a - s.a, e) / denominator;
  const double v = cross(q.a - s.a, d) / denominator;
  if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0)
    return false;
  where = s.a + u * d;
  return true;
}

/// A uniform value in [mean - deviation, mean + deviation] from the raw output of the
/// generator: the top 53 bits as a fraction in [0, 1). Written out so that the joints do
/// not depend on the standard library's std::uniform_real_distribution.
class Draw {
public:
  explicit Draw(std::uint64_t seed) : engine_(seed) {}
  double operator()(double mean, double deviation) {
    if (deviation <= 0.0)
      return mean;
    const double unit = static_cast<double>(engine_() >> 11U) * 0x1.0p-53;
    return mean + deviation * (2.0 * unit - 1.0);
  }

private:
  std::mt19937_64 engine_;
};

/// One straight carrier of joints: the points c + u t for u in [u0, u1].
struct Trace {
  Point2 c;
  Point2 t;
  double u0;
  double u1;
};

/// Buckets of segments and points on a uniform grid, so that the lines near a joint are
/// found without looking at every line of the model (a set of 20,000 joints would otherwise
/// take 4e8 tests). A segment is in every cell its walk at steps of half a cell passes, and
/// in their neighbours; a query walks its segment the same way. Anything within half a cell
/// of a query segment is therefore among the candidates (tolerance <= cell / 2).
class Grid {
public:
  Grid(const BoundingBox& material, double cell) : cell_(cell) {
    const Point2 margin(4.0 * cell, 4.0 * cell);
    min_ = material.min - margin;
    max_ = material.max + margin;
    nx_ = static_cast<int>(std::ceil((max_.x() - min_.x()) / cell)) + 1;
    ny_ = static_cast<int>(std::ceil((max_.y() - min_.y()) / cell)) + 1;
    segments_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
    points_.resize(segments_.size());
  }

  void add_segment(int id, const JointSegment& s) {
    walk(s, [&](std::size_t c) {
      if (segments_[c].empty() || segments_[c].back() != id)
        segments_[c].push_back(id);
    });
  }
  void add_point(int id, const Point2& p) {
    if (inside(p))
      points_[cell_of(p)].push_back(id);
  }
  /// Candidate segments / points within half a cell of @p s, each once.
  std::vector<int> segments_along(const JointSegment& s) const { return collect(s, segments_); }
  std::vector<int> points_along(const JointSegment& s) const { return collect(s, points_); }

private:
  bool inside(const Point2& p) const {
    return p.x() >= min_.x() && p.x() <= max_.x() && p.y() >= min_.y() && p.y() <= max_.y();
  }
  std::size_t cell_of(const Point2& p) const {
    const int i = std::clamp(static_cast<int>((p.x() - min_.x()) / cell_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((p.y() - min_.y()) / cell_), 0, ny_ - 1);
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
           static_cast<std::size_t>(i);
  }

  /// Calls @p visit for the cells along @p s clipped to the grid (Liang-Barsky) and their
  /// neighbours; outside the grid nothing can come near the material.
  template <class Visit> void walk(const JointSegment& s, Visit visit) const {
    double t0 = 0.0;
    double t1 = 1.0;
    const Point2 d = s.b - s.a;
    for (int axis = 0; axis < 2; ++axis) {
      if (d[axis] == 0.0) {
        if (s.a[axis] < min_[axis] || s.a[axis] > max_[axis])
          return;
        continue;
      }
      double ta = (min_[axis] - s.a[axis]) / d[axis];
      double tb = (max_[axis] - s.a[axis]) / d[axis];
      if (ta > tb)
        std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 > t1)
      return;
    const Point2 a = s.a + t0 * d;
    const Point2 b = s.a + t1 * d;
    const long steps = static_cast<long>(std::ceil((b - a).norm() / (0.5 * cell_))) + 1;
    for (long k = 0; k <= steps; ++k) {
      const Point2 p = a + (static_cast<double>(k) / static_cast<double>(steps)) * (b - a);
      const std::size_t c = cell_of(p);
      const int i = static_cast<int>(c % static_cast<std::size_t>(nx_));
      const int j = static_cast<int>(c / static_cast<std::size_t>(nx_));
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di)
          if (i + di >= 0 && i + di < nx_ && j + dj >= 0 && j + dj < ny_)
            visit(static_cast<std::size_t>(j + dj) * static_cast<std::size_t>(nx_) +
                  static_cast<std::size_t>(i + di));
    }
  }

  std::vector<int> collect(const JointSegment& s,
                           const std::vector<std::vector<int>>& cells) const {
    std::vector<int> result;
    walk(s, [&](std::size_t c) { result.insert(result.end(), cells[c].begin(), cells[c].end()); });
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
  }

  double cell_;
  Point2 min_;
  Point2 max_;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<std::vector<int>> segments_;
  std::vector<std::vector<int>> points_;
};

/// The material polygons, the boundary edges and the lines already in the model.
class Scene {
public:
  /// @param cell  the grid's cell, at least twice the largest snap tolerance.
  Scene(const PhysicalMesh& physical, std::span<const int> drawn_joints, double cell)
      : physical_(physical), grid_(material_bounding_box(physical), cell) {
    for (const MaterialRegion& region : physical.regions) {
      for (const Polygon& polygon : region.polygons) {
        add_loop(polygon.outer);
        for (const Loop& hole : polygon.holes)
          add_loop(hole);
      }
    }
    const std::size_t first_joint = lines_.size();
    for (const int c : drawn_joints) {
      for (const auto& line : physical.curves[static_cast<std::size_t>(c)].polylines) {
        for (std::size_t i = 0; i + 1 < line.size(); ++i)
          add_line({line[i], line[i + 1]}, false);
        add_junction(line.front());
        add_junction(line.back());
      }
    }
    // Where drawn joints meet the boundary or each other, a generated joint passing by
    // would cut a sliver, as near a corner.
    for (std::size_t i = first_joint; i < lines_.size(); ++i) {
      for (const int j : grid_.segments_along(lines_[i])) {
        const JointSegment& q = lines_[static_cast<std::size_t>(j)];
        Point2 where;
        if (static_cast<std::size_t>(j) < i && segment_crossing(lines_[i], q, where) &&
            (where - lines_[i].a).norm() > 0.0 && (where - lines_[i].b).norm() > 0.0)
          add_junction(where);
      }
    }
  }

  /// Bounding box of the outer loops of @p regions (all regions when empty).
  BoundingBox region_box(const std::vector<int>& regions) const {
    BoundingBox box;
    for (std::size_t r = 0; r < physical_.regions.size(); ++r) {
      if (!regions.empty() &&
          std::find(regions.begin(), regions.end(), static_cast<int>(r)) == regions.end())
        continue;
      for (const Polygon& polygon : physical_.regions[r].polygons)
        for (const Point2& p : polygon.outer)
          box.extend(p);
    }
    return box;
  }

  /// Is @p p inside one of the polygons of @p regions (all regions when empty)?
  bool is_inside(const Point2& p, const std::vector<int>& regions) const {
    for (std::size_t r = 0; r < physical_.regions.size(); ++r) {
      if (!regions.empty() &&
          std::find(regions.begin(), regions.end(), static_cast<int>(r)) == regions.end())
        continue;
      for (const Polygon& polygon : physical_.regions[r].polygons) {
        if (!in_loop(p, polygon.outer))
          continue;
        if (std::none_of(polygon.holes.begin(), polygon.holes.end(),
                         [&](const Loop& hole) { return in_loop(p, hole); }))
          return true;
      }
    }
    return false;
  }

  /// The boundary edges (@p boundary) or the joints near the segment @p s.
  std::vector<const JointSegment*> lines_along(const JointSegment& s, bool boundary) const {
    std::vector<const JointSegment*> result;
    for (const int id : grid_.segments_along(s))
      if (is_boundary_[static_cast<std::size_t>(id)] == (boundary ? 1 : 0))
        result.push_back(&lines_[static_cast<std::size_t>(id)]);
    return result;
  }

  /// Does every one of 9 points along @p s lie within @p tolerance of a line?
  bool is_near_lines_everywhere(const JointSegment& s, double tolerance) const {
    const std::vector<int> near = grid_.segments_along(s);
    for (int i = 0; i < 9; ++i) {
      const Point2 sample = s.a + (i + 0.5) / 9.0 * (s.b - s.a);
      if (std::none_of(near.begin(), near.end(), [&](int id) {
            const JointSegment& q = lines_[static_cast<std::size_t>(id)];
            return distance_to_segment(sample, q.a, q.b) < tolerance;
          }))
        return false;
    }
    return true;
  }

  /// Is a corner of the boundary or a meeting point of lines within @p tolerance of @p s?
  bool passes_near_junction(const JointSegment& s, double tolerance) const {
    const std::vector<int> near = grid_.points_along(s);
    return std::any_of(near.begin(), near.end(), [&](int id) {
      return distance_to_segment(junctions_[static_cast<std::size_t>(id)], s.a, s.b) < tolerance;
    });
  }

  /// Adds an accepted joint; @p ends are its ends that lie on a line (boundary or joint).
  /// @return the points where it meets the lines before it (ends on lines included).
  int accept(const JointSegment& s, const std::vector<Point2>& ends) {
    int meetings = static_cast<int>(ends.size());
    for (const Point2& e : ends)
      add_junction(e);
    for (const int id : grid_.segments_along(s)) {
      Point2 where;
      if (!segment_crossing(s, lines_[static_cast<std::size_t>(id)], where))
        continue;
      // An end snapped onto this line lies within the overshoot of it: counted already.
      if (std::any_of(ends.begin(), ends.end(),
                      [&](const Point2& e) { return (e - where).norm() < overshoot_ * 10.0; }))
        continue;
      add_junction(where);
      ++meetings;
    }
    add_line(s, false);
    return meetings;
  }

  void set_overshoot(double overshoot) { overshoot_ = overshoot; }

private:
  static bool in_loop(const Point2& p, const Loop& loop) {
    bool inside = false;
    for (std::size_t i = 0, j = loop.size() - 1; i < loop.size(); j = i++) {
      const Point2& a = loop[i];
      const Point2& b = loop[j];
      if ((a.y() > p.y()) != (b.y() > p.y()) &&
          p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
        inside = !inside;
    }
    return inside;
  }

  void add_loop(const Loop& loop) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2& previous = loop[(i + n - 1) % n];
      const Point2& here = loop[i];
      const Point2& next = loop[(i + 1) % n];
      add_line({here, next}, true);
      // Material is on the left of a validated loop (outer counter-clockwise, holes
      // clockwise): a left turn is a convex corner, which a line passing near cuts off as
      // a sliver. Sampled curves turn by a few degrees per vertex and do not count.
      const Point2 in = here - previous;
      const Point2 out = next - here;
      const double turn = std::atan2(cross(in, out), in.dot(out));
      if (turn > 10.0 * std::numbers::pi / 180.0)
        add_junction(here);
    }
  }

  void add_line(const JointSegment& s, bool boundary) {
    grid_.add_segment(static_cast<int>(lines_.size()), s);
    lines_.push_back(s);
    is_boundary_.push_back(boundary ? 1 : 0);
  }
  void add_junction(const Point2& p) {
    grid_.add_point(static_cast<int>(junctions_.size()), p);
    junctions_.push_back(p);
  }

  const PhysicalMesh& physical_;
  Grid grid_;
  std::vector<JointSegment> lines_;
  std::vector<char> is_boundary_;
  std::vector<Point2> junctions_;
  double overshoot_ = 0.0;
};

/// Why pieces of a set were dropped or snapped, for the notes.
struct Tally {
  long short_pieces = 0;
  long near_lines = 0;
  long near_junctions = 0;
  long snapped_to_boundary = 0;
  long snapped_to_joint = 0;
};

/// Generates and clips the joints of one set into @p scene.
class SetGenerator {
public:
  SetGenerator(Scene& scene, const JointSetParameters& set, double tolerance, long blocks_before)
      : scene_(scene), set_(set), tolerance_(tolerance), draw_(set.seed),
        block_bound_(blocks_before) {
    const double radians = set.angle_degrees * std::numbers::pi / 180.0;
    t_ = Point2(std::cos(radians), std::sin(radians));
    n_ = Point2(-t_.y(), t_.x());
    box_ = scene.region_box(set.regions);
  }

  std::vector<JointSegment> run() {
    if (box_.is_empty())
      return {};
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const Point2& corner : corners()) {
      low = std::min(low, (corner - set_.origin).dot(n_));
      high = std::max(high, (corner - set_.origin).dot(n_));
    }
    // Lines from the origin's upwards, then downwards, each spacing drawn in turn.
    double p = 0.0;
    if (set_.spacing_deviation <= 0.0 && p < low)
      p = std::ceil(low / set_.spacing) * set_.spacing;
    for (long visited = 0; p <= high + tolerance_; ++visited) {
      check_visits(visited);
      if (p >= low - tolerance_)
        line(p);
      p += draw_(set_.spacing, set_.spacing_deviation);
    }
    p = 0.0;
    if (set_.spacing_deviation <= 0.0 && p > high)
      p = std::floor(high / set_.spacing) * set_.spacing + set_.spacing;
    for (long visited = 0;; ++visited) {
      check_visits(visited);
      p -= draw_(set_.spacing, set_.spacing_deviation);
      if (p < low - tolerance_)
        break;
      if (p <= high + tolerance_)
        line(p);
    }
    return std::move(result_);
  }

  [[nodiscard]] long block_bound() const { return block_bound_; }
  [[nodiscard]] const Tally& tally() const { return tally_; }

private:
  std::vector<Point2> corners() const {
    return {box_.min, box_.max, Point2(box_.min.x(), box_.max.y()),
            Point2(box_.max.x(), box_.min.y())};
  }

  void check_visits(long visited) const {
    if (visited > 10'000'000) {
      throw InputError(set_.where + ": the origin is more than 10^7 spacings from the material; "
                                    "put `origin` on or near the model");
    }
  }

  /// Rotation of @p t by a drawn angle deviation.
  Point2 deviated(const Point2& t) {
    if (set_.angle_deviation_degrees <= 0.0)
      return t;
    const double d = draw_(0.0, set_.angle_deviation_degrees) * std::numbers::pi / 180.0;
    return {t.x() * std::cos(d) - t.y() * std::sin(d), t.x() * std::sin(d) + t.y() * std::cos(d)};
  }

  /// Extent along @p t of the set's bounding box seen from @p c.
  std::pair<double, double> extent(const Point2& c, const Point2& t) const {
    double low = std::numeric_limits<double>::infinity();
    double high = -low;
    for (const Point2& corner : corners()) {
      low = std::min(low, (corner - c).dot(t));
      high = std::max(high, (corner - c).dot(t));
    }
    return {low - 2.0 * tolerance_, high + 2.0 * tolerance_};
  }

  void line(double p) {
    const Point2 c = set_.origin + p * n_;
    if (!set_.trace) {
      const Point2 t = deviated(t_);
      const auto [low, high] = extent(c, t);
      clip({c, t, low, high});
      return;
    }
    const auto [low, high] = extent(c, t_);
    // Forwards from the origin's trace, then backwards; a gap narrower than the tolerance
    // joins its two traces into one (a rock bridge that thin would be a sliver).
    std::vector<std::pair<double, double>> spans;
    double u = 0.0;
    if (set_.trace_deviation <= 0.0 && set_.gap_deviation <= 0.0 &&
        set_.angle_deviation_degrees <= 0.0) {
      const double period = *set_.trace + set_.gap;
      u = std::floor(std::max(0.0, low) / period) * period;
    }
    for (long visited = 0; u <= high; ++visited) {
      check_visits(visited);
      const double length = draw_(*set_.trace, set_.trace_deviation);
      spans.emplace_back(u, u + length);
      u += length + draw_(set_.gap, set_.gap_deviation);
    }
    u = 0.0;
    if (set_.trace_deviation <= 0.0 && set_.gap_deviation <= 0.0 &&
        set_.angle_deviation_degrees <= 0.0) {
      const double period = *set_.trace + set_.gap;
      u = -std::floor(std::max(0.0, -high) / period) * period;
    }
    for (long visited = 0; u >= low; ++visited) {
      check_visits(visited);
      const double end = u - draw_(set_.gap, set_.gap_deviation);
      const double length = draw_(*set_.trace, set_.trace_deviation);
      spans.emplace_back(end - length, end);
      u = end - length;
    }
    std::sort(spans.begin(), spans.end());
    std::vector<std::pair<double, double>> merged;
    for (const auto& span : spans) {
      if (set_.angle_deviation_degrees <= 0.0 && !merged.empty() &&
          span.first - merged.back().second < tolerance_)
        merged.back().second = std::max(merged.back().second, span.second);
      else
        merged.push_back(span);
    }
    for (const auto& [u0, u1] : merged) {
      if (u1 < low || u0 > high)
        continue;
      if (set_.angle_deviation_degrees <= 0.0) {
        clip({c, t_, u0, u1});
      } else {
        const Point2 middle = c + 0.5 * (u0 + u1) * t_;
        clip({middle, deviated(t_), -0.5 * (u1 - u0), 0.5 * (u1 - u0)});
      }
    }
  }

  /// Parameters along the trace's line where it crosses @p lines.
  static std::vector<double> crossings(const Trace& trace,
                                       const std::vector<const JointSegment*>& lines) {
    std::vector<double> result;
    for (const JointSegment* line : lines) {
      const JointSegment& q = *line;
      const Point2 e = q.b - q.a;
      const double denominator = cross(trace.t, e);
      if (std::abs(denominator) <= 1e-14 * e.norm())
        continue;
      const double v = cross(q.a - trace.c, trace.t) / denominator;
      if (v < 0.0 || v > 1.0)
        continue;
      result.push_back(cross(q.a - trace.c, e) / denominator);
    }
    std::sort(result.begin(), result.end());
    return result;
  }

  /// Clips one trace to the set's material and hands each piece to keep().
  void clip(const Trace& trace) {
    // The line only near the trace: an end of this window is no boundary, and lies 2
    // tolerances beyond the trace, farther than any snap.
    const auto [line_low, line_high] = extent(trace.c, trace.t);
    const double low = std::max(line_low, trace.u0 - 2.0 * tolerance_);
    const double high = std::min(line_high, trace.u1 + 2.0 * tolerance_);
    const JointSegment reach{trace.c + low * trace.t, trace.c + high * trace.t};
    std::vector<double> cuts = crossings(trace, scene_.lines_along(reach, true));
    cuts.insert(cuts.begin(), low);
    cuts.push_back(high);
    // Material intervals of the line, adjacent ones merged (an interface inside the clipped
    // material is no end).
    std::vector<std::pair<double, double>> material;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      if (cuts[i + 1] - cuts[i] <= 0.0)
        continue;
      const Point2 middle = trace.c + 0.5 * (cuts[i] + cuts[i + 1]) * trace.t;
      if (!scene_.is_inside(middle, set_.regions))
        continue;
      if (!material.empty() && material.back().second >= cuts[i])
        material.back().second = cuts[i + 1];
      else
        material.emplace_back(cuts[i], cuts[i + 1]);
    }
    const std::vector<double> joints = crossings(trace, scene_.lines_along(reach, false));
    for (const auto& [m0, m1] : material) {
      if (m1 < trace.u0 - tolerance_ || m0 > trace.u1 + tolerance_)
        continue;
      keep(trace, m0, m1, joints);
    }
  }

  void keep(const Trace& trace, double m0, double m1, const std::vector<double>& joints) {
    const double overshoot = 1e-3 * tolerance_;
    double a = std::max(trace.u0, m0);
    double b = std::min(trace.u1, m1);
    std::vector<Point2> ends;
    const auto snap_free_end = [&](double& end, double direction) {
      double best = std::numeric_limits<double>::infinity();
      for (const double j : joints) {
        if (std::abs(j - end) < tolerance_ && std::abs(j - end) < std::abs(best - end))
          best = j;
      }
      if (std::isfinite(best)) {
        end = best + direction * overshoot;
        ends.push_back(trace.c + best * trace.t);
        ++tally_.snapped_to_joint;
      }
    };
    if (a - m0 < tolerance_) {
      if (trace.u0 > m0)
        ++tally_.snapped_to_boundary;
      ends.push_back(trace.c + m0 * trace.t);
      a = m0 - overshoot;
    } else {
      snap_free_end(a, -1.0);
    }
    if (m1 - b < tolerance_) {
      if (trace.u1 < m1)
        ++tally_.snapped_to_boundary;
      ends.push_back(trace.c + m1 * trace.t);
      b = m1 + overshoot;
    } else {
      snap_free_end(b, 1.0);
    }
    if (b - a < tolerance_) {
      ++tally_.short_pieces;
      return;
    }
    const JointSegment piece{trace.c + a * trace.t, trace.c + b * trace.t};
    const bool near_everywhere = scene_.is_near_lines_everywhere(piece, tolerance_);
    if (near_everywhere) {
      ++tally_.near_lines;
      return;
    }
    if (scene_.passes_near_junction(piece, tolerance_)) {
      ++tally_.near_junctions;
      return;
    }
    if (static_cast<long>(result_.size()) >= set_.max_joints) {
      throw InputError(set_.where + ": the joint set makes more than max_joints = " +
                       std::to_string(set_.max_joints) +
                       " joints; raise `max_joints` in this table (each joint adds contacts "
                       "and blocks) or give a larger `spacing` or `trace`");
    }
    block_bound_ += std::max(scene_.accept(piece, ends) - 1, 0);
    if (block_bound_ > set_.max_blocks) {
      throw InputError(set_.where +
                       ": with this joint set the material would be cut into "
                       "more than max_blocks = " +
                       std::to_string(set_.max_blocks) + " blocks (counted from the " +
                       std::to_string(result_.size() + 1) +
                       " joints made so far and their crossings); raise `max_blocks` in this "
                       "table or give a larger `spacing` or a shorter `trace`");
    }
    result_.push_back(piece);
  }

  Scene& scene_;
  const JointSetParameters& set_;
  double tolerance_;
  Draw draw_;
  long block_bound_;
  Point2 t_;
  Point2 n_;
  BoundingBox box_;
  std::vector<JointSegment> result_;
  Tally tally_;
};

std::string note(const JointSetParameters& set, const Tally& tally, double tolerance) {
  std::ostringstream out;
  out.precision(4);
  out << set.where << ": ";
  std::vector<std::string> parts;
  // "1 joint ... dropped", "3 joints ... dropped".
  const auto add = [&](long count, const std::string& noun, const std::string& what) {
    if (count > 0)
      parts.push_back(std::to_string(count) + " " + noun + (count == 1 ? " " : "s ") + what);
  };
  add(tally.short_pieces, "joint", "shorter than the tolerance dropped");
  add(tally.near_lines, "joint", "lying along a boundary or another joint dropped");
  add(tally.near_junctions, "joint", "passing by a corner or a joint crossing dropped");
  add(tally.snapped_to_boundary, "end", "moved onto the boundary");
  add(tally.snapped_to_joint, "end", "moved onto another joint");
  if (parts.empty())
    return {};
  for (std::size_t i = 0; i < parts.size(); ++i)
    out << (i == 0 ? "" : ", ") << parts[i];
  out << " (snap_tolerance = " << tolerance << " m: closer lines would cut sliver blocks)";
  return out.str();
}

} // namespace

double default_snap_tolerance(const PhysicalMesh& physical,
                              std::span<const JointSetParameters> sets) {
  const BoundingBox box = material_bounding_box(physical);
  double tolerance = box.is_empty() ? 0.0 : 2e-3 * box.size().norm();
  for (const JointSetParameters& set : sets)
    tolerance = std::min(tolerance, 0.1 * (set.spacing - set.spacing_deviation));
  return tolerance;
}

JointSetResult generate_joint_sets(const PhysicalMesh& physical,
                                   std::span<const int> drawn_joints,
                                   std::span<const JointSetParameters> sets) {
  JointSetResult result;
  const double automatic = default_snap_tolerance(physical, sets);
  double largest = automatic;
  for (const JointSetParameters& set : sets)
    largest = std::max(largest, set.snap_tolerance);
  const BoundingBox box = material_bounding_box(physical);
  // Cells of at least twice the tolerance (the grid's rule), and not more than about 400 x
  // 400 of them.
  Scene scene(physical, drawn_joints, std::max(2.0 * largest, 2.5e-3 * box.size().norm()));
  long blocks = 0;
  for (const MaterialRegion& region : physical.regions)
    blocks += static_cast<long>(region.polygons.size());
  for (const JointSetParameters& set : sets) {
    const double tolerance = set.snap_tolerance > 0.0 ? set.snap_tolerance : automatic;
    scene.set_overshoot(1e-3 * tolerance);
    SetGenerator generator(scene, set, tolerance, blocks);
    result.joints.push_back(generator.run());
    result.snap_tolerance.push_back(tolerance);
    blocks = generator.block_bound();
    if (std::string text = note(set, generator.tally(), tolerance); !text.empty())
      result.notes.push_back(std::move(text));
  }
  result.block_bound = blocks;
  return result;
}

} // namespace nmm
