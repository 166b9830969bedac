// SPDX-License-Identifier: MIT
#include "io/scene_bolts.hpp"

#include "io/text.hpp"
#include "mesh/error.hpp"

#include <cmath>
#include <string>
#include <utility>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

[[noreturn]] void fail(const CaseSpec& spec, const BoltSpec& bolt, const std::string& message) {
  throw InputError(spec.file.string(), bolt.line, 0, message);
}

/// The straight segments of a bolt: its from and to, or each gmsh curve of its curve.
std::vector<std::pair<Point2, Point2>>
segments_of(const CaseSpec& spec, const PhysicalMesh& physical, const BoltSpec& bolt) {
  if (bolt.from && bolt.to)
    return {{*bolt.from, *bolt.to}};
  const int curve = physical.find_curve(bolt.curve);
  if (curve < 0)
    fail(spec, bolt,
         "[[bolt]] " + in_quotes(bolt.name) + ": curve " + in_quotes(bolt.curve) +
             " is not a Physical Curve of " + spec.geometry.filename().string() +
             " (it has: " + physical.curve_names() + "); correct the name, or give from and to");
  std::vector<std::pair<Point2, Point2>> segments;
  for (const std::vector<Point2>& polyline : physical.curves[at(curve)].polylines) {
    const Point2 a = polyline.front();
    const Point2 b = polyline.back();
    const double length = (b - a).norm();
    for (const Point2& x : polyline) {
      const Point2 d = b - a;
      const double off = length > 0.0 ? std::abs(d.x() * (x - a).y() - d.y() * (x - a).x()) / length
                                      : (x - a).norm();
      if (!(off <= 1e-3 * length))
        fail(spec, bolt,
             "[[bolt]] " + in_quotes(bolt.name) + ": a curve of " + in_quotes(bolt.curve) +
                 " from " + point_text(a, 6) + " to " + point_text(b, 6) + " passes " +
                 point_text(x, 6) + ", " + number_text(off, 3) +
                 " m off its chord: a bolt is straight; draw it as a straight line");
    }
    segments.emplace_back(a, b);
  }
  return segments;
}

} // namespace

std::vector<Bolt> place_bolts(const CaseSpec& spec,
                              const PhysicalMesh& physical,
                              const Model& model,
                              double tolerance,
                              int stage) {
  std::vector<Bolt> bolts;
  for (const BoltSpec& b : spec.bolts) {
    if (b.stage != stage)
      continue;
    const std::vector<std::pair<Point2, Point2>> segments = segments_of(spec, physical, b);
    for (std::size_t k = 0; k < segments.size(); ++k) {
      const auto& [from, to] = segments[k];
      Bolt bolt;
      bolt.name = segments.size() == 1 ? b.name : b.name + "_" + std::to_string(k + 1);
      bolt.kind = b.kind;
      bolt.rupture_force = b.rupture_force;
      bolt.hardening = b.hardening;
      const std::string subject = "[[bolt]] " + in_quotes(bolt.name);
      for (const Point2& end : {from, to}) {
        if (model.find_element(end, tolerance) < 0)
          fail(spec, b,
               subject + ": its end " + point_text(end) + " lies outside the material of " +
                   spec.geometry.filename().string() +
                   ", so it would anchor in nothing; move it into a Physical Surface");
      }
      const int first = model.elements[at(model.find_element(from, tolerance))].block;
      const int last = model.elements[at(model.find_element(to, tolerance))].block;
      if (first == last)
        fail(spec, b,
             subject + ": both ends, " + point_text(from) + " and " + point_text(to) +
                 ", lie in one block, so the bolt would hold nothing to anything; a bolt ties "
                 "blocks across joints: make it long enough to reach the block behind the "
                 "joint it is to hold");
      bolt.bars = make_bolt_bars(model, b.kind, from, to, b.axial_rigidity((to - from).norm()),
                                 b.pretension, b.yield_force, tolerance);
      NMM_ASSERT(!bolt.bars.empty(), "a bolt with both ends in the material has bars");
      bolts.push_back(std::move(bolt));
    }
  }
  return bolts;
}

} // namespace nmm
