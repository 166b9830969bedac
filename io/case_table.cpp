// SPDX-License-Identifier: MIT
#include "io/case_table.hpp"

#include "io/text.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <sstream>

namespace nmm::case_table {

std::string join(std::span<const std::string_view> words, std::string_view quote) {
  std::string result;
  for (const std::string_view word : words) {
    if (!result.empty())
      result += ", ";
    result.append(quote).append(word).append(quote);
  }
  return result;
}

std::string format_number(double value) {
  std::array<char, 32> buffer{};
  const auto [end, error] = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return error == std::errc{} ? std::string(buffer.data(), end) : std::string("?");
}

std::string range_requirement(std::int64_t minimum, std::int64_t maximum) {
  if (maximum == std::numeric_limits<std::int64_t>::max())
    return "it must be >= " + std::to_string(minimum);
  return "it must be from " + std::to_string(minimum) + " to " + std::to_string(maximum);
}

std::string describe_type(const toml::node& node) {
  switch (node.type()) {
  case toml::node_type::table:
    return "a table";
  case toml::node_type::array:
    return "an array";
  case toml::node_type::string:
    return "a string (" + in_quotes(node.as_string()->get()) + ")";
  case toml::node_type::integer:
    return "an integer";
  case toml::node_type::floating_point:
    return "a number";
  case toml::node_type::boolean:
    return "a boolean";
  case toml::node_type::date:
  case toml::node_type::time:
  case toml::node_type::date_time:
    return "a date or time";
  case toml::node_type::none:
    break;
  }
  return "nothing";
}

Position position_of(const toml::source_region& region) {
  return {static_cast<int>(region.begin.line), static_cast<int>(region.begin.column)};
}

void Context::fail(Position at, const std::string& message) const {
  throw InputError(file_, at.line, at.column, message);
}

void Context::warn(int line, const std::string& message) {
  std::ostringstream out;
  out << file_ << ':' << line << ": " << message;
  warnings_.push_back(out.str());
}

std::string Context::where_key_belongs(std::string_view key, std::string_view this_table) const {
  std::vector<std::string_view> tables;
  for (const TableKeys& entry : schema_) {
    if (entry.table != this_table &&
        std::find(entry.keys.begin(), entry.keys.end(), key) != entry.keys.end())
      tables.push_back(entry.table);
  }
  if (tables.empty())
    return {};
  if (tables.front() == top_level_name)
    return std::string(key) +
           " is a top-level key: move it above the first [table] header (a key belongs to "
           "the nearest header above it)";
  return std::string(key) + " belongs in " + join(tables) + ": move it under that header";
}

const toml::table*
single_table(const Context& context, const toml::table& root, std::string_view key) {
  const toml::node* node = root.get(key);
  if (!node)
    return nullptr;
  if (const auto* table = node->as_table())
    return table;
  const std::string header = std::string("[").append(key).append("]");
  if (node->is_array())
    context.fail(position_of(node->source()),
                 std::string(key) + " must be one table, not an array of tables; write " + header +
                     ", not [" + header + "]");
  context.fail(position_of(node->source()), std::string(key) + " must be a table, not " +
                                                describe_type(*node) + "; write the header " +
                                                header + " and put its keys on the lines below");
}

std::vector<const toml::table*>
table_array(const Context& context, const toml::table& root, std::string_view key) {
  std::vector<const toml::table*> tables;
  const toml::node* node = root.get(key);
  if (!node)
    return tables;
  const std::string header = std::string("[[").append(key).append("]]");
  const auto* array = node->as_array();
  if (!array)
    context.fail(position_of(node->source()),
                 std::string(key) + " must be an array of tables, not " + describe_type(*node) +
                     "; write " + header + " (double brackets) before each entry");
  for (const toml::node& element : *array) {
    const auto* table = element.as_table();
    if (!table)
      context.fail(position_of(element.source()), "each " + std::string(key) +
                                                      " entry must be a table, not " +
                                                      describe_type(element) + "; write " + header +
                                                      " followed by its keys on the lines below");
    tables.push_back(table);
  }
  return tables;
}

std::vector<NamedTable> named_tables(const Context& context,
                                     const toml::table& root,
                                     std::string_view key,
                                     std::span<const std::string_view> item_keys,
                                     std::string_view what) {
  std::vector<NamedTable> items;
  const toml::table* parent = single_table(context, root, key);
  if (!parent)
    return items;
  for (auto&& [name, node] : *parent) {
    const Position at = position_of(name.source());
    const auto* table = node.as_table();
    if (!table) {
      const std::string item = std::string(key) + "." + std::string(name.str());
      std::string message = item + " must be a table, not " + describe_type(node) + "; write [" +
                            item + "] (" + std::string(name.str()) + " = a " + std::string(what) +
                            ") and put its keys on the lines below";
      if (std::find(item_keys.begin(), item_keys.end(), name.str()) != item_keys.end())
        message = std::string(name.str()) + " cannot be set on [" + std::string(key) +
                  "] itself; write [" + std::string(key) + ".NAME] (NAME = a " + std::string(what) +
                  ") and put " + std::string(name.str()) + " under it";
      context.fail(at, message);
    }
    if (name.str().empty())
      context.fail(
          at, std::string("[").append(key).append(".\"\"] has an empty name; use the name of a ") +
                  std::string(what));
    items.push_back({std::string(name.str()), at, table});
  }
  std::sort(items.begin(), items.end(),
            [](const NamedTable& a, const NamedTable& b) { return a.position < b.position; });
  return items;
}

void check_column_name(const TableView& view, std::string_view key, const std::string& name) {
  if (name.empty())
    view.fail_at_value(key, view.subject(key) + " is empty; give a name of letters, digits and _");
  const auto bad = std::find_if(name.begin(), name.end(), [](char c) {
    return !(std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  });
  if (bad != name.end()) {
    std::string fixed = name;
    for (char& c : fixed)
      if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
        c = '_';
    view.fail_at_value(key, view.subject(key) + " = " + in_quotes(name) + " contains '" +
                                std::string(1, *bad) +
                                "'; use only letters, digits and _ (it prefixes the "
                                "history.csv columns), e.g. " +
                                std::string(key) + " = " + in_quotes(fixed));
  }
}

} // namespace nmm::case_table
