// SPDX-License-Identifier: MIT
// io/fos_table.hpp — reads the `[fos]` table of a case file (io/fos_spec.hpp) with the
// case-table reader. Internal to io/ (io/case_file.cpp calls it).
#pragma once

#include "io/case_table.hpp"
#include "io/fos_spec.hpp"

#include <string_view>

namespace nmm {

/// The keys `[fos]` accepts (the case file's schema).
inline constexpr std::string_view fos_keys[] = {"steps",   "decay",     "rest",
                                                "bracket", "tolerance", "time_step"};

/// The `[fos]` table of @p root, every default applied; the defaults when it has none.
/// @throws InputError "file:line:column: [fos] KEY ...; what to do" for a value out of range.
[[nodiscard]] FosSpec read_fos_table(case_table::Context& context, const toml::table& root);

} // namespace nmm
