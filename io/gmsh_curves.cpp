// SPDX-License-Identifier: MIT
// ModelReader's curves: a gmsh curve as polylines in the plane, straight lines as they are,
// curved ones sampled by adaptive subdivision within the curve tolerance, discrete ones from
// their line elements; and points.
#include "io/gmsh_internal.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace nmm::detail {

namespace {

/// Per initial chord, at most 2^16 subdivisions: enough for a 1e-9 relative tolerance on a
/// circle, and bounded work on a curve gmsh evaluates badly.
constexpr int max_subdivision_depth = 16;

double distance_to_segment(const Point3& q, const Point3& a, const Point3& b) {
  const Point3 ab = b - a;
  const double length_squared = ab.squaredNorm();
  if (length_squared == 0.0)
    return (q - a).norm();
  const double s = std::clamp((q - a).dot(ab) / length_squared, 0.0, 1.0);
  return (q - (a + s * ab)).norm();
}

} // namespace

const std::vector<std::vector<Point2>>& ModelReader::curve(int tag, const std::string& context) {
  const auto found = curves_.find(tag);
  if (found != curves_.end())
    return found->second;
  std::string type;
  gmsh::model::getType(1, tag, type);
  std::vector<std::vector<Point3>> polylines;
  if (type == "Discrete curve")
    polylines = discrete_curve(tag, context);
  else
    polylines.push_back(parametric_curve(tag, type, context));
  if (type != "Line")
    sampled_.insert(tag);
  std::vector<std::vector<Point2>> result;
  for (const std::vector<Point3>& polyline : polylines) {
    std::vector<Point2>& points = result.emplace_back();
    for (const Point3& p : polyline)
      points.push_back(in_plane(p, context));
  }
  return curves_.emplace(tag, std::move(result)).first->second;
}

Point2 ModelReader::point(int tag, const std::string& context) {
  std::vector<double> xyz;
  gmsh::model::getValue(0, tag, {}, xyz);
  if (xyz.size() < 3)
    throw InputError(file_ + ": " + context + ": gmsh cannot give the coordinates of point " +
                     std::to_string(tag));
  return in_plane(Point3(xyz[0], xyz[1], xyz[2]), context);
}

Point2 ModelReader::in_plane(const Point3& p, const std::string& context) const {
  if (!(std::abs(p.z()) <= z_limit_)) {
    throw InputError(file_ + ": " + context + ": the point " + point_text(planar(p)) +
                     " has z = " + number_text(p.z(), 10) +
                     "; nmm is two-dimensional: draw the whole geometry in the plane z = 0");
  }
  return planar(p);
}

std::vector<Point3> ModelReader::evaluate(int tag, const std::vector<double>& parameters) const {
  std::vector<double> xyz;
  gmsh::model::getValue(1, tag, parameters, xyz);
  if (xyz.size() != 3 * parameters.size())
    throw InputError(file_ + ": gmsh cannot evaluate curve " + std::to_string(tag));
  std::vector<Point3> points;
  points.reserve(parameters.size());
  for (std::size_t i = 0; i < parameters.size(); ++i)
    points.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return points;
}

std::optional<std::array<Point3, 2>>
ModelReader::end_points(int tag, const Point3& first, const Point3& last) const {
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary({{1, tag}}, boundary, false, false, false);
  std::vector<Point3> points;
  for (const auto& dim_tag : boundary) {
    std::vector<double> xyz;
    gmsh::model::getValue(0, std::abs(dim_tag.second), {}, xyz);
    if (xyz.size() == 3)
      points.emplace_back(xyz[0], xyz[1], xyz[2]);
  }
  if (points.empty())
    return std::nullopt;
  if (points.size() == 1)
    return std::array<Point3, 2>{points[0], points[0]};
  const double straight = (points[0] - first).norm() + (points[1] - last).norm();
  const double crossed = (points[1] - first).norm() + (points[0] - last).norm();
  if (straight <= crossed)
    return std::array<Point3, 2>{points[0], points[1]};
  return std::array<Point3, 2>{points[1], points[0]};
}

