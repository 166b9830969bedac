// SPDX-License-Identifier: MIT
// ModelReader's surfaces: the loops of a geometric surface from its boundary curves, and of a
// meshed (discrete) one from the boundary edges of its elements; and the edge chaining both
// use.
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
#include <unordered_map>
#include <utility>
#include <vector>

namespace nmm::detail {

std::vector<Chain> chain_edges(const std::vector<std::array<std::size_t, 2>>& edges) {
  std::unordered_map<std::size_t, std::vector<std::size_t>> incident;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    incident[edges[e][0]].push_back(e);
    incident[edges[e][1]].push_back(e);
  }
  std::vector<bool> used(edges.size(), false);
  auto walk = [&](std::size_t edge, std::size_t start) {
    Chain chain;
    chain.first_node = start;
    std::size_t node = start;
    while (true) {
      used[edge] = true;
      const bool forward = edges[edge][0] == node;
      chain.edges.emplace_back(edge, forward);
      node = forward ? edges[edge][1] : edges[edge][0];
      if (node == start) {
        chain.closed = true;
        break;
      }
      // Where several edges meet (two loops touching), prefer the one that follows the
      // current edge in the input: gmsh lists a surface's boundary loop by loop.
      std::optional<std::size_t> next;
      for (const std::size_t candidate : incident[node]) {
        if (used[candidate])
          continue;
        if (!next || (*next < edge && candidate > edge))
          next = candidate;
      }
      if (!next)
        break;
      edge = *next;
    }
    chain.last_node = node;
    return chain;
  };
  std::vector<Chain> chains;
  // Open paths first, started at an end (a node of odd degree), never in their middle.
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (used[e])
      continue;
    for (const std::size_t end : edges[e]) {
      if (incident[end].size() % 2 == 1) {
        chains.push_back(walk(e, end));
        break;
      }
    }
  }
  for (std::size_t e = 0; e < edges.size(); ++e) {
    if (!used[e])
      chains.push_back(walk(e, edges[e][0]));
  }
  return chains;
}

Polygon ModelReader::surface(int tag, const std::string& group) {
  std::string type;
  gmsh::model::getType(2, tag, type);
  const std::string context =
      "Physical Surface \"" + group + "\" (gmsh surface " + std::to_string(tag) + ")";
  std::vector<Loop> loops =
      type == "Discrete surface" ? discrete_loops(tag, context) : curve_loops(tag, context);
  if (loops.empty())
    throw InputError(file_ + ": " + context +
                     " has no boundary curves; define it from a closed Curve Loop");
  // The loop enclosing the others has the largest area; validate_physical_mesh() checks
  // that the holes do lie inside it.
  const auto outer = std::max_element(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    return std::abs(signed_area(a)) < std::abs(signed_area(b));
  });
  Polygon polygon;
  polygon.outer = std::move(*outer);
  loops.erase(outer);
  polygon.holes = std::move(loops);
  return polygon;
}

