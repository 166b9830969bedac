// SPDX-License-Identifier: MIT
// io/joint_set_table.hpp — the case file's `[[joint_set]]` tables (docs/case-file.md): joints
// generated from a set's angle, spacing, trace, gap and origin (UDEC's `jset`), read with the
// case_table reader. Internal to io/.
#pragma once

#include "io/case_file.hpp"
#include "io/case_table.hpp"

#include <string_view>
#include <vector>

namespace nmm {

/// The keys a `[[joint_set]]` table accepts (the case file's schema).
inline constexpr std::string_view joint_set_keys[] = {
    "joint",         "angle",  "spacing",           "trace",           "gap",
    "origin",        "region", "spacing_deviation", "angle_deviation", "trace_deviation",
    "gap_deviation", "seed",   "snap_tolerance",    "max_joints",      "max_blocks"};

/// Reads every `[[joint_set]]` of @p root; each `joint` must name one of @p joints.
/// @throws InputError "file:line:column: ..." naming the table's key for a missing or out of
///         range value (a spacing <= 0, a deviation not below its mean, a gap without a
///         trace) or a joint that is no `[joints.NAME]` of the case.
[[nodiscard]] std::vector<JointSetSpec> read_joint_set_tables(case_table::Context& context,
                                                              const toml::table& root,
                                                              const std::string& file,
                                                              const std::vector<JointSpec>& joints);

} // namespace nmm
