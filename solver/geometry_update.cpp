// SPDX-License-Identifier: MIT
#include "solver/geometry_update.hpp"

#include "manifold/boundary_conditions.hpp"

#include <vector>

namespace nmm {

void update_geometry(
    Model& model, Scene& scene, Eigen::VectorXd& raw, Eigen::VectorXd& velocity, double time) {
  model.turn_exactly(raw, velocity);
  // One list of every point, moved together.
  std::vector<MaterialPoint> points;
  for (const SupportPoint& s : scene.supports)
    points.push_back(s.point);
  for (const PointLoad& l : scene.point_loads)
    points.push_back(l.point);
  for (const MaterialPoint& p : scene.monitors)
    points.push_back(p);
  model.move(raw, points);
  std::size_t k = 0;
  for (SupportPoint& s : scene.supports)
    s.point = points[k++];
  hold_supported_points(scene.supports, time);
  for (PointLoad& l : scene.point_loads)
    l.point = points[k++];
  for (MaterialPoint& p : scene.monitors)
    p = points[k++];
}

} // namespace nmm
