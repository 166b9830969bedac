// SPDX-License-Identifier: MIT
// solver/geometry_update.hpp — the geometry moves with the material at the end of a step:
// covers, element polygons and the scene's material points (DESIGN.md, "Data flow").
#pragma once

#include "manifold/model.hpp"
#include "solver/time_stepper.hpp"

#include <Eigen/Core>

namespace nmm {

/// Moves @p model by the step displacement @p raw: the NMM and VEM blocks with exact_rotation
/// turned exactly first (Model::turn_exactly(), which corrects @p raw and @p velocity), then
/// the covers and element polygons, and with them the supports', point loads' and monitors'
/// material points of @p scene; the held components of exact supports then go where their
/// supports hold them at @p time, the step's end (hold_supported_points()). Call after the
/// stresses took the step's strain.
void update_geometry(
    Model& model, Scene& scene, Eigen::VectorXd& raw, Eigen::VectorXd& velocity, double time);

} // namespace nmm
