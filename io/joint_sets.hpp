// SPDX-License-Identifier: MIT
// io/joint_sets.hpp — the joints of the case's `[[joint_set]]` tables put into the physical
// mesh, where the cover mesher takes them exactly like drawn Physical Curves.
#pragma once

#include "io/case_file.hpp"
#include "mesh/physical_mesh.hpp"

namespace nmm {

/// Generates the joints of every `[[joint_set]]` of @p spec (generate_joint_sets()) in
/// @p physical and appends them, one two-point polyline each, to the Physical Curve named
/// after the set's `joint` (made when the geometry has none), so that `[joints.NAME]` gives
/// them their properties and `nmm mesh` and `nmm run` cut the material by them. Notes on
/// joints snapped or dropped go to PhysicalMesh::warnings. Does nothing without joint sets.
/// @throws InputError naming the case file and the table's line when `region` is no Physical
///         Surface of the geometry, or a set exceeds its max_joints or max_blocks.
void add_joint_sets(const CaseSpec& spec, PhysicalMesh& physical);

} // namespace nmm
