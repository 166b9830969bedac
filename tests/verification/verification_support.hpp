// SPDX-License-Identifier: MIT
// tests/verification/verification_support.hpp — small builders shared by the verification
// tests: rectangles, regular meshes, materials, and a model + stepper in a few lines.
#pragma once

#include "manifold/boundary_conditions.hpp"
#include "manifold/model.hpp"
#include "mesh/cover_mesher.hpp"
#include "mesh/math_mesh.hpp"
#include "mesh/physical_mesh.hpp"
#include "solver/time_stepper.hpp"

#include <string>
#include <vector>

namespace nmm::testing {

inline MaterialRegion
rectangle(const std::string& name, double x0, double y0, double x1, double y1) {
  return {name, {{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}, {}}}};
}

inline NamedCurve line(const std::string& name, Point2 a, Point2 b) { return {name, {{a, b}}}; }

inline ElasticMaterial elastic(double young, double poisson, double density, PlaneCondition plane) {
  ElasticMaterial m;
  m.name = "rock";
  m.young = young;
  m.poisson = poisson;
  m.density = density;
  m.plane = plane;
  return m;
}

/// Physical mesh + math mesh + cover system + model, ready for a stepper.
struct Setup {
  PhysicalMesh physical;
  MathMesh math;
  CoverSystem covers;
  Model model;
};

inline Setup make_setup(std::vector<MaterialRegion> regions,
                        std::vector<NamedCurve> curves,
                        std::vector<int> joints,
                        const MathMesh* math,
                        double size,
                        const ElasticMaterial& material,
                        int order) {
  Setup s;
  s.physical.source = "verification";
  s.physical.regions = std::move(regions);
  s.physical.curves = std::move(curves);
  validate_physical_mesh(s.physical);
  s.math =
      math != nullptr ? *math : make_regular_math_mesh(material_bounding_box(s.physical), size);
  s.covers = build_cover_system(s.math, s.physical, joints);
  std::vector<ElasticMaterial> materials(s.physical.regions.size(), material);
  ModelOptions options;
  options.order = order;
  s.model = make_model(s.covers, s.math, materials, options);
  return s;
}

} // namespace nmm::testing
