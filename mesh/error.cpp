// SPDX-License-Identifier: MIT
#include "mesh/error.hpp"

#include <sstream>

namespace nmm {

std::string
InputError::format(const std::string& file, int line, int column, const std::string& message) {
  std::ostringstream out;
  if (!file.empty()) {
    out << file;
    if (line > 0) {
      out << ':' << line;
      if (column > 0)
        out << ':' << column;
    }
    out << ": ";
  }
  out << message;
  return out.str();
}

namespace detail {
void assertion_failed(const char* condition,
                      const char* file,
                      int line,
                      const std::string& message) {
  std::ostringstream out;
  out << file << ':' << line << ": internal check failed: " << condition << " — " << message
      << " (this is a bug in nmm; please report it with the case that triggers it)";
  throw std::logic_error(out.str());
}
} // namespace detail

} // namespace nmm
