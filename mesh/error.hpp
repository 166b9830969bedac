// SPDX-License-Identifier: MIT
// mesh/error.hpp — the error types and the one assertion macro every module uses.
#pragma once

#include <stdexcept>
#include <string>

namespace nmm {

/// A problem with what the user gave us (case file, geometry, command line).
///
/// The message says where (file, line, column or physical group) and what to do; it is
/// thrown in every build type. Only io/cli.cpp catches it and turns it into an exit code.
class InputError : public std::runtime_error {
public:
  /// @param message  the whole message, already naming the place and the remedy.
  explicit InputError(const std::string& message) : std::runtime_error(message) {}

  /// Formats "file:line:column: message" (line/column 0 are left out).
  InputError(const std::string& file, int line, int column, const std::string& message)
      : std::runtime_error(format(file, line, column, message)), file_(file), line_(line) {}

  /// The file the problem is in, empty when not tied to a file.
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  /// 1-based line of the problem, 0 when unknown.
  [[nodiscard]] int line() const noexcept { return line_; }

private:
  static std::string
  format(const std::string& file, int line, int column, const std::string& message);
  std::string file_;
  int line_ = 0;
};

/// A numerical failure the caller may be able to recover from (e.g. by cutting the step).
/// Library code prefers returning a status; this is for failures deep inside a call chain.
class NumericalError : public std::runtime_error {
public:
  explicit NumericalError(const std::string& message) : std::runtime_error(message) {}
};

namespace detail {
/// Throws std::logic_error describing a failed NMM_ASSERT (never aborts: CGAL's rule).
[[noreturn]] void
assertion_failed(const char* condition, const char* file, int line, const std::string& message);
} // namespace detail

} // namespace nmm

/// Programmer-error check, active in Debug and sanitizer builds, compiled out in Release.
#if defined(NDEBUG) && !defined(NMM_ENABLE_ASSERTS)
// Unevaluated operands keep variables used only in checks from warning as unused.
#define NMM_ASSERT(condition, message)                                                             \
  static_cast<void>(sizeof(static_cast<bool>(condition)) + sizeof(message))
#else
#define NMM_ASSERT(condition, message)                                                             \
  ((condition) ? static_cast<void>(0)                                                              \
               : ::nmm::detail::assertion_failed(#condition, __FILE__, __LINE__, (message)))
#endif
