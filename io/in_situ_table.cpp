// SPDX-License-Identifier: MIT
#include "io/in_situ_table.hpp"

#include "io/text.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

namespace nmm::case_table {
namespace {

constexpr std::array<std::string_view, 3> component_keys{"sxx", "syy", "sxy"};
constexpr std::array<std::string_view, 3> gradient_keys{"sxx_gradient", "syy_gradient",
                                                        "sxy_gradient"};

/// The first key of the components form the table has, or an empty view.
std::string_view first_component(const TableView& view) {
  for (const auto& keys : {component_keys, gradient_keys}) {
    for (const std::string_view key : keys) {
      if (view.has(key))
        return key;
    }
  }
  return {};
}

/// Reads the stress form: k0 (with unit_weight) or the components with their gradients.
void read_form(const TableView& view, InSituSpec& in_situ) {
  in_situ.k0 = view.number("k0", "horizontal over vertical stress", "0.5");
  in_situ.unit_weight = view.number("unit_weight", "N/m^3", "25000.0");
  const std::string_view component = first_component(view);
  if (in_situ.k0) {
    if (!component.empty())
      view.fail_at_key(component,
                       view.subject(component) +
                           " cannot be given with k0: k0 makes syy = -unit_weight x depth, sxx "
                           "= k0 syy and sxy = 0; remove " +
                           std::string(component) +
                           ", or remove k0 and give sxx, syy, sxy at the surface with "
                           "sxx_gradient, syy_gradient, sxy_gradient (Pa per m of depth)");
    if (!(*in_situ.k0 >= 0.0))
      view.fail_range("k0", *in_situ.k0,
                      "k0 is the horizontal over the vertical stress, >= 0 (e.g. 0.5)");
  } else {
    if (in_situ.unit_weight)
      view.fail_at_key("unit_weight",
                       "[in_situ] unit_weight is used only with k0 (syy = -unit_weight x "
                       "depth); with sxx, syy, sxy give syy_gradient = -unit_weight instead, "
                       "or add k0");
    if (component.empty())
      view.fail_at_key("k0", // (absent: the table's header)
                       "[in_situ] gives no stress; add k0 = 0.5 (syy = -unit_weight x depth "
                       "below the surface, sxx = k0 syy), or sxx, syy, sxy at the surface (Pa) "
                       "with sxx_gradient, syy_gradient, sxy_gradient (Pa per m of depth)");
    for (std::size_t i = 0; i < 3; ++i) {
      in_situ.stress(static_cast<Eigen::Index>(i)) =
          view.number_or(component_keys[i], 0.0, "Pa, tension positive", "-1.0e6");
      in_situ.gradient(static_cast<Eigen::Index>(i)) =
          view.number_or(gradient_keys[i], 0.0, "Pa per m of depth, tension positive", "-25000.0");
    }
  }
  if (in_situ.unit_weight && !(*in_situ.unit_weight > 0.0))
    view.fail_range("unit_weight", *in_situ.unit_weight,
                    "it must be > 0 (N/m^3): the weight of a cubic metre of the rock, e.g. "
                    "2600 x 9.81 = 25506");
}

/// The sum of the gravity loads and the first one's line (0: none).
std::pair<Eigen::Vector2d, const LoadSpec*> gravity_of(const CaseSpec& spec) {
  Eigen::Vector2d gravity = Eigen::Vector2d::Zero();
  const LoadSpec* first = nullptr;
  for (const LoadSpec& load : spec.loads) {
    if (load.kind != LoadKind::gravity)
      continue;
    gravity += load.vector;
    if (first == nullptr)
      first = &load;
  }
  return {gravity, first};
}

/// Remarks on a field that is not in equilibrium with the case's gravity from the start.
void warn_about_gravity(Context& context, const CaseSpec& spec, const InSituSpec& in_situ) {
  const auto [gravity, first] = gravity_of(spec);
  if (first == nullptr)
    return;
  const double g = gravity.norm();
  if (std::abs(gravity.x()) > 1e-6 * g || gravity.y() > 0.0)
    context.warn(first->line, "[in_situ] grows with depth along -y, but the gravity [[load]] "
                              "points along " +
                                  point_text(gravity, 4) +
                                  ": the field is not in equilibrium with it; turn the model "
                                  "so that gravity is [0, -g]");
  for (const LoadSpec& load : spec.loads) {
    if (load.kind == LoadKind::gravity && load.ramp_end > 0.0)
      context.warn(load.line, "[in_situ] is in equilibrium with the full gravity from the first "
                              "step, but this gravity [[load]] is ramped: the rock rises "
                              "until the ramp ends; remove the ramp");
  }
  if (in_situ.k0 && !in_situ.unit_weight) {
    const auto other =
        std::find_if(spec.materials.begin(), spec.materials.end(), [&](const MaterialSpec& m) {
          return m.density != spec.materials.front().density;
        });
    if (other != spec.materials.end())
      context.warn(in_situ.line,
                   "[in_situ] without unit_weight gives each material its own density x |g| "
                   "(materials " +
                       in_quotes(spec.materials.front().name) + " and " + in_quotes(other->name) +
                       " differ): the field is in equilibrium within each material, not across "
                       "their interfaces; give unit_weight for one field over all");
  }
}

} // namespace

void read_in_situ(Context& context, const toml::table& root, CaseSpec& spec) {
  const toml::table* table = single_table(context, root, "in_situ");
  if (table == nullptr)
    return;
  const TableView view(context, *table, "[in_situ]", in_situ_keys);
  InSituSpec in_situ;
  in_situ.line = view.position().line;
  read_form(view, in_situ);
  const std::optional<double> surface =
      view.number("surface", "m, the y coordinate of the ground surface", "20.0");
  if (!surface && (in_situ.k0 || !in_situ.gradient.isZero()))
    view.fail_missing("surface",
                      "the y coordinate of the ground surface, from which the depth is counted",
                      "20.0");
  in_situ.surface = surface.value_or(0.0);
  const Eigen::Vector2d gravity = gravity_of(spec).first;
  if (in_situ.k0 && !in_situ.unit_weight && gravity.norm() == 0.0)
    view.fail_at_key("k0", "[in_situ] k0 needs the rock's unit weight, and the case has no "
                           "gravity [[load]] to take it from (density x |g|); add unit_weight = "
                           "25000.0 (N/m^3) to [in_situ], or a [[load]] with gravity = "
                           "[0.0, -9.81]");
  for (const MaterialSpec& m : spec.materials) {
    if (!m.initial_stress.isZero())
      view.fail_at_key(view.has("k0") ? "k0" : first_component(view),
                       "[materials." + m.name + "] initial_stress (line " + std::to_string(m.line) +
                           ") and [in_situ] both give the initial stress, and [in_situ] "
                           "applies to every material; remove one of them");
  }
  for (MaterialSpec& m : spec.materials) {
    if (in_situ.k0) {
      const double gamma = in_situ.unit_weight.value_or(m.density * gravity.norm());
      m.initial_stress = Eigen::Vector3d::Zero();
      m.initial_stress_gradient = Eigen::Vector3d(-*in_situ.k0 * gamma, -gamma, 0.0);
    } else {
      m.initial_stress = in_situ.stress;
      m.initial_stress_gradient = in_situ.gradient;
    }
    m.initial_stress_surface = in_situ.surface;
  }
  warn_about_gravity(context, spec, in_situ);
  spec.in_situ = in_situ;
}

} // namespace nmm::case_table
