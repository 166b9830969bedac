// SPDX-License-Identifier: MIT
#include "io/fos_table.hpp"

namespace nmm {

using namespace case_table;

FosSpec read_fos_table(Context& context, const toml::table& root) {
  FosSpec spec;
  const toml::table* table = single_table(context, root, "fos");
  if (table == nullptr)
    return spec;
  const TableView view(context, *table, "[fos]", fos_keys);
  spec.line = view.position().line;
  spec.steps = view.small_integer_or("steps", spec.steps, 10, 1'000'000, "200");
  spec.decay = view.number_or("decay", spec.decay, "a fraction", "0.1");
  if (!(spec.decay > 0.0 && spec.decay < 1.0))
    view.fail_range("decay", spec.decay,
                    "it must be > 0 and < 1: a trial fails when its last steps move more than "
                    "decay times its first steps");
  spec.rest = view.number_or("rest", spec.rest, "m", "1.0e-10");
  if (!(spec.rest > 0.0))
    view.fail_range("rest", spec.rest,
                    "it must be > 0 (m): the step displacement below which a trial is at rest");
  if (const auto bracket = view.vector<2>("bracket", "factors", "[1.0, 2.0]")) {
    if (!((*bracket)(0) > 0.0 && (*bracket)(1) > (*bracket)(0)))
      view.fail_at_value("bracket", "[fos] bracket = [" + format_number((*bracket)(0)) + ", " +
                                        format_number((*bracket)(1)) +
                                        "] is out of range; it must be [low, high] with "
                                        "0 < low < high (factors of safety), e.g. [1.0, 2.0]");
    spec.bracket_low = (*bracket)(0);
    spec.bracket_high = (*bracket)(1);
  }
  spec.tolerance = view.number_or("tolerance", spec.tolerance, "a fraction", "0.01");
  if (!(spec.tolerance >= 1e-4 && spec.tolerance <= 0.5))
    view.fail_range("tolerance", spec.tolerance,
                    "it must be between 1e-4 and 0.5: the bracket's width relative to its "
                    "lower end at which the search stops");
  const TableView::TimeStep dt = view.time_step(
      "time_step", "0.05", "it must be > 0 (s), or \"auto\" for Shi's automatic static step");
  spec.time_step_set = dt.set;
  spec.time_step = dt.seconds;
  return spec;
}

} // namespace nmm
