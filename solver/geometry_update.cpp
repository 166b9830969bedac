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
  for (const Bolt& bolt : scene.bolts) {
    for (const BoltBar& bar : bolt.bars) {
      points.push_back(bar.a);
      points.push_back(bar.b);
    }
  }
  model.move(raw, points);
  std::size_t k = 0;
  for (SupportPoint& s : scene.supports)
    s.point = points[k++];
  hold_supported_points(scene.supports, time);
  for (PointLoad& l : scene.point_loads)
    l.point = points[k++];
  for (MaterialPoint& p : scene.monitors)
    p = points[k++];
  for (Bolt& bolt : scene.bolts) {
    for (BoltBar& bar : bolt.bars) {
      bar.a = points[k++];
      bar.b = points[k++];
    }
  }
}

} // namespace nmm
