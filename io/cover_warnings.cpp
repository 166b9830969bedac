// SPDX-License-Identifier: MIT
#include "io/cover_warnings.hpp"

#include "io/text.hpp"
#include "mesh/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace nmm {

namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// Area of a regular math mesh's triangle of edge @p size, m² (the estimate of the reader).
double triangle_area(double size) { return std::sqrt(3.0) / 4.0 * size * size; }

/// @p value rounded down to one significant digit (0.069 -> 0.06): a size to type.
double round_down(double value) {
  const double unit = std::pow(10.0, std::floor(std::log10(value)));
  return std::floor(value / unit + 1e-9) * unit;
}

/// "joint "cut" and curve "base"": the Physical Curves with a piece along @p block.
std::string
curves_along(const CaseGeometry& geometry, int block, std::vector<std::string>& joints) {
  std::vector<std::string> names;
  for (std::size_t c = 0; c < geometry.covers.curve_pieces.size(); ++c) {
    const auto& pieces = geometry.covers.curve_pieces[c];
    if (std::none_of(pieces.begin(), pieces.end(), [&](const CurvePiece& p) {
          return p.left_block == block || p.right_block == block;
        }))
      continue;
    const std::string& name = geometry.physical.curves[c].name;
    const bool is_joint = std::find(geometry.joint_curves.begin(), geometry.joint_curves.end(),
                                    static_cast<int>(c)) != geometry.joint_curves.end();
    if (is_joint)
      joints.push_back(name);
    names.push_back((is_joint ? "joint " : "curve ") + in_quotes(name));
  }
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k)
    text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return text;
}

} // namespace

long long triangles_at_size(const PhysicalMesh& physical, double size) {
  return std::llround(material_area(physical) / triangle_area(size));
}

double resolving_cover_size(double area, double length, double min_cover_area_ratio) {
  if (!(min_cover_area_ratio > 0.0) || !(area > 0.0))
    return std::numeric_limits<double>::infinity();
  // A node's star: six triangles of the size, 6 sqrt(3)/4 h².
  const double star = 6.0 * triangle_area(1.0) * min_cover_area_ratio;
  const double whole = std::sqrt(area / star);
  if (whole >= length)
    return whole;
  // A strip of width w across stars: a cover holds about w 2h of it.
  const double width = area / length;
  return std::min(2.0 * width / star, length);
}

std::string
tiny_block_warning(const CaseSpec& spec, const CaseGeometry& geometry, const TinyBlock& tiny) {
  const CoverSystem& covers = geometry.covers;
  const Block& block = covers.blocks[at(tiny.block)];
  BoundingBox box;
  std::string material;
  for (const int e : block.elements) {
    const Element& element = covers.elements[at(e)];
    if (material.empty())
      material = geometry.physical.regions[at(element.material)].name;
    for (const Polygon& polygon : element.polygons)
      for (const Point2& p : polygon.outer)
        box.extend(p);
  }
  const double size = spec.cover_mesh.size;
  std::ostringstream out;
  out << "block " << tiny.block;
  if (!material.empty())
    out << " of " << in_quotes(material);
  out << " (" << number_text(block.area, 3) << " m²";
  // Built with streams: GCC 12 at -O3 warns falsely (-Wrestrict) on "text" + a temporary.
  std::ostringstream place;
  if (box.is_empty()) {
    place << "it";
  } else {
    const Point2 centre = 0.5 * (box.min + box.max);
    place << '(' << number_text(centre.x(), 6) << ", " << number_text(centre.y(), 6) << ')';
    out << " around " << place.str() << ": x " << number_text(box.min.x(), 6) << " to "
        << number_text(box.max.x(), 6) << " m, y " << number_text(box.min.y(), 6) << " to "
        << number_text(box.max.y(), 6) << " m";
  }
  std::vector<std::string> joints;
  const std::string along = curves_along(geometry, tiny.block, joints);
  if (!along.empty())
    out << "; along " << along;
  out << ") is too small for the cover mesh of size " << number_text(size, 4) << " m: a cover of "
      << number_text(tiny.cover_area, 3)
      << " m² has no well-posed element near it, so the block keeps its own unknowns, which "
         "may be poorly conditioned; ";

  // The fixes that fit: the joints that cut the piece off, then a finer cover mesh.
  if (!joints.empty()) {
    out << "trim joint ";
    for (std::size_t k = 0; k < joints.size(); ++k)
      out << (k == 0 ? "" : " or ") << in_quotes(joints[k]);
    out << " near " << place.str()
        << " so that it does not cut off this piece (end it on the boundary or the other "
           "joint, or short of it); or ";
  }
  const Point2 extent = box.is_empty() ? Point2(size, size) : box.size();
  const double wanted =
      round_down(0.5 * std::min(size, resolving_cover_size(block.area, extent.norm(),
                                                           spec.cover_mesh.min_cover_area_ratio)));
  const long long triangles = triangles_at_size(geometry.physical, wanted);
  const bool own_msh =
      spec.cover_mesh.kind == CoverMeshKind::gmsh && spec.geometry.extension() == ".msh";
  std::ostringstream local;
  local << "triangles of about " << number_text(wanted, 3) << " m around " << place.str()
        << " (a gmsh size field there)";
  if (own_msh) {
    out << "mesh " << spec.geometry.filename().string() << " with " << local.str();
  } else if (triangles <= spec.cover_mesh.max_triangles) {
    out << "[cover_mesh] size = " << number_text(wanted, 3) << " (about " << triangles
        << " triangles; max_triangles = " << spec.cover_mesh.max_triangles << ")";
  } else {
    out << "a cover mesh finer around the block only: [cover_mesh] kind = \"gmsh\" on a .msh "
           "geometry with "
        << local.str() << " (a [cover_mesh] size of " << number_text(wanted, 3)
        << " m everywhere would need about " << triangles
        << " triangles, more than max_triangles = " << spec.cover_mesh.max_triangles << ")";
  }
  return out.str();
}

std::vector<std::string> cover_system_warnings(const CaseSpec& spec, const CaseGeometry& geometry) {
  const std::string prefix = spec.geometry.filename().string() + ": ";
  std::vector<std::string> warnings;
  for (const std::string& w : geometry.physical.warnings)
    warnings.push_back(prefix + w);
  for (const std::string& w : geometry.covers.warnings)
    warnings.push_back(prefix + w);
  for (const TinyBlock& tiny : geometry.covers.tiny_blocks)
    warnings.push_back(prefix + tiny_block_warning(spec, geometry, tiny));
  return warnings;
}

} // namespace nmm
