// SPDX-License-Identifier: MIT
#include "io/history.hpp"

#include "io/atomic_file.hpp"
#include "mesh/error.hpp"

#include <fcntl.h>
#include <linux/falloc.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <system_error>

namespace nmm {

namespace {

/// Appends the members of an object, each line indented by @p indent.
class JsonObject {
public:
  JsonObject(std::string& out, int indent) : out_(out), indent_(indent) { out_ += '{'; }
  void key(std::string_view name) {
    out_ += first_ ? "\n" : ",\n";
    first_ = false;
    out_.append(static_cast<std::size_t>(indent_ + 2), ' ');
    out_ += json_string(name);
    out_ += ": ";
  }
  void number(std::string_view name, double value) {
    key(name);
    out_ += json_number(value);
  }
  /// Wall-clock seconds: 6 significant digits (more would be noise).
  void seconds(std::string_view name, double value) {
    key(name);
    if (!std::isfinite(value)) {
      out_ += "null";
      return;
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    out_ += text;
  }
  void integer(std::string_view name, long value) {
    key(name);
    out_ += std::to_string(value);
  }
  void string(std::string_view name, std::string_view value) {
    key(name);
    out_ += json_string(value);
  }
  void close() {
    if (!first_) {
      out_ += '\n';
      out_.append(static_cast<std::size_t>(indent_), ' ');
    }
    out_ += '}';
  }
  [[nodiscard]] int inner_indent() const noexcept { return indent_ + 2; }

private:
  std::string& out_;
  int indent_;
  bool first_ = true;
};

/// Member @p name of @p root: an array of one object per item, each written by @p write
/// (an empty array as []).
template <class Items, class Write>
void object_array(
    JsonObject& root, std::string& out, std::string_view name, const Items& items, Write write) {
  root.key(name);
  out += '[';
  for (std::size_t k = 0; k < items.size(); ++k) {
    out += k == 0 ? "\n" : ",\n";
    out.append(static_cast<std::size_t>(root.inner_indent() + 2), ' ');
    JsonObject item(out, root.inner_indent() + 2);
    write(item, items[k]);
    item.close();
  }
  if (!items.empty()) {
    out += '\n';
    out.append(static_cast<std::size_t>(root.inner_indent()), ' ');
  }
  out += ']';
}

} // namespace

std::string history_header(std::span<const std::string> monitor_names,
                           std::span<const std::string> bolt_names,
                           bool stage) {
  std::string header = "step,time,dt,open_close_iterations,contacts,kinetic_energy";
  for (const std::string& name : monitor_names) {
    for (const std::string_view value : monitor_value_names) {
      header += ',';
      header += name;
      header += '.';
      header += value;
    }
  }
  // Columns added after the first release go last: readers that count columns keep working.
  header += ",load_work,step_cuts,max_penetration,lock_excess,slide_feed";
  header += ",external_work,strain_energy,contact_energy,dissipated_energy,energy_error";
  if (stage)
    header += ",stage";
  for (const std::string& name : bolt_names)
    header += "," + name + ".force";
  return header;
}

HistoryWriter::HistoryWriter(std::filesystem::path file,
                             std::vector<std::string> monitor_names,
                             std::vector<std::string> bolt_names,
                             bool stage)
    : n_monitors_(monitor_names.size()), n_bolts_(bolt_names.size()), stage_(stage),
      rows_(std::move(file), history_header(monitor_names, bolt_names, stage) + '\n') {}

HistoryWriter::HistoryWriter(std::filesystem::path file,
                             std::vector<std::string> monitor_names,
                             std::uintmax_t keep_bytes,
                             std::vector<std::string> bolt_names)
    : n_monitors_(monitor_names.size()), n_bolts_(bolt_names.size()),
      rows_(std::move(file),
            history_header(monitor_names, bolt_names) + '\n',
            bolt_names.empty() ? "that of the case's monitors"
                               : "that of the case's monitors and bolts",
            keep_bytes) {}

void HistoryWriter::write_row(const StepReport& report,
                              std::span<const MonitorValues> monitors,
                              std::span<const double> bolt_forces,
                              std::string_view stage) {
  NMM_ASSERT(monitors.size() == n_monitors_, "one MonitorValues per monitor");
  NMM_ASSERT(bolt_forces.size() == n_bolts_, "one force per bolt");
  std::string row;
  row.reserve(32 * (11 + 9 * monitors.size()));
  char field[64];
  const auto add = [&](int length) {
    row.append(field, static_cast<std::size_t>(std::clamp(length, 0, int{sizeof field} - 1)));
  };
  // One value a field: a field holds one number at full precision (%.17g is at most 24
  // characters), never several (three of them could pass its 64 and be cut).
  const auto number = [&](double value) {
    add(std::snprintf(field, sizeof field, ",%.17g", value));
  };
  add(std::snprintf(field, sizeof field, "%ld", report.step));
  number(report.time);
  number(report.dt);
  add(std::snprintf(field, sizeof field, ",%d,%d", report.open_close_iterations, report.contacts));
  number(report.kinetic_energy);
  for (const MonitorValues& monitor : monitors)
    for (const double value : monitor.values())
      number(value);
  number(report.load_work);
  add(std::snprintf(field, sizeof field, ",%d", report.step_cuts));
  for (const double value :
       {report.max_penetration, report.lock_excess, report.slide_feed, report.external_work,
        report.strain_energy, report.contact_energy, report.dissipated_energy, report.energy_error})
    number(value);
  if (stage_) {
    row += ',';
    row += stage; // (letters, digits and _)
  }
  for (const double force : bolt_forces)
    number(force);
  row += '\n';
  rows_.append(row,
               "the row of step " + std::to_string(report.step) + " (the rows before it stay)");
}

std::string json_string(std::string_view text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    case '\b':
      out += "\\b";
      break;
    case '\f':
      out += "\\f";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20) {
        char escaped[8];
        std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
        out += escaped;
      } else {
        out += c;
      }
    }
  }
  out += '"';
  return out;
}

