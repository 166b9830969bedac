// SPDX-License-Identifier: MIT
#include "manifold/regular_shapes.hpp"

#include "mesh/error.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace nmm {
namespace {

// Faces of a convex solid from its vertices and one outward direction per face: the
// vertices furthest along the direction, ordered counter-clockwise about it.
Polyhedron convex_solid(std::vector<Point3> vertices, const std::vector<Point3>& normals) {
  Polyhedron solid;
  for (const Point3& normal_raw : normals) {
    const Point3 normal = normal_raw.normalized();
    double top = -1e300;
    for (const Point3& v : vertices)
      top = std::max(top, v.dot(normal));
    std::vector<int> face;
    Point3 center = Point3::Zero();
    for (int k = 0; k < static_cast<int>(vertices.size()); ++k) {
      if (vertices[k].dot(normal) > top - 1e-9) {
        face.push_back(k);
        center += vertices[k];
      }
    }
    center /= static_cast<double>(face.size());
    const Point3 u = (vertices[face[0]] - center).normalized();
    const Point3 w = normal.cross(u);
    auto angle = [&](int k) {
      const Point3 r = vertices[k] - center;
      return std::atan2(r.dot(w), r.dot(u));
    };
    std::sort(face.begin(), face.end(), [&](int i, int j) { return angle(i) < angle(j); });
    solid.faces.push_back(std::move(face));
  }
  solid.vertices = std::move(vertices);
  return solid;
}

} // namespace

Loop regular_polygon(int n_vertices) {
  NMM_ASSERT(n_vertices >= 3, "a polygon needs at least 3 vertices");
  Loop loop;
  loop.reserve(static_cast<std::size_t>(n_vertices));
  for (int i = 1; i <= n_vertices; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n_vertices;
    loop.emplace_back(std::sin(angle), std::cos(angle));
  }
  return loop;
}

Polyhedron regular_solid(RegularSolid kind) {
  const double s3 = 1.0 / std::sqrt(3.0);
  switch (kind) {
  case RegularSolid::tetrahedron: {
    // Alternate corners of the cube (±1,±1,±1)/√3; each face is opposite a vertex.
    std::vector<Point3> v{{s3, s3, s3}, {s3, -s3, -s3}, {-s3, s3, -s3}, {-s3, -s3, s3}};
    std::vector<Point3> normals;
    for (const Point3& p : v)
      normals.push_back(-p);
    return convex_solid(v, normals);
  }
  case RegularSolid::cube: {
    std::vector<Point3> v;
    for (int i = 0; i < 8; ++i) {
      v.emplace_back((i & 1) ? s3 : -s3, (i & 2) ? s3 : -s3, (i & 4) ? s3 : -s3);
    }
    return convex_solid(v, {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}});
  }
  case RegularSolid::dodecahedron: {
    // (±1,±1,±1), (0,±1/φ,±φ) and cyclic permutations, circumradius √3; the face
    // directions are the icosahedron's vertices (0,±φ,±1), (±φ,±1,0), (±1,0,±φ).
    const double phi = std::numbers::phi;
    std::vector<Point3> v;
    for (int i = 0; i < 8; ++i) {
      v.emplace_back((i & 1) ? 1.0 : -1.0, (i & 2) ? 1.0 : -1.0, (i & 4) ? 1.0 : -1.0);
    }
    std::vector<Point3> normals;
    for (int i = 0; i < 4; ++i) {
      const double a = (i & 1) ? 1.0 : -1.0;
      const double b = (i & 2) ? 1.0 : -1.0;
      v.emplace_back(0.0, a / phi, b * phi);
      v.emplace_back(a / phi, b * phi, 0.0);
      v.emplace_back(b * phi, 0.0, a / phi);
      normals.emplace_back(0.0, a * phi, b);
      normals.emplace_back(a * phi, b, 0.0);
      normals.emplace_back(b, 0.0, a * phi);
    }
    for (Point3& p : v)
      p *= s3;
    return convex_solid(v, normals);
  }
  }
  NMM_ASSERT(false, "unknown regular solid");
  return {};
}

} // namespace nmm
