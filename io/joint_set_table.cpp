// SPDX-License-Identifier: MIT
// io/joint_set_table.cpp — `[[joint_set]]` tables to JointSetSpec (docs/case-file.md).
#include "io/joint_set_table.hpp"

#include "io/text.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace nmm {
namespace {

using namespace case_table;

/// An optional number that must be >= 0 and below @p limit (when it is finite).
double deviation(const TableView& view,
                 std::string_view key,
                 double limit,
                 std::string_view mean_name,
                 std::string_view unit) {
  const double value = view.number_or(key, 0.0, unit, "0.1");
  if (value < 0.0 || value >= limit)
    view.fail_range(key, value,
                    "it must be >= 0 and below " + std::string(mean_name) + " (" +
                        format_number(limit) +
                        " here): values are drawn uniformly within the mean +- the deviation");
  return value;
}

JointSetSpec read_joint_set(Context& context,
                            const toml::table& table,
                            const std::string& file,
                            const std::vector<JointSpec>& joints) {
  const TableView view(context, table, "[[joint_set]]", joint_set_keys);
  JointSetSpec spec;
  spec.line = view.position().line;
  const std::optional<std::string> joint =
      view.name_string("joint", "[joints.NAME] table whose properties the set takes");
  if (!joint)
    view.fail_missing("joint", "the [joints.NAME] whose properties the joints take", "\"cross\"");
  const bool known = std::any_of(joints.begin(), joints.end(),
                                 [&](const JointSpec& j) { return j.name == *joint; });
  if (!known) {
    std::vector<std::string_view> names;
    for (const JointSpec& j : joints)
      names.push_back(j.name);
    view.fail_at_value("joint", "[[joint_set]] joint = " + in_quotes(*joint) +
                                    " is not a [joints.NAME] table of the case; add [joints." +
                                    *joint + "] (friction_angle, ...) or use one of: " +
                                    (names.empty() ? std::string("(none)") : join(names, "\"")));
  }
  spec.joint = *joint;
  JointSetParameters& p = spec.parameters;
  const std::string subject = "[[joint_set]] (joint = " + in_quotes(*joint) + ")";
  p.where = file + ":" + std::to_string(spec.line) + ": " + subject;
  p.angle_degrees = view.required_number("angle",
                                         "the direction of the joints, degrees "
                                         "counter-clockwise from +x",
                                         "degrees", "35.0");
  p.spacing = view.required_number("spacing", "the distance between the joints, normal to them",
                                   "m", "2.0");
  if (!(p.spacing > 0.0))
    view.fail_range("spacing", p.spacing,
                    "it must be > 0 (m): the distance between neighbouring joints of the set, "
                    "measured normal to them");
  p.trace = view.number("trace", "m", "5.0");
  if (p.trace && !(*p.trace > 0.0))
    view.fail_range("trace", *p.trace,
                    "it must be > 0 (m), the length of each joint; leave trace out for "
                    "persistent joints");
  p.gap = view.number_or("gap", 0.0, "m", "1.0");
  if (p.gap < 0.0)
    view.fail_range("gap", p.gap, "it must be >= 0 (m): the rock bridge between two joints");
  if (view.has("gap") && !p.trace)
    view.fail_at_key("gap", "[[joint_set]] gap needs a trace: without trace the joints are "
                            "persistent and have no rock bridges; add trace = 5.0 (m) or "
                            "remove gap");
  // gap defaults to 0: the traces of a line touch end to end and cut like persistent joints,
  // while a user who gives a trace most likely means joints that end in rock; say so.
  if (p.trace && !view.has("gap"))
    context.warn(view.key_position("trace").line,
                 subject + " trace = " + format_number(*p.trace) +
                     " without gap: the joints of each line follow end to end with no rock "
                     "bridge between them, so they cut like persistent joints; add gap = 1.0 "
                     "(m) for rock bridges, or gap = 0.0 to keep this and silence the warning");
  p.origin = view.vector<2>("origin", "m", "[0.0, 0.0]").value_or(Point2::Zero());
  if (const std::optional<std::string> region = view.name_string("region", "Physical Surface"))
    spec.region = *region;
  p.spacing_deviation = deviation(view, "spacing_deviation", p.spacing, "spacing", "m");
  p.angle_deviation_degrees = deviation(view, "angle_deviation", 90.0, "90 degrees", "degrees");
  if (!p.trace) {
    for (const std::string_view key : {"trace_deviation", "gap_deviation"})
      if (view.has(key))
        view.fail_at_key(key, "[[joint_set]] " + std::string(key) +
                                  " needs a trace (persistent joints have no trace or gap "
                                  "to vary); add trace = 5.0 (m) or remove it");
  } else {
    p.trace_deviation = deviation(view, "trace_deviation", *p.trace, "trace", "m");
    p.gap_deviation = view.number_or("gap_deviation", 0.0, "m", "0.2");
    if (p.gap_deviation < 0.0 || p.gap_deviation > p.gap)
      view.fail_range("gap_deviation", p.gap_deviation,
                      "it must be >= 0 and at most gap (" + format_number(p.gap) +
                          " here): a gap is drawn uniformly within gap +- gap_deviation");
  }
  p.seed = static_cast<std::uint64_t>(
      view.integer("seed", 0, std::numeric_limits<std::int64_t>::max(), "46").value_or(0));
  p.snap_tolerance = view.number_or("snap_tolerance", 0.0, "m", "0.05");
  const double closest_lines = p.spacing - p.spacing_deviation;
  if (view.has("snap_tolerance") &&
      !(p.snap_tolerance > 0.0 && p.snap_tolerance < 0.5 * closest_lines))
    view.fail_range("snap_tolerance", p.snap_tolerance,
                    "it must be > 0 and below half the closest spacing (" +
                        format_number(0.5 * closest_lines) +
                        " m here), or left out for the automatic value");
  p.max_joints =
      static_cast<long>(view.integer("max_joints", 1, 100'000'000, "50000").value_or(p.max_joints));
  p.max_blocks = static_cast<long>(
      view.integer("max_blocks", 1, 1'000'000'000, "200000").value_or(p.max_blocks));
  return spec;
}

} // namespace

std::vector<JointSetSpec> read_joint_set_tables(Context& context,
                                                const toml::table& root,
                                                const std::string& file,
                                                const std::vector<JointSpec>& joints) {
  std::vector<JointSetSpec> sets;
  for (const toml::table* table : table_array(context, root, "joint_set"))
    sets.push_back(read_joint_set(context, *table, file, joints));
  return sets;
}

} // namespace nmm
