// SPDX-License-Identifier: MIT
// io/text.hpp — small text helpers for the messages of the io module.
#pragma once

#include <chrono>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace nmm {

/// @p text in lower case (ASCII).
[[nodiscard]] std::string lower(std::string_view text);

/// "text", in double quotes (names and values of the case file).
[[nodiscard]] std::string in_quotes(std::string_view text);

/// 'path', in single quotes (files).
[[nodiscard]] std::string quoted(const std::filesystem::path& path);

/// Optimal string alignment distance (Levenshtein plus adjacent transpositions), ignoring
/// case, so that "yung", "Young" and "poisosn" all find their key.
[[nodiscard]] int edit_distance(std::string_view first, std::string_view second);

/// The candidate closest to @p word when it is close enough to be a typing slip (at most a
/// third of its letters, at least one; never for words of one or two letters), else "".
[[nodiscard]] std::string_view closest(std::string_view word,
                                       std::span<const std::string_view> candidates);

/// @p value with @p digits significant digits, as iostreams print it (for messages).
[[nodiscard]] std::string number_text(double value, int digits = 4);

/// Wall-clock seconds since @p start.
[[nodiscard]] double seconds_since(std::chrono::steady_clock::time_point start);

} // namespace nmm
