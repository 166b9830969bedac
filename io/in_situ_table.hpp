// SPDX-License-Identifier: MIT
// io/in_situ_table.hpp — the case file's `[in_situ]` table: an initial stress growing with
// depth below a ground surface, in equilibrium with gravity (docs/case-file.md, "[in_situ]").
// Internal to io/ (read by io/case_file.cpp).
#pragma once

#include "io/case_file.hpp"
#include "io/case_table.hpp"

#include <toml++/toml.h>

#include <string_view>

namespace nmm::case_table {

/// The keys `[in_situ]` accepts (the schema of io/case_file.cpp).
inline constexpr std::string_view in_situ_keys[] = {"surface",      "unit_weight",  "k0",
                                                    "sxx",          "syy",          "sxy",
                                                    "sxx_gradient", "syy_gradient", "sxy_gradient"};

/// Reads `[in_situ]`, when the case file has one, into spec.in_situ and gives every material
/// its field (MaterialSpec::initial_stress at the surface, initial_stress_gradient,
/// initial_stress_surface). Call after the materials and loads are read and checked.
/// @throws InputError naming the file, line and key: k0 with components, unit_weight
///         without k0, no stress, a missing surface, k0 without a unit weight or gravity, a
///         material with an initial_stress of its own, out-of-range values.
void read_in_situ(Context& context, const toml::table& root, CaseSpec& spec);

} // namespace nmm::case_table