std::vector<Loop> ModelReader::curve_loops(int tag, const std::string& context) {
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary({{2, tag}}, boundary, false, true, false);
  // A curve listed twice (a slit traversed both ways) lies inside the surface: not part of
  // its outline. Curves embedded with "In Surface" are not listed at all.
  std::map<int, int> count;
  for (const auto& dim_tag : boundary)
    ++count[std::abs(dim_tag.second)];
  std::vector<std::vector<Point2>> pieces;
  std::vector<int> piece_curve;
  for (const auto& dim_tag : boundary) {
    const int curve_tag = std::abs(dim_tag.second);
    if (count[curve_tag] != 1)
      continue;
    outlines_[tag].push_back(curve_tag);
    for (const std::vector<Point2>& polyline : curve(curve_tag, context)) {
      std::vector<Point2>& piece = pieces.emplace_back(polyline);
      if (dim_tag.second < 0)
        std::reverse(piece.begin(), piece.end());
      piece_curve.push_back(curve_tag);
    }
  }
  // End points are exact gmsh point coordinates, so equal coordinates mean a shared point.
  std::map<std::pair<double, double>, std::size_t> node_of;
  std::vector<Point2> node_point;
  auto node = [&](const Point2& p) {
    const auto [it, inserted] = node_of.try_emplace({p.x(), p.y()}, node_point.size());
    if (inserted)
      node_point.push_back(p);
    return it->second;
  };
  std::vector<std::array<std::size_t, 2>> edges;
  for (const std::vector<Point2>& piece : pieces)
    edges.push_back({node(piece.front()), node(piece.back())});

  std::vector<Loop> loops;
  std::vector<std::string> loose_ends;
  std::vector<int> open_curves;
  for (const Chain& chain : chain_edges(edges)) {
    if (!chain.closed) {
      loose_ends.push_back(point_text(node_point[chain.first_node]));
      loose_ends.push_back(point_text(node_point[chain.last_node]));
      for (const auto& step : chain.edges)
        open_curves.push_back(piece_curve[step.first]);
      continue;
    }
    Loop& loop = loops.emplace_back();
    for (const auto& [edge, forward] : chain.edges) {
      const std::vector<Point2>& piece = pieces[edge];
      // Every piece but the last point, which is the next piece's first.
      if (forward)
        loop.insert(loop.end(), piece.begin(), piece.end() - 1);
      else
        loop.insert(loop.end(), piece.rbegin(), piece.rend() - 1);
    }
  }
  if (!open_curves.empty()) {
    std::string ends;
    for (std::size_t i = 0; i < loose_ends.size() && i < 6; ++i)
      ends += (i > 0 ? (i + 1 == loose_ends.size() ? " and " : ", ") : "") + loose_ends[i];
    throw InputError(file_ + ": " + context + ": the boundary does not close: curves " +
                     tag_list(open_curves) + " leave loose ends at " + ends +
                     "; make consecutive curves of each Curve Loop share their end Point "
                     "(Coherence in the built-in kernel, BooleanFragments in OpenCASCADE)");
  }
  return loops;
}

std::vector<Loop> ModelReader::discrete_loops(int tag, const std::string& context) {
  const std::vector<std::vector<std::size_t>> elements = element_corners(2, tag);
  if (elements.empty()) {
    throw InputError(file_ + ": " + context +
                     " comes from a mesh but has no 2D elements; mesh it (gmsh -2) before "
                     "saving the .msh");
  }
  // Boundary edges of the surface mesh are those used by one element only; kept in the
  // order of first use so that loops come out the same on every run.
  struct EdgeUse {
    std::array<std::size_t, 2> directed;
    std::size_t first_use;
    int count;
  };
  std::map<std::pair<std::size_t, std::size_t>, EdgeUse> uses;
  std::size_t order = 0;
  for (const std::vector<std::size_t>& element : elements) {
    for (std::size_t i = 0; i < element.size(); ++i) {
      const std::size_t a = element[i];
      const std::size_t b = element[(i + 1) % element.size()];
      const auto found =
          uses.try_emplace({std::min(a, b), std::max(a, b)}, EdgeUse{{a, b}, order++, 0}).first;
      ++found->second.count;
    }
  }
  std::vector<EdgeUse> boundary;
  for (const auto& use : uses) {
    if (use.second.count == 1)
      boundary.push_back(use.second);
  }
  std::sort(boundary.begin(), boundary.end(),
            [](const EdgeUse& a, const EdgeUse& b) { return a.first_use < b.first_use; });
  std::vector<std::array<std::size_t, 2>> edges;
  for (const EdgeUse& use : boundary)
    edges.push_back(use.directed);
  std::vector<Loop> loops;
  for (const Chain& chain : chain_edges(edges)) {
    if (!chain.closed)
      throw InputError(file_ + ": " + context + ": the boundary of its mesh does not close near " +
                       point_text(planar(nodes_.at(chain.first_node))) +
                       "; save the mesh again from gmsh");
    Loop& loop = loops.emplace_back();
    for (const auto& [edge, forward] : chain.edges)
      loop.push_back(in_plane(nodes_.at(edges[edge][forward ? 0 : 1]), context));
  }
  return loops;
}

} // namespace nmm::detail
