// SPDX-License-Identifier: MIT
// io/case_table.hpp — reading one TOML table of a case file: its allowed keys, typed values
// and the messages that name the file, line and key of a problem (docs/case-file.md, "Rules
// for every key"). Internal to io/: the readers of each table (io/case_file.cpp and the
// files beside it) share it.
#pragma once

#include "io/text.hpp"
#include "mesh/error.hpp"

#include <Eigen/Core>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nmm::case_table {

// No number of a case in SI units comes near this (a neutron star's density is 5e17 kg/m^3),
// and products of three such numbers still fit in a double.
constexpr double largest_input_magnitude = 1e100;

// How the top level is named in messages and in a schema.
constexpr std::string_view top_level_name = "the top level";

// One entry of the schema: a table's display name and the keys it accepts. The schema is
// also used to say where a misplaced key belongs.
struct TableKeys {
  std::string_view table;
  std::span<const std::string_view> keys;
};

[[nodiscard]] std::string join(std::span<const std::string_view> words,
                               std::string_view quote = "");
[[nodiscard]] std::string format_number(double value);
[[nodiscard]] std::string range_requirement(std::int64_t minimum, std::int64_t maximum);
[[nodiscard]] std::string describe_type(const toml::node& node);

struct Position {
  int line = 0;
  int column = 0;
  auto operator<=>(const Position&) const = default;
};

[[nodiscard]] Position position_of(const toml::source_region& region);

// Where the messages go: the file name, the schema and the warnings collected so far.
class Context {
public:
  Context(std::string file, std::span<const TableKeys> schema)
      : file_(std::move(file)), schema_(schema) {}

  [[noreturn]] void fail(Position at, const std::string& message) const;
  void warn(int line, const std::string& message);
  [[nodiscard]] std::vector<std::string> take_warnings() { return std::move(warnings_); }
  // Where else a misplaced key would be accepted, as a hint for the unknown-key message.
  [[nodiscard]] std::string where_key_belongs(std::string_view key,
                                              std::string_view this_table) const;

private:
  std::string file_;
  std::span<const TableKeys> schema_;
  std::vector<std::string> warnings_;
};

// One TOML table of the case file with its allowed keys; every accessor reports problems
// at the key or value they concern. Unknown keys are rejected on construction, before any
// value is read, so a misspelt key is reported as such and not as a missing one.
class TableView {
public:
  TableView(Context& context,
            const toml::table& table,
            std::string display_name,
            std::span<const std::string_view> allowed)
      : context_(context), table_(table), name_(std::move(display_name)), allowed_(allowed) {
    reject_unknown_keys();
  }

  [[nodiscard]] const std::string& name() const { return name_; }
  // How a key is named in messages: "[materials.rock] young", or just "geometry".
  [[nodiscard]] std::string subject(std::string_view key) const {
    return name_ == top_level_name ? std::string(key) : name_ + " " + std::string(key);
  }
  [[nodiscard]] Position position() const { return position_of(table_.source()); }
  [[nodiscard]] const toml::node* find(std::string_view key) const { return table_.get(key); }
  [[nodiscard]] bool has(std::string_view key) const { return find(key) != nullptr; }

  [[nodiscard]] Position key_position(std::string_view key) const {
    for (auto&& [name, node] : table_) {
      if (name.str() == key)
        return position_of(name.source());
    }
    return position();
  }
  [[nodiscard]] Position value_position(std::string_view key) const {
    const toml::node* node = find(key);
    return node ? position_of(node->source()) : position();
  }

  [[noreturn]] void fail_at_key(std::string_view key, const std::string& message) const {
    context_.fail(key_position(key), message);
  }
  [[noreturn]] void fail_at_value(std::string_view key, const std::string& message) const {
    context_.fail(value_position(key), message);
  }
  [[noreturn]] void
  fail_missing(std::string_view key, std::string_view meaning, std::string_view example) const {
    context_.fail(position(), name_ + " is missing " + std::string(key) + " (" +
                                  std::string(meaning) + "); add a line such as " +
                                  std::string(key) + " = " + std::string(example));
  }
  // "[materials.rock] young = -5 is out of range; " + requirement.
  [[noreturn]] void
  fail_range(std::string_view key, double value, const std::string& requirement) const {
    fail_at_value(key,
                  subject(key) + " = " + format_number(value) + " is out of range; " + requirement);
  }

