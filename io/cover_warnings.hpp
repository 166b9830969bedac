// SPDX-License-Identifier: MIT
// io/cover_warnings.hpp — the cover mesher's warnings in the case's terms: where a block too
// small for the cover mesh is, what cuts it and which change of the case resolves it.
#pragma once

#include "io/case_runner.hpp"

#include <string>
#include <vector>

namespace nmm {

/// The geometry's and the cover mesher's warnings for @p spec, each starting with the
/// geometry's file name: the physical mesh's (a curve sampled coarser than the cover mesh),
/// the mesher's own (a joint that cuts nothing, a joint ending inside a block region), then one per
/// CoverSystem::tiny_blocks entry (tiny_block_warning()). `nmm run`, `check` and `mesh` list
/// these.
[[nodiscard]] std::vector<std::string> cover_system_warnings(const CaseSpec& spec,
                                                             const CaseGeometry& geometry);

/// The warning for a block too small for the cover mesh: its material, area and place (centre
/// and extent of its bounding box), the Physical Curves along it (joints named as joints), and
/// the fixes that fit: trimming the joints that cut it off, when joints do; a global
/// `[cover_mesh] size` that resolves it, only when the triangles it needs stay within
/// `max_triangles` (and the cover mesh is not the file's own .msh), else a cover mesh made
/// finer around the block alone (a gmsh `.msh` graded there, `kind = "gmsh"`).
[[nodiscard]] std::string
tiny_block_warning(const CaseSpec& spec, const CaseGeometry& geometry, const TinyBlock& tiny);

/// About how many triangles a regular math mesh of edge @p size m needs for the material of
/// @p physical (its area over a triangle's; gmsh's triangles are a little smaller).
[[nodiscard]] long long triangles_at_size(const PhysicalMesh& physical, double size);

/// The largest cover size, m, at which a piece of material of @p area m², @p length m long,
/// has covers of at least @p min_cover_area_ratio of their star (six triangles of that size):
/// the piece inside one star when it fits in one, else a strip of width area / length across
/// stars. An estimate, for the advice of tiny_block_warning().
[[nodiscard]] double resolving_cover_size(double area, double length, double min_cover_area_ratio);

} // namespace nmm
