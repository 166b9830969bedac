// SPDX-License-Identifier: MIT
// Queries of gmsh's current model: physical groups, entities, mesh elements and nodes.
#include "io/gmsh_internal.hpp"
#include "mesh/error.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cstddef>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace nmm::detail {

namespace {

std::string group_names(const std::vector<PhysicalGroup>& groups) {
  std::string text;
  for (const PhysicalGroup& group : groups)
    text += (text.empty() ? "\"" : ", \"") + group.name + '"';
  return text;
}

} // namespace

std::string tag_list(const std::vector<int>& tags) {
  std::string text;
  const std::size_t shown = std::min<std::size_t>(tags.size(), 12);
  for (std::size_t i = 0; i < shown; ++i)
    text += (i > 0 ? ", " : "") + std::to_string(tags[i]);
  if (shown < tags.size())
    text += ", ... (" + std::to_string(tags.size()) + " in all)";
  return text;
}

std::vector<PhysicalGroup> physical_groups(int dim, const std::string& unnamed_prefix) {
  gmsh::vectorpair dim_tags;
  gmsh::model::getPhysicalGroups(dim_tags, dim);
  std::vector<PhysicalGroup> groups;
  for (const auto& [group_dim, tag] : dim_tags) {
    PhysicalGroup group;
    group.tag = tag;
    gmsh::model::getPhysicalName(group_dim, tag, group.name);
    if (group.name.empty())
      group.name = unnamed_prefix + "_" + std::to_string(tag);
    gmsh::model::getEntitiesForPhysicalGroup(group_dim, tag, group.entities);
    groups.push_back(std::move(group));
  }
  return groups;
}

std::set<int> entity_tags(int dim) {
  gmsh::vectorpair dim_tags;
  gmsh::model::getEntities(dim_tags, dim);
  std::set<int> tags;
  for (const auto& dim_tag : dim_tags)
    tags.insert(dim_tag.second);
  return tags;
}

void throw_no_physical_surface(const std::string& file) {
  const std::set<int> surfaces = entity_tags(2);
  std::string message = file + ": the geometry has no Physical Surface, so nmm sees no material";
  if (surfaces.empty()) {
    message += " (it has no surface at all); define surfaces (Plane Surface from a Curve Loop, "
               "or Rectangle/Disk with OpenCASCADE) and name them with Physical Surface(\"rock\")"
               " = {...}";
  } else {
    const std::vector<int> tags(surfaces.begin(), surfaces.end());
    message += "; it has surface(s) " + tag_list(tags) +
               ": name each material with a line like Physical Surface(\"rock\") = {" +
               tag_list(tags) + "}; (the name is the material name in the case file)";
  }
  const std::string curves = group_names(physical_groups(1, "curve"));
  if (!curves.empty())
    message += ". Physical Curves found: " + curves;
  throw InputError(message);
}

std::vector<std::vector<std::size_t>> element_corners(int dim, int tag) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags;
  std::vector<std::vector<std::size_t>> node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, tag);
  std::vector<std::vector<std::size_t>> corners;
  for (std::size_t k = 0; k < types.size(); ++k) {
    std::string name;
    int element_dim = 0;
    int order = 0;
    int n_nodes = 0;
    int n_primary = 0;
    std::vector<double> local_coordinates;
    gmsh::model::mesh::getElementProperties(types[k], name, element_dim, order, n_nodes,
                                            local_coordinates, n_primary);
    if (element_dim != dim || n_nodes <= 0)
      continue;
    const auto stride = static_cast<std::size_t>(n_nodes);
    for (std::size_t first = 0; first + stride <= node_tags[k].size(); first += stride) {
      const auto begin = node_tags[k].begin() + static_cast<std::ptrdiff_t>(first);
      corners.emplace_back(begin, begin + n_primary);
    }
  }
  return corners;
}

const Point3& NodeTable::at(std::size_t tag) {
  if (!loaded_)
    load();
  const auto found = coordinates_.find(tag);
  if (found == coordinates_.end())
    throw InputError("gmsh mesh: element refers to node " + std::to_string(tag) +
                     ", which the file does not define; save the .msh again from gmsh");
  return found->second;
}

void NodeTable::load() {
  std::vector<std::size_t> tags;
  std::vector<double> coordinates;
  std::vector<double> parametric;
  gmsh::model::mesh::getNodes(tags, coordinates, parametric, -1, -1, false, false);
  coordinates_.reserve(tags.size());
  for (std::size_t i = 0; i < tags.size(); ++i)
    coordinates_[tags[i]] =
        Point3(coordinates[3 * i], coordinates[3 * i + 1], coordinates[3 * i + 2]);
  loaded_ = true;
}

} // namespace nmm::detail
