// SPDX-License-Identifier: MIT
// The gmsh session (GmshSession) and the errors gmsh reports (throw_gmsh_error()).
#include "io/gmsh_internal.hpp"
#include "io/gmsh_reader.hpp"
#include "mesh/error.hpp"

#include <gmsh.h>

#include <atomic>
#include <clocale>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

namespace nmm {

namespace {

std::atomic<bool> session_alive{false};

} // namespace

namespace detail {

void throw_gmsh_error(const std::string& file,
                      const std::string& doing,
                      const std::vector<std::string>& errors) {
  const std::string& first = errors.front();
  const std::string more =
      errors.size() > 1
          ? " (gmsh reported " + std::to_string(errors.size() - 1) + " more error(s) after this)"
          : std::string();
  // gmsh's .geo parser writes "'FILE', line N: what"; keep FILE (it may be an included file)
  // and N so that editors can jump there.
  static const std::regex located(R"('([^']*)', line ([0-9]+): (.*))");
  std::smatch match;
  if (std::regex_search(first, match, located)) {
    const int line = std::stoi(match[2].str());
    throw InputError(match[1].str(), line, 0,
                     "gmsh: " + match[3].str() + more +
                         "; fix the file there (gmsh names the line where it noticed the "
                         "problem, which can be just after the actual mistake)");
  }
  throw InputError(file + ": gmsh could not " + doing + ": " + first + more);
}

} // namespace detail

// ------------------------------------------------------------------------------------------
// GmshSession

GmshSession::GmshSession() {
  bool expected = false;
  if (!session_alive.compare_exchange_strong(expected, true)) {
    throw std::logic_error("nmm::GmshSession: a gmsh session is already alive; gmsh has one "
                           "global state, so keep a single GmshSession at a time");
  }
  const char* locale = std::setlocale(LC_ALL, nullptr);
  saved_locale_ = locale != nullptr ? locale : "C";
  try {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", 0);
    // Errors go to the log (read back by run_gmsh) instead of being thrown: an exception out
    // of gmsh 4.8's .geo parser leaves it unusable for the rest of the process.
    gmsh::option::setNumber("General.AbortOnError", 0);
    // Errors and warnings only: the log is copied whenever we look at it.
    gmsh::option::setNumber("General.Verbosity", 2);
    gmsh::option::setNumber("General.NumThreads", 1);
    gmsh::logger::start();
  } catch (...) {
    std::setlocale(LC_ALL, saved_locale_.c_str());
    session_alive = false;
    throw;
  }
}

GmshSession::~GmshSession() {
  try {
    gmsh::logger::stop();
    gmsh::finalize();
  } catch (...) {
    // A destructor must not throw; gmsh has nothing left for us to release.
  }
  std::setlocale(LC_ALL, saved_locale_.c_str());
  session_alive = false;
}

bool GmshSession::is_alive() noexcept { return session_alive.load(); }

} // namespace nmm