std::vector<Point3>
ModelReader::parametric_curve(int tag, const std::string& type, const std::string& context) {
  std::vector<double> low;
  std::vector<double> high;
  gmsh::model::getParametrizationBounds(1, tag, low, high);
  if (low.empty() || high.empty() || !(high[0] > low[0]))
    throw InputError(file_ + ": " + context + ": gmsh gives curve " + std::to_string(tag) + " (" +
                     type + ") no parameter range; redraw the curve");
  const double t0 = low[0];
  const double t1 = high[0];
  const std::vector<Point3> bounds = evaluate(tag, {t0, t1});
  const auto ends = end_points(tag, bounds[0], bounds[1]);
  const Point3 start = ends ? (*ends)[0] : bounds[0];
  const Point3 end = ends ? (*ends)[1] : bounds[1];
  if (type == "Line")
    return {start, end};

  // Adaptive subdivision, one level at a time so that gmsh evaluates each level in one
  // call. A closed curve starts from 4 chords so that its first chord is not a point.
  const bool closed = (end - start).norm() == 0.0;
  const int initial = closed ? 4 : 1;
  std::map<double, Point3> samples;
  std::vector<double> parameters;
  for (int i = 0; i <= initial; ++i)
    parameters.push_back(i == initial ? t1 : t0 + (t1 - t0) * i / initial);
  const std::vector<Point3> initial_points = evaluate(tag, parameters);
  for (std::size_t i = 0; i < parameters.size(); ++i)
    samples.emplace(parameters[i], initial_points[i]);

  struct Piece {
    double t0;
    double t1;
    int depth;
  };
  std::vector<Piece> pending;
  for (int i = 0; i < initial; ++i)
    pending.push_back(
        {parameters[static_cast<std::size_t>(i)], parameters[static_cast<std::size_t>(i) + 1], 0});
  double unresolved = 0.0;
  while (!pending.empty()) {
    std::vector<double> inner;
    inner.reserve(3 * pending.size());
    for (const Piece& piece : pending) {
      for (int k = 1; k <= 3; ++k)
        inner.push_back(piece.t0 + (piece.t1 - piece.t0) * k / 4.0);
    }
    const std::vector<Point3> values = evaluate(tag, inner);
    std::vector<Piece> next;
    for (std::size_t p = 0; p < pending.size(); ++p) {
      const Piece& piece = pending[p];
      const Point3& a = samples.at(piece.t0);
      const Point3& b = samples.at(piece.t1);
      double deviation = 0.0;
      for (std::size_t k = 0; k < 3; ++k)
        deviation = std::max(deviation, distance_to_segment(values[3 * p + k], a, b));
      const bool too_long = max_chord_ > 0.0 && (b - a).norm() > max_chord_;
      if (deviation <= tolerance_ && !too_long)
        continue;
      if (piece.depth >= max_subdivision_depth) {
        if (deviation > tolerance_)
          unresolved = std::max(unresolved, deviation);
        continue;
      }
      const double middle = inner[3 * p + 1];
      samples.emplace(middle, values[3 * p + 1]);
      next.push_back({piece.t0, middle, piece.depth + 1});
      next.push_back({middle, piece.t1, piece.depth + 1});
    }
    pending = std::move(next);
  }
  if (unresolved > 0.0) {
    throw InputError(file_ + ": " + context + ": curve " + std::to_string(tag) + " (" + type +
                     ") still deviates by " + number_text(unresolved, 10) +
                     " m from its chords after " + std::to_string(1 << max_subdivision_depth) +
                     " subdivisions, more than the curve tolerance of " +
                     number_text(tolerance_, 10) +
                     " m; raise the curve tolerance or check that the curve is smooth");
  }
  std::vector<Point3> points;
  points.reserve(samples.size());
  for (const auto& sample : samples)
    points.push_back(sample.second);
  points.front() = start;
  points.back() = end;
  return points;
}

std::vector<std::vector<Point3>> ModelReader::discrete_curve(int tag, const std::string& context) {
  const std::vector<std::vector<std::size_t>> lines = element_corners(1, tag);
  if (lines.empty()) {
    throw InputError(file_ + ": " + context + ": curve " + std::to_string(tag) +
                     " comes from a mesh but has no line elements; mesh it (gmsh -2) and "
                     "keep its elements when saving (Physical Curve or Mesh.SaveAll = 1)");
  }
  std::vector<std::array<std::size_t, 2>> edges;
  for (const std::vector<std::size_t>& line : lines) {
    if (line.size() >= 2)
      edges.push_back({line[0], line[1]});
  }
  std::vector<std::vector<Point3>> polylines;
  for (const Chain& chain : chain_edges(edges)) {
    std::vector<Point3>& points = polylines.emplace_back();
    points.push_back(nodes_.at(chain.first_node));
    for (const auto& [edge, forward] : chain.edges)
      points.push_back(nodes_.at(edges[edge][forward ? 1 : 0]));
  }
  return polylines;
}

} // namespace nmm::detail
