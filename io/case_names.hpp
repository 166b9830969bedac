// SPDX-License-Identifier: MIT
// io/case_names.hpp — the names of a case (materials, curves, points, regions) resolved
// against its geometry, with the messages that name the case file's line and what to do.
// Internal to io/ (io/case_runner.cpp, io/case_stages.cpp).
#pragma once

#include "io/case_file.hpp"
#include "io/text.hpp"
#include "manifold/model.hpp"
#include "mesh/physical_mesh.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace nmm::case_names {

/// @throws InputError "case.toml:LINE: message".
[[noreturn]] void fail(const CaseSpec& spec, int line, const std::string& message);

/// The geometry file's name, for messages.
[[nodiscard]] std::string geometry_name(const CaseSpec& spec);

/// " (did you mean \"NAME\"?)" for the item of @p items closest to @p name, or "".
template <class Items> std::string did_you_mean(const std::string& name, const Items& items) {
  std::vector<std::string_view> names;
  for (const auto& item : items)
    names.emplace_back(item.name);
  const std::string_view best = closest(name, names);
  return best.empty() ? std::string() : " (did you mean " + in_quotes(best) + "?)";
}

/// "a Physical Surface" / "a Physical Curve" / "a Physical Point" when @p name is a group of
/// that kind, else empty.
[[nodiscard]] std::string group_kind(const PhysicalMesh& physical, const std::string& name);

/// The message for a name of the case that is not a group of the wanted kind.
/// @param what    how the case file refers to it: `material "granit"`, `[[boundary]] curve "x"`
/// @param wanted  "Physical Surface", "Physical Curve" or "Physical Point"
/// @param remedy  what to do when the name exists as another kind, e.g. `write point = "x"`
template <class Items>
std::string unknown_name(const CaseSpec& spec,
                         const PhysicalMesh& physical,
                         const std::string& what,
                         const std::string& name,
                         const std::string& wanted,
                         const Items& wanted_items,
                         const std::string& names,
                         const std::string& remedy) {
  const std::string other = group_kind(physical, name);
  if (!other.empty()) {
    return what + " is " + other + " of " + geometry_name(spec) + ", not a " + wanted + "; " +
           remedy + " (the " + wanted + "s are: " + names + ")";
  }
  return what + " is not a " + wanted + " of " + geometry_name(spec) + " (it has: " + names +
         "); correct the name in the case file" + did_you_mean(name, wanted_items) + ", or add " +
         wanted + "(" + in_quotes(name) + ") = {...}; to " + geometry_name(spec);
}

/// The curve a `[[boundary]]` or `[[load]]` names (@p entry, at @p line), checked to touch
/// the material. @throws InputError naming the line and what to do.
[[nodiscard]] int resolve_curve(const CaseSpec& spec,
                                const PhysicalMesh& physical,
                                const Model& model,
                                const std::string& entry,
                                const std::string& name,
                                int line);

/// The point group a `[[boundary]]` or `[[load]]` names. @throws InputError as above.
[[nodiscard]] int resolve_point_group(const CaseSpec& spec,
                                      const PhysicalMesh& physical,
                                      const std::string& entry,
                                      const std::string& name,
                                      int line);

} // namespace nmm::case_names