  // A number (integers are accepted); finite.
  [[nodiscard]] std::optional<double>
  number(std::string_view key, std::string_view unit, std::string_view example) const {
    const toml::node* node = find(key);
    if (!node)
      return std::nullopt;
    return to_number(*node, key, unit, example);
  }
  // A time step: a number of seconds > 0, or "auto" (set, no seconds: Shi's automatic step);
  // absent: not set. @p example is the number the messages suggest, @p requirement what a
  // number out of range is told.
  struct TimeStep {
    bool set = false;
    std::optional<double> seconds;
  };
  [[nodiscard]] TimeStep
  time_step(std::string_view key, std::string_view example, const std::string& requirement) const {
    const toml::node* node = find(key);
    if (!node)
      return {};
    if (const auto* text = node->as_string()) {
      if (text->get() != "auto")
        fail_at_value(key, subject(key) + " = " + in_quotes(text->get()) +
                               " is not allowed; write a number of seconds (" + std::string(key) +
                               " = " + std::string(example) + ") or \"auto\"");
      return {true, std::nullopt};
    }
    const double seconds = to_number(*node, key, "s, or \"auto\"", example);
    if (!(seconds > 0.0))
      fail_range(key, seconds, requirement);
    return {true, seconds};
  }
  [[nodiscard]] double number_or(std::string_view key,
                                 double fallback,
                                 std::string_view unit,
                                 std::string_view example) const {
    return number(key, unit, example).value_or(fallback);
  }
  [[nodiscard]] double required_number(std::string_view key,
                                       std::string_view meaning,
                                       std::string_view unit,
                                       std::string_view example) const {
    const std::optional<double> value = number(key, unit, example);
    if (!value)
      fail_missing(key, meaning, example);
    return *value;
  }

  // A whole number in [minimum, maximum]; an integral float such as 1e4 is accepted.
  [[nodiscard]] std::optional<std::int64_t> integer(std::string_view key,
                                                    std::int64_t minimum,
                                                    std::int64_t maximum,
                                                    std::string_view example) const {
    const toml::node* node = find(key);
    if (!node)
      return std::nullopt;
    std::int64_t value = 0;
    if (const auto* integral = node->as_integer()) {
      value = integral->get();
    } else if (const auto* floating = node->as_floating_point()) {
      const double x = floating->get();
      if (!std::isfinite(x) || x != std::floor(x))
        context_.fail(position_of(node->source()),
                      subject(key) + " must be a whole number, not " + format_number(x) +
                          "; write e.g. " + std::string(key) + " = " + std::string(example));
      // Beyond 2^53 a double no longer holds every integer; no count here gets near that.
      if (std::abs(x) > 9.0e15)
        context_.fail(position_of(node->source()), subject(key) + " = " + format_number(x) +
                                                       " is out of range; " +
                                                       range_requirement(minimum, maximum));
      value = static_cast<std::int64_t>(x);
    } else {
      fail_type(*node, key, "a whole number", example);
    }
    if (value < minimum || value > maximum)
      context_.fail(position_of(node->source()), subject(key) + " = " + std::to_string(value) +
                                                     " is out of range; " +
                                                     range_requirement(minimum, maximum));
    return value;
  }
  [[nodiscard]] int small_integer_or(std::string_view key,
                                     int fallback,
                                     int minimum,
                                     int maximum,
                                     std::string_view example) const {
    return static_cast<int>(integer(key, minimum, maximum, example).value_or(fallback));
  }

  [[nodiscard]] bool boolean_or(std::string_view key, bool fallback) const {
    const toml::node* node = find(key);
    if (!node)
      return fallback;
    const auto* value = node->as_boolean();
    if (!value)
      fail_type(*node, key, "true or false (without quotes)", fallback ? "true" : "false");
    return value->get();
  }

  [[nodiscard]] std::optional<std::string>
  string(std::string_view key, std::string_view meaning, std::string_view example) const {
    const toml::node* node = find(key);
    if (!node)
      return std::nullopt;
    const auto* text = node->as_string();
    if (!text)
      fail_type(*node, key, "a string in double quotes (" + std::string(meaning) + ")", example);
    return text->get();
  }
  // A name of something in the geometry: a non-empty string.
  [[nodiscard]] std::optional<std::string> name_string(std::string_view key,
                                                       std::string_view meaning) const {
    std::optional<std::string> text = string(key, meaning, "\"base\"");
    if (text && text->empty())
      fail_at_value(key, subject(key) + " is empty; give the name of a " + std::string(meaning));
    return text;
  }

  // One of @p choices; returns its index (or @p fallback when the key is absent).
  [[nodiscard]] std::size_t choice(std::string_view key,
                                   std::span<const std::string_view> choices,
                                   std::size_t fallback) const {
    const toml::node* node = find(key);
    if (!node)
      return fallback;
    const auto* text = node->as_string();
    if (!text)
      fail_type(*node, key, "one of the strings " + join(choices, "\""),
                in_quotes(choices[fallback]));
    const auto found = std::find(choices.begin(), choices.end(), text->get());
    if (found != choices.end())
      return static_cast<std::size_t>(found - choices.begin());
    std::string message = subject(key) + " = " + in_quotes(text->get()) +
                          " is not allowed; use one of " + join(choices, "\"");
    if (const std::string_view near = closest(text->get(), choices); !near.empty())
      message = subject(key) + " = " + in_quotes(text->get()) + " is not allowed; did you mean " +
                in_quotes(near) + "? (allowed: " + join(choices, "\"") + ")";
    context_.fail(position_of(node->source()), message);
  }

