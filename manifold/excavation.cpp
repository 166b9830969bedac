// SPDX-License-Identifier: MIT
// manifold/excavation.cpp — the Model's excavation by a `[[stage]]` (docs/formulation.md,
// "Excavation in stages"): elements switched off in place, the covers they leave without
// material fixed, those left with a sliver extended as the cover mesher's tiny covers.
#include "manifold/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

} // namespace

void Model::excavate(const std::vector<int>& removed, double min_cover_area_ratio) {
  for (const int e : removed) {
    elements[at(e)].excavated = true;
    elements[at(e)].release = 1.0;
  }
  // Each NMM cover's material area and its elements' triangles' area.
  std::vector<double> material(covers.size(), 0.0);
  std::vector<double> star(covers.size(), 0.0);
  for (int e = 0; e < n_elements(); ++e) {
    const ModelElement& element = elements[at(e)];
    if (element.kind != ElementKind::nmm)
      continue;
    const double full = std::abs(signed_area(triangle(e)));
    for (const int c : element.covers) {
      star[at(c)] += full;
      if (!element.excavated)
        material[at(c)] += element.area;
    }
  }
  const auto tiny = [&](int c) {
    return covers[at(c)].kind == ElementKind::nmm && material[at(c)] > 0.0 &&
           material[at(c)] < min_cover_area_ratio * star[at(c)];
  };
  const auto well_posed = [&](int e) {
    const ModelElement& element = elements[at(e)];
    if (element.excavated || element.kind != ElementKind::nmm)
      return false;
    for (const int c : element.covers) {
      if (tiny(c) || covers[at(c)].extension_element >= 0)
        return false;
    }
    return true;
  };
  for (int c = 0; c < n_covers(); ++c) {
    ModelCover& cover = covers[at(c)];
    const bool root_removed =
        cover.extension_element >= 0 && elements[at(cover.extension_element)].excavated;
    if (!tiny(c) && !root_removed)
      continue;
    int best = -1;
    double best_distance = std::numeric_limits<double>::infinity();
    for (int e = 0; e < n_elements(); ++e) {
      if (elements[at(e)].block != cover.block || !well_posed(e))
        continue;
      const std::array<Point2, 3> t = triangle(e);
      const double distance = ((t[0] + t[1] + t[2]) / 3.0 - cover.position).norm();
      if (distance < best_distance) {
        best_distance = distance;
        best = e;
      }
    }
    cover.extension_element = best; // (-1: none left; its elements alone hold it)
  }
}

std::vector<char> Model::excavated_blocks() const {
  std::vector<char> left(blocks.size(), 0);
  for (const ModelElement& element : elements) {
    if (!element.excavated)
      left[at(element.block)] = 1;
  }
  for (char& b : left)
    b = b == 0 ? 1 : 0;
  return left;
}

std::vector<LinearConstraint> Model::excavated_cover_relations() const {
  std::vector<LinearConstraint> relations;
  // (every step: nothing allocated while nothing is excavated)
  if (std::none_of(elements.begin(), elements.end(),
                   [](const ModelElement& e) { return e.excavated; }))
    return relations;
  std::vector<char> active(covers.size(), 0);
  for (const ModelElement& e : elements) {
    if (!e.excavated) {
      for (const int c : e.covers)
        active[at(c)] = 1;
    }
  }
  for (std::size_t c = 0; c < covers.size(); ++c) {
    if (active[c] != 0)
      continue;
    for (int k = 0; k < covers[c].n_dofs; ++k) {
      const int dof = covers[c].first_dof + k;
      relations.push_back({{{dof, 1.0}}, 0.0, dof, "a cover of excavated material"});
    }
  }
  return relations;
}

} // namespace nmm
