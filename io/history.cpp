// SPDX-License-Identifier: MIT
#include "io/history.hpp"

#include "io/atomic_file.hpp"
#include "mesh/error.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <system_error>

namespace nmm {

namespace {

std::string system_reason(int error) { return std::generic_category().message(error); }

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

} // namespace

std::string history_header(std::span<const std::string> monitor_names) {
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
  return header;
}

HistoryWriter::HistoryWriter(std::filesystem::path file, std::vector<std::string> monitor_names)
    : file_(std::move(file)), n_monitors_(monitor_names.size()) {
  stream_ = std::fopen(file_.c_str(), "w");
  if (stream_ == nullptr) {
    throw InputError("cannot write " + file_.string() + ": " + system_reason(errno) +
                     "; choose a writable output folder with -o DIR or [output] dir");
  }
  const std::string header = history_header(monitor_names) + '\n';
  if (std::fputs(header.c_str(), stream_) < 0 || std::fflush(stream_) != 0)
    throw InputError("cannot write " + file_.string() + ": " + system_reason(errno));
  bytes_ = header.size();
}

HistoryWriter::HistoryWriter(std::filesystem::path file,
                             std::vector<std::string> monitor_names,
                             std::uintmax_t keep_bytes)
    : file_(std::move(file)), n_monitors_(monitor_names.size()), bytes_(keep_bytes) {
  const std::string header = history_header(monitor_names) + '\n';
  const auto fail = [&](const std::string& what) {
    throw InputError("cannot continue " + file_.string() + " after the checkpoint: " + what +
                     "; run the case from the start without --restart");
  };
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(file_, error);
  if (error)
    fail(error.message());
  if (size < keep_bytes || keep_bytes < header.size())
    fail("it has " + std::to_string(size) + " bytes, the checkpoint's step ends at byte " +
         std::to_string(keep_bytes));
  {
    std::FILE* in = std::fopen(file_.c_str(), "rb");
    if (in == nullptr)
      fail(system_reason(errno));
    std::string head(header.size(), '\0');
    const bool read = std::fread(head.data(), 1, head.size(), in) == head.size();
    char last = 0;
    const bool end = std::fseek(in, static_cast<long>(keep_bytes) - 1, SEEK_SET) == 0 &&
                     std::fread(&last, 1, 1, in) == 1;
    static_cast<void>(std::fclose(in));
    if (!read || head != header)
      fail("its header is not that of the case's monitors");
    if (!end || last != '\n')
      fail("no row ends at byte " + std::to_string(keep_bytes));
  }
  std::filesystem::resize_file(file_, keep_bytes, error);
  if (error)
    fail(error.message());
  stream_ = std::fopen(file_.c_str(), "a");
  if (stream_ == nullptr)
    fail(system_reason(errno));
}

HistoryWriter::~HistoryWriter() {
  if (stream_ != nullptr)
    static_cast<void>(std::fclose(stream_));
}

void HistoryWriter::write_row(const StepReport& report, std::span<const MonitorValues> monitors) {
  NMM_ASSERT(monitors.size() == n_monitors_, "one MonitorValues per monitor");
  int status =
      std::fprintf(stream_, "%ld,%.17g,%.17g,%d,%d,%.17g", report.step, report.time, report.dt,
                   report.open_close_iterations, report.contacts, report.kinetic_energy);
  long written = status;
  for (const MonitorValues& monitor : monitors) {
    for (const double value : monitor.values()) {
      if (status >= 0)
        written += status = std::fprintf(stream_, ",%.17g", value);
    }
  }
  if (status >= 0)
    written += status =
        std::fprintf(stream_, ",%.17g,%d,%.17g,%.17g,%.17g", report.load_work, report.step_cuts,
                     report.max_penetration, report.lock_excess, report.slide_feed);
  if (status >= 0)
    bytes_ += static_cast<std::uintmax_t>(written) + 1;
  if (status < 0 || std::fputc('\n', stream_) == EOF || std::fflush(stream_) != 0)
    throw InputError("cannot write " + file_.string() + ": " + system_reason(errno) +
                     "; is the disk full?");
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
  root.close();
  out += '\n';
  return out;
}

void write_summary_json(const std::filesystem::path& file, const RunSummary& summary) {
  const std::string text = summary_json(summary);
  write_file_atomically(file, [&](const std::filesystem::path& temporary) {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    return static_cast<bool>(out);
  });
}

} // namespace nmm
