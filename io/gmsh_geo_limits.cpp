// SPDX-License-Identifier: MIT
// Reading a .geo in a child process under the case's time and memory limits
// (geometry_time_limit, NMM_MEMORY_LIMIT), before the reader runs it in this process.
#include "io/gmsh_internal.hpp"
#include "io/text.hpp"
#include "mesh/error.hpp"

#include <gmsh.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <fstream>
#include <new>
#include <string>
#include <thread>

namespace nmm::detail {

namespace {

/// The address space of this process, bytes (0 when unknown).
double address_space() {
  std::ifstream statm("/proc/self/statm");
  double pages = 0.0;
  if (!(statm >> pages))
    return 0.0;
  return pages * static_cast<double>(::sysconf(_SC_PAGE_SIZE));
}

/// The exit code of the child of read_within_limits() that ran out of memory.
constexpr int out_of_memory_exit = 3;

} // namespace

void read_within_limits(const std::filesystem::path& file, const GeometryReadOptions& options) {
  if (!(options.time_limit > 0.0) && !(options.memory_limit > 0.0))
    return;
  const std::string name = file.string();
  const double space = address_space();
  const pid_t child = ::fork();
  if (child < 0)
    return; // no process to spare: read it without the limits
  if (child == 0) {
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (options.memory_limit > 0.0 && space > 0.0) {
      struct rlimit limit {};
      limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(space + options.memory_limit);
      ::setrlimit(RLIMIT_AS, &limit);
    }
    try {
      gmsh::clear();
      gmsh::open(name);
    } catch (const std::bad_alloc&) {
      ::_exit(out_of_memory_exit);
    } catch (...) {
      ::_exit(0); // gmsh's own error: reported by the read in the parent
    }
    ::_exit(0);
  }
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const double limit = options.time_limit > 0.0 ? options.time_limit : 1e30;
  int status = 0;
  for (;;) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child)
      break;
    if (done < 0 && errno != EINTR)
      return;
    if (std::chrono::duration<double>(Clock::now() - start).count() > limit) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      throw InputError(
          name + ": reading the geometry was stopped after " + number_text(options.time_limit) +
          " s, the case's geometry_time_limit: gmsh was still running the file (an endless "
          "For or While loop, a Macro that calls itself, or far too many entities?); fix the "
          ".geo, or raise geometry_time_limit (s) in the case file if it really takes that long");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
    return;
  const std::string memory =
      options.memory_limit > 0.0
          ? "the " + number_text(options.memory_limit / 1e9, 3) +
                " GB it may use (the machine's memory, or NMM_MEMORY_LIMIT when it is set)"
          : std::string("the memory there is");
  const std::string how = WIFSIGNALED(status)
                              ? "stopped by signal " + std::to_string(WTERMSIG(status))
                              : "exited with code " + std::to_string(WEXITSTATUS(status));
  throw InputError(name + ": reading the geometry (in a child process, " + how + ") ran out of " +
                   memory +
                   ", or gmsh crashed: does the .geo make far too many points or entities (a "
                   "runaway For loop)?; fix the .geo, or set NMM_MEMORY_LIMIT (bytes) higher");
}

} // namespace nmm::detail