std::string json_number(double value) {
  if (!std::isfinite(value))
    return "null";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string summary_json(const RunSummary& s) {
  std::string out;
  JsonObject root(out, 0);
  root.string("status", s.status);
  root.integer("steps", s.steps);
  root.number("time", s.time);
  root.seconds("wall_seconds", s.wall_seconds);
  root.integer("dofs", s.dofs);
  root.integer("covers", s.covers);
  root.integer("elements", s.elements);
  root.integer("blocks", s.blocks);
  root.key("warnings");
  out += '[';
  for (std::size_t k = 0; k < s.warnings.size(); ++k) {
    out += k == 0 ? "\n" : ",\n";
    out.append(static_cast<std::size_t>(root.inner_indent() + 2), ' ');
    out += json_string(s.warnings[k]);
  }
  if (!s.warnings.empty()) {
    out += '\n';
    out.append(static_cast<std::size_t>(root.inner_indent()), ' ');
  }
  out += ']';
  root.key("monitors");
  JsonObject monitors(out, root.inner_indent());
  for (const auto& [name, values] : s.monitors) {
    monitors.key(name);
    JsonObject monitor(out, monitors.inner_indent());
    const auto numbers = values.values();
    for (std::size_t k = 0; k < numbers.size(); ++k)
      monitor.number(monitor_value_names[k], numbers[k]);
    monitor.close();
  }
  monitors.close();

  root.string("title", s.title);
  root.string("case", s.case_file);
  root.string("geometry", s.geometry);
  root.integer("unknowns", s.unknowns);
  root.integer("step_cuts", s.step_cuts);
  root.number("max_penetration", s.max_penetration);
  root.number("max_lock_excess", s.counters.max_lock_excess);
  root.key("counters");
  JsonObject counters(out, root.inner_indent());
  counters.integer("steps", s.counters.steps);
  counters.integer("step_cuts", s.counters.step_cuts);
  counters.integer("pattern_builds", s.counters.pattern_builds);
  counters.integer("contact_searches", s.counters.contact_searches);
  counters.integer("stress_updates", s.counters.stress_updates);
  counters.integer("stress_recoveries", s.stress_recoveries);
  counters.integer("friction_terms", s.counters.friction_terms);
  counters.integer("symbolic_analyses", s.solver_counters.symbolic_analyses);
  counters.integer("factorizations", s.solver_counters.factorizations);
  counters.integer("solves", s.solver_counters.solves);
  counters.integer("cg_iterations", s.solver_counters.iterations);
  counters.integer("cg_fallbacks", s.solver_counters.fallbacks);
  counters.integer("plan_rebuilds", s.counters.plan_rebuilds);
  counters.integer("augmentations", s.counters.augmentations);
  counters.integer("coupled_friction_tries", s.counters.coupled_friction_tries);
  counters.integer("coupled_friction_iterations", s.counters.coupled_friction_iterations);
  counters.integer("locks_beyond_friction", s.counters.locks_beyond_friction);
  counters.integer("slides_against_motion", s.counters.slides_against_motion);
  counters.number("slide_feed_work", s.counters.slide_feed_work);
  // Where the steps' time went (StepperCounters): the parts add up to seconds_steps.
  const StepperCounters& c = s.counters;
  counters.seconds("seconds_steps", c.seconds_steps);
  counters.seconds("seconds_step_control", c.seconds_step_control);
  counters.seconds("seconds_detection", c.seconds_detection);
  counters.seconds("seconds_constraints", c.seconds_constraints);
  counters.seconds("seconds_pattern", c.seconds_pattern);
  counters.seconds("seconds_assembly", c.seconds_assembly);
  counters.seconds("seconds_contact_springs", c.seconds_contact_springs);
  counters.seconds("seconds_analysis", c.seconds_analysis);
  counters.seconds("seconds_factorization", c.seconds_factorization);
  counters.seconds("seconds_solve", c.seconds_solve);
  counters.seconds("seconds_contact_modes", c.seconds_contact_modes);
  counters.seconds("seconds_update", c.seconds_update);
  counters.close();
  root.key("mesher");
  JsonObject mesher(out, root.inner_indent());
  mesher.integer("math_triangles", s.mesher.math_triangles);
  mesher.integer("cut_triangles", s.mesher.cut_triangles);
  mesher.integer("physical_edges", s.mesher.physical_edges);
  mesher.integer("tiny_atoms", s.mesher.tiny_atoms);
  mesher.integer("tiny_covers", s.mesher.tiny_covers);
  mesher.seconds("seconds_physical_arrangement", s.mesher.seconds_physical_arrangement);
  mesher.seconds("seconds_cut_triangles", s.mesher.seconds_cut_triangles);
  mesher.seconds("seconds_rest", s.mesher.seconds_rest);
  mesher.close();
  if (s.moved_blocks)
    object_array(root, out, "moved_blocks", *s.moved_blocks,
                 [](JsonObject& block, const MovedBlock& moved) {
                   block.integer("block", moved.block);
                   block.string("material", moved.material);
                   block.number("displacement", moved.displacement);
                 });
  if (!s.stages.empty()) {
    root.string("stage", s.stage);
    object_array(root, out, "stages", s.stages, [](JsonObject& item, const StageSummary& stage) {
      item.string("name", stage.name);
      item.integer("first_step", stage.first_step);
      item.integer("steps", stage.steps);
    });
  }
  if (!s.bolts.empty())
    object_array(root, out, "bolts", s.bolts, [](JsonObject& item, const BoltSummary& bolt) {
      item.string("name", bolt.name);
      item.number("force", bolt.force);
      item.string("state", bolt.state);
      item.integer("bars", bolt.bars);
      item.integer("yielding_bars", bolt.yielding_bars);
      item.integer("ruptured_bars", bolt.ruptured_bars);
    });
  root.close();
  out += '\n';
  return out;
}

namespace {

/// Blocks each summary.json keeps allocated beyond its end (fallocate, FALLOC_FL_KEEP_SIZE),
/// so that the summary of a run that fills the disk can still be written over it.
constexpr off_t summary_reserve = 64 * 1024;

/// Writes all of @p text at offset @p offset of @p descriptor; false on failure (errno set).
bool write_all_at(int descriptor, std::string_view text, off_t offset) {
  while (!text.empty()) {
    const ssize_t written = ::pwrite(descriptor, text.data(), text.size(), offset);
    if (written < 0 && errno == EINTR)
      continue;
    if (written <= 0) {
      if (written == 0)
        errno = ENOSPC;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(written));
    offset += written;
  }
  return true;
}

/// Closes @p descriptor, keeping errno (of the failure before it) unless closing fails.
bool close_keeping_errno(int descriptor, bool ok) {
  const int error = errno;
  const bool closed = ::close(descriptor) == 0;
  if (closed)
    errno = error;
  return ok && closed;
}

/// Writes @p text as the new file @p file with summary_reserve bytes allocated after it.
bool write_reserving(const std::filesystem::path& file, const std::string& text) {
  const int descriptor = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (descriptor < 0)
    return false;
  // No reserve on a file system without fallocate, or a disk too full for it: the summary
  // is still written.
  static_cast<void>(::fallocate(descriptor, FALLOC_FL_KEEP_SIZE, 0,
                                static_cast<off_t>(text.size()) + summary_reserve));
  return close_keeping_errno(descriptor, write_all_at(descriptor, text, 0));
}

/// Writes @p text over the existing @p file in place, into the blocks it holds (its
/// reserve): what a full disk still allows. Not atomic: a reader may see it half written.
bool overwrite_in_place(const std::filesystem::path& file, const std::string& text) {
  const int descriptor = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
  if (descriptor < 0)
    return false;
  const bool ok = write_all_at(descriptor, text, 0) &&
                  ::ftruncate(descriptor, static_cast<off_t>(text.size())) == 0 &&
                  ::fsync(descriptor) == 0;
  return close_keeping_errno(descriptor, ok);
}

} // namespace

void write_summary_json(const std::filesystem::path& file, const RunSummary& summary) {
  const std::string text = summary_json(summary);
  try {
    write_file_atomically(file, [&](const std::filesystem::path& temporary) {
      return write_reserving(temporary, text);
    });
  } catch (const OutputWriteError&) {
    // The disk is full: the summary of a run that ends so must still say why.
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error) || !overwrite_in_place(file, text))
      throw;
  }
}

} // namespace nmm
