// SPDX-License-Identifier: MIT
// io/scene_bolts.hpp — the case's `[[bolt]]` tables placed in the model: their bars between
// the elements of their ends (make_bolt_bars()), every end checked against the material and
// the blocks (docs/case-file.md, "[[bolt]]"). Internal to io/.
#pragma once

#include "io/case_file.hpp"
#include "manifold/bolt.hpp"
#include "manifold/model.hpp"
#include "mesh/physical_mesh.hpp"

#include <vector>

namespace nmm {

/// The bolts of @p spec in @p model, whose geometry is @p physical: one per `[[bolt]]` with
/// from and to, one per gmsh curve of a `curve` (NAME_1, NAME_2... when it has several).
/// @param tolerance  how far outside the material an end may lie (m): on its boundary.
/// @param stage      only the bolts installed with this stage (BoltSpec::stage).
/// @throws InputError naming the case file, the `[[bolt]]` line and the bolt: an end outside
///         the material, both ends in one block, a curve that is no Physical Curve or is not
///         straight.
[[nodiscard]] std::vector<Bolt> place_bolts(const CaseSpec& spec,
                                            const PhysicalMesh& physical,
                                            const Model& model,
                                            double tolerance,
                                            int stage = 0);

} // namespace nmm
