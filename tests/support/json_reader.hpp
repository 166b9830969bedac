// SPDX-License-Identifier: MIT
// tests/support/json_reader.hpp — a strict, small JSON reader (RFC 8259) for the tests of
// summary.json: it rejects anything a real JSON parser would reject (trailing commas,
// NaN, unescaped control characters, single quotes), so a test that reads a file with it
// shows the file is valid JSON.
#pragma once

#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nmm::testing {

struct Json {
  enum class Kind { null, boolean, number, string, array, object };
  Kind kind = Kind::null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> items;
  std::vector<std::pair<std::string, Json>> members; // in file order

  [[nodiscard]] bool is_object() const { return kind == Kind::object; }
  [[nodiscard]] bool is_array() const { return kind == Kind::array; }
  [[nodiscard]] bool is_number() const { return kind == Kind::number; }
  [[nodiscard]] bool is_string() const { return kind == Kind::string; }
  /// The member called @p key, or nullptr.
  [[nodiscard]] const Json* find(std::string_view key) const {
    for (const auto& [name, value] : members)
      if (name == key)
        return &value;
    return nullptr;
  }
  /// The member called @p key; throws std::out_of_range when missing.
  [[nodiscard]] const Json& at(std::string_view key) const {
    const Json* value = find(key);
    if (value == nullptr)
      throw std::out_of_range("no JSON member \"" + std::string(key) + "\"");
    return *value;
  }
  [[nodiscard]] std::vector<std::string> keys() const {
    std::vector<std::string> result;
    for (const auto& member : members)
      result.push_back(member.first);
    return result;
  }
};

namespace detail {

class JsonParser {
public:
  explicit JsonParser(std::string_view text) : text_(text) {}

  Json document() {
    Json value = parse_value();
    skip_space();
    if (position_ != text_.size())
      fail("text after the JSON value");
    return value;
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("invalid JSON at offset " + std::to_string(position_) + ": " + what);
  }
  void skip_space() {
    while (position_ < text_.size() && (text_[position_] == ' ' || text_[position_] == '\n' ||
                                        text_[position_] == '\r' || text_[position_] == '\t'))
      ++position_;
  }
  char peek() {
    skip_space();
    if (position_ >= text_.size())
      fail("unexpected end");
    return text_[position_];
  }
  void expect(char c) {
    if (peek() != c)
      fail(std::string("expected '") + c + "'");
    ++position_;
  }
  bool literal(std::string_view word) {
    if (text_.substr(position_, word.size()) != word)
      return false;
    position_ += word.size();
    return true;
  }

  Json parse_value() {
    const char c = peek();
    Json value;
    if (c == '{') {
      value.kind = Json::Kind::object;
      ++position_;
      if (peek() == '}') {
        ++position_;
        return value;
      }
      for (;;) {
        if (peek() != '"')
          fail("expected a member name");
        std::string key = parse_string();
        expect(':');
        value.members.emplace_back(std::move(key), parse_value());
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect('}');
        return value;
      }
    }
    if (c == '[') {
      value.kind = Json::Kind::array;
      ++position_;
      if (peek() == ']') {
        ++position_;
        return value;
      }
      for (;;) {
        value.items.push_back(parse_value());
        if (peek() == ',') {
          ++position_;
          continue;
        }
        expect(']');
        return value;
      }
    }
    if (c == '"') {
      value.kind = Json::Kind::string;
      value.string = parse_string();
      return value;
    }
    if (literal("true")) {
      value.kind = Json::Kind::boolean;
      value.boolean = true;
      return value;
    }
    if (literal("false")) {
      value.kind = Json::Kind::boolean;
      return value;
    }
    if (literal("null"))
      return value;
    value.kind = Json::Kind::number;
    value.number = parse_number();
    return value;
  }

  std::string parse_string() {
    expect('"');
    std::string out;
    for (;;) {
      if (position_ >= text_.size())
        fail("unterminated string");
      const char c = text_[position_++];
      if (c == '"')
        return out;
      if (static_cast<unsigned char>(c) < 0x20)
        fail("unescaped control character in a string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (position_ >= text_.size())
        fail("unterminated escape");
      const char e = text_[position_++];
      switch (e) {
      case '"':
      case '\\':
      case '/':
        out += e;
        break;
      case 'b':
        out += '\b';
        break;
      case 'f':
        out += '\f';
        break;
      case 'n':
        out += '\n';
        break;
      case 'r':
        out += '\r';
        break;
      case 't':
        out += '\t';
        break;
      case 'u': {
        if (position_ + 4 > text_.size())
          fail("short \\u escape");
        const std::string hex(text_.substr(position_, 4));
        char* end = nullptr;
        const long code = std::strtol(hex.c_str(), &end, 16);
        if (end != hex.c_str() + 4)
          fail("bad \\u escape");
        position_ += 4;
        if (code >= 0x80)
          fail("the tests only expect \\u escapes of ASCII control characters");
        out += static_cast<char>(code);
        break;
      }
      default:
        fail("unknown escape");
      }
    }
  }

  double parse_number() {
    // JSON grammar: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
    const std::size_t start = position_;
    auto digits = [&] {
      const std::size_t from = position_;
      while (position_ < text_.size() && text_[position_] >= '0' && text_[position_] <= '9')
        ++position_;
      return position_ - from;
    };
    if (position_ < text_.size() && text_[position_] == '-')
      ++position_;
    if (position_ < text_.size() && text_[position_] == '0')
      ++position_;
    else if (digits() == 0)
      fail("expected a value");
    if (position_ < text_.size() && text_[position_] == '.') {
      ++position_;
      if (digits() == 0)
        fail("digits expected after '.'");
    }
    if (position_ < text_.size() && (text_[position_] == 'e' || text_[position_] == 'E')) {
      ++position_;
      if (position_ < text_.size() && (text_[position_] == '+' || text_[position_] == '-'))
        ++position_;
      if (digits() == 0)
        fail("digits expected in the exponent");
    }
    const std::string number(text_.substr(start, position_ - start));
    return std::strtod(number.c_str(), nullptr);
  }

  std::string_view text_;
  std::size_t position_ = 0;
};

} // namespace detail

/// Parses @p text; throws std::runtime_error naming the offset on any deviation from JSON.
inline Json parse_json(std::string_view text) { return detail::JsonParser(text).document(); }

} // namespace nmm::testing
