// SPDX-License-Identifier: MIT
#include "io/bolt_table.hpp"

#include "io/text.hpp"

#include <cmath>
#include <optional>
#include <string>

namespace nmm::case_table {
namespace {

constexpr std::string_view bolt_kinds[] = {"end_anchored", "grouted"};

/// Where the bolt lies: `from` and `to`, or `curve`.
void read_place(const TableView& view, BoltSpec& bolt) {
  bolt.from = view.vector<2>("from", "m", "[2.0, 3.0]");
  bolt.to = view.vector<2>("to", "m", "[6.0, 3.0]");
  const std::optional<std::string> curve = view.name_string("curve", "Physical Curve");
  if (curve && (bolt.from || bolt.to))
    view.fail_at_key("curve", "[[bolt]] curve cannot be given with " +
                                  std::string(bolt.from ? "from" : "to") +
                                  ": the bolt runs either from `from` to `to` or along the "
                                  "curve (from its first point to its last); remove one");
  if (curve) {
    bolt.curve = *curve;
    return;
  }
  if (!bolt.from)
    view.fail_missing("from",
                      "the bolt's first end [x, y] in m, with `to`; or give curve = "
                      "\"NAME\", a Physical Curve along the bolt",
                      "[2.0, 3.0]");
  if (!bolt.to)
    view.fail_missing("to", "the bolt's second end [x, y] in m", "[6.0, 3.0]");
  if (*bolt.from == *bolt.to)
    view.fail_at_value("to", "[[bolt]] to = " + point_text(*bolt.to) +
                                 " is its `from`: a bolt needs two different ends");
}

/// `stiffness`, or `young` and `area`.
void read_rigidity(const TableView& view, BoltSpec& bolt) {
  bolt.stiffness = view.number("stiffness", "N/m", "2.0e8");
  const std::optional<double> young = view.number("young", "Pa", "2.0e11");
  const std::optional<double> area = view.number("area", "m^2", "4.9e-4");
  if (bolt.stiffness) {
    if (young || area)
      view.fail_at_key(young ? "young" : "area",
                       "[[bolt]] " + std::string(young ? "young" : "area") +
                           " cannot be given with stiffness: give the axial stiffness (N/m), or "
                           "young (Pa) and area (m^2) for EA / length; remove one");
    if (!(*bolt.stiffness > 0.0))
      view.fail_range("stiffness", *bolt.stiffness,
                      "the axial stiffness must be > 0 (N/m per metre of thickness)");
    return;
  }
  if (!young && !area)
    view.fail_missing("stiffness",
                      "the axial stiffness in N/m; or young (Pa) and area (m^2) of the bar",
                      "2.0e8");
  if (!young)
    view.fail_missing("young", "Young's modulus of the bar in Pa, with area", "2.0e11");
  if (!area)
    view.fail_missing("area", "the bar's cross-section in m^2, with young", "4.9e-4");
  if (!(*young > 0.0))
    view.fail_range("young", *young, "Young's modulus of the bar must be > 0 (Pa)");
  if (!(*area > 0.0))
    view.fail_range("area", *area, "the cross-section must be > 0 (m^2 per metre of thickness)");
  bolt.young = *young;
  bolt.area = *area;
}

/// pretension, yield_force, rupture_force, hardening.
void read_strength(Context& context, const TableView& view, BoltSpec& bolt) {
  for (const auto& [key, value] : {std::pair{"yield_force", &bolt.yield_force},
                                   std::pair{"rupture_force", &bolt.rupture_force}}) {
    if (const std::optional<double> force = view.number(key, "N", "1.5e5")) {
      if (!(*force > 0.0))
        view.fail_range(key, *force, "the force must be > 0 (N per metre of thickness)");
      *value = *force;
    }
  }
  bolt.pretension = view.number_or("pretension", 0.0, "N", "5.0e4");
  const double limit = std::min(bolt.yield_force, bolt.rupture_force);
  if (!(std::abs(bolt.pretension) < limit))
    view.fail_range("pretension", bolt.pretension,
                    "|pretension| must be below the yield and rupture forces (" +
                        format_number(limit) + " N)");
  bolt.hardening = view.number_or("hardening", 0.0, "yielding over elastic stiffness", "0.02");
  if (!(bolt.hardening >= 0.0 && bolt.hardening < 1.0))
    view.fail_range("hardening", bolt.hardening,
                    "it is the stiffness of a yielding bolt over its elastic stiffness, in [0, 1)");
  if (view.has("hardening") && !view.has("yield_force"))
    context.warn(view.key_position("hardening").line,
                 "[[bolt]] hardening has no effect without yield_force: the bolt stays elastic");
  if (bolt.hardening == 0.0 && bolt.yield_force < bolt.rupture_force &&
      std::isfinite(bolt.rupture_force))
    context.warn(view.key_position("rupture_force").line,
                 "[[bolt]] rupture_force " + format_number(bolt.rupture_force) +
                     " N is above yield_force " + format_number(bolt.yield_force) +
                     " N and the bolt has no hardening, so it yields at its yield force and "
                     "never breaks; give hardening (e.g. 0.02) for a bolt that hardens to its "
                     "rupture force, or rupture_force <= yield_force for a brittle one");
}

} // namespace

BoltSpec read_bolt_table(Context& context, const toml::table& table, std::size_t index) {
  const TableView view(context, table, "[[bolt]]", bolt_keys);
  BoltSpec bolt;
  bolt.line = view.position().line;
  bolt.name =
      view.string("name", "the bolt's name", "\"B1\"").value_or("bolt" + std::to_string(index + 1));
  check_column_name(view, "name", bolt.name);
  read_place(view, bolt);
  bolt.kind = static_cast<BoltKind>(view.choice("kind", bolt_kinds, 0));
  read_rigidity(view, bolt);
  read_strength(context, view, bolt);
  return bolt;
}

void check_bolt_names(Context& context, const std::vector<BoltSpec>& bolts) {
  for (std::size_t i = 0; i < bolts.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (bolts[j].name == bolts[i].name)
        context.fail({bolts[i].line, 1}, "[[bolt]] name " + in_quotes(bolts[i].name) +
                                             " is already used by the [[bolt]] at line " +
                                             std::to_string(bolts[j].line) +
                                             "; give each bolt a unique name");
    }
  }
}

std::vector<BoltSpec> read_bolt_tables(Context& context, const toml::table& root) {
  std::vector<BoltSpec> bolts;
  for (const toml::table* table : table_array(context, root, "bolt"))
    bolts.push_back(read_bolt_table(context, *table, bolts.size()));
  check_bolt_names(context, bolts);
  return bolts;
}

} // namespace nmm::case_table
