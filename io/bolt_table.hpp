// SPDX-License-Identifier: MIT
// io/bolt_table.hpp — the case file's `[[bolt]]` tables: rock bolts between two points or
// along a Physical Curve (docs/case-file.md, "[[bolt]]"). Internal to io/ (read by
// io/case_file.cpp; io/scene_bolts.cpp places them in the model).
#pragma once

#include "io/case_file.hpp"
#include "io/case_table.hpp"

#include <toml++/toml.h>

#include <string_view>
#include <vector>

namespace nmm::case_table {

/// The keys `[[bolt]]` accepts (the schema of io/case_file.cpp).
inline constexpr std::string_view bolt_keys[] = {
    "name",  "from", "to",         "curve",       "kind",          "stiffness",
    "young", "area", "pretension", "yield_force", "rupture_force", "hardening"};

/// Reads one `[[bolt]]` table (or `[[stage.bolt]]`), the @p index th of the case (its
/// default name "bolt" + (index + 1)). @throws InputError as read_bolt_tables().
[[nodiscard]] BoltSpec
read_bolt_table(Context& context, const toml::table& table, std::size_t index);

/// Refuses two bolts of @p bolts with one name, at the line of the second.
void check_bolt_names(Context& context, const std::vector<BoltSpec>& bolts);

/// Reads every `[[bolt]]` table, in the order of the file.
/// @throws InputError naming the file, line and key: both or neither of from/to and curve,
///         both or neither of stiffness and young/area, values out of range, a pretension
///         at or beyond the yield or rupture force, a name used twice or not of letters,
///         digits and _.
[[nodiscard]] std::vector<BoltSpec> read_bolt_tables(Context& context, const toml::table& root);

} // namespace nmm::case_table