  // An array of exactly N finite numbers.
  template <int N>
  [[nodiscard]] std::optional<Eigen::Matrix<double, N, 1>>
  vector(std::string_view key, std::string_view unit, std::string_view example) const {
    const toml::node* node = find(key);
    if (!node)
      return std::nullopt;
    const auto* array = node->as_array();
    if (!array)
      fail_type(*node, key,
                "an array of " + std::to_string(N) + " numbers (" + std::string(unit) + ")",
                example);
    if (array->size() != static_cast<std::size_t>(N))
      context_.fail(position_of(node->source()),
                    subject(key) + " has " + std::to_string(array->size()) +
                        " value(s) but needs exactly " + std::to_string(N) + "; write e.g. " +
                        std::string(key) + " = " + std::string(example));
    Eigen::Matrix<double, N, 1> result;
    for (int i = 0; i < N; ++i)
      result[i] = to_number((*array)[static_cast<std::size_t>(i)], key, unit, example);
    return result;
  }

private:
  [[noreturn]] void fail_type(const toml::node& node,
                              std::string_view key,
                              const std::string& expected,
                              std::string_view example) const {
    std::string message = subject(key) + " must be " + expected + ", not " + describe_type(node);
    if (node.is_string() && expected.find("number") != std::string::npos)
      message += "; remove the quotes: " + std::string(key) + " = " + std::string(example);
    else
      message += "; write e.g. " + std::string(key) + " = " + std::string(example);
    context_.fail(position_of(node.source()), message);
  }

  double to_number(const toml::node& node,
                   std::string_view key,
                   std::string_view unit,
                   std::string_view example) const {
    double value = 0.0;
    if (const auto* integral = node.as_integer())
      value = static_cast<double>(integral->get());
    else if (const auto* floating = node.as_floating_point())
      value = floating->get();
    else
      fail_type(node, key, "a number (" + std::string(unit) + ")", example);
    if (!std::isfinite(value))
      context_.fail(position_of(node.source()), subject(key) + " is " + format_number(value) +
                                                    "; it must be a finite number (" +
                                                    std::string(unit) + ")");
    if (std::abs(value) > largest_input_magnitude)
      context_.fail(position_of(node.source()),
                    subject(key) + " is " + format_number(value) + ", which is not finite in " +
                        "the model's units: the step equations multiply such values together " +
                        "(stiffness by displacement, mass by velocity squared) and beyond " +
                        format_number(largest_input_magnitude) +
                        " the products overflow double precision (1.8e308); check the value "
                        "and its unit (" +
                        std::string(unit) + ", SI)");
    return value;
  }

  void reject_unknown_keys() const {
    const toml::key* first = nullptr;
    for (auto&& [key, node] : table_) {
      if (std::find(allowed_.begin(), allowed_.end(), key.str()) != allowed_.end())
        continue;
      if (!first || position_of(key.source()) < position_of(first->source()))
        first = &key;
    }
    if (!first)
      return;
    const std::string_view key = first->str();
    std::string message = name_ == top_level_name
                              ? "unknown key " + std::string(key) + " at the top level"
                              : name_ + " has no key " + std::string(key);
    if (const std::string elsewhere = context_.where_key_belongs(key, name_); !elsewhere.empty())
      message += "; " + elsewhere;
    else if (const std::string_view near = closest(key, allowed_); !near.empty())
      message += "; did you mean " + std::string(near) + "?";
    else
      message += "; remove it or correct its spelling";
    message += " (allowed: " + join(allowed_) + ")";
    context_.fail(position_of(first->source()), message);
  }

  Context& context_;
  const toml::table& table_;
  std::string name_;
  std::span<const std::string_view> allowed_;
};

// Refuses a name @p name of @p key that is empty or has a character other than letters,
// digits and _ (it prefixes history.csv columns: [[monitor]], [[bolt]]).
void check_column_name(const TableView& view, std::string_view key, const std::string& name);

// A table-valued top-level key ([cover_mesh], [analysis], ...), or nullptr when absent.
[[nodiscard]] const toml::table*
single_table(const Context& context, const toml::table& root, std::string_view key);

// The tables of an array of tables ([[boundary]], [[load]], [[monitor]]).
[[nodiscard]] std::vector<const toml::table*>
table_array(const Context& context, const toml::table& root, std::string_view key);

// Named tables ([materials.NAME], [joints.NAME]) in the order of the file.
struct NamedTable {
  std::string name;
  Position position;
  const toml::table* table;
};

[[nodiscard]] std::vector<NamedTable> named_tables(const Context& context,
                                                   const toml::table& root,
                                                   std::string_view key,
                                                   std::span<const std::string_view> item_keys,
                                                   std::string_view what);

} // namespace nmm::case_table
