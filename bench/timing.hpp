// SPDX-License-Identifier: MIT
// bench/timing.hpp — wall-clock helpers shared by the plain benchmark programs.
#pragma once

#include <algorithm>
#include <chrono>
#include <fstream>

namespace nmm::bench {

using Clock = std::chrono::steady_clock;

/// Seconds since @p t.
inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

/// Best wall time of at least @p repeats calls of f, and of more (up to @p most) while they
/// have taken less than half a second: on a shared 2-core machine the best of many short
/// runs is the figure that other processes disturb least.
template <class Function> double best_seconds(int repeats, Function&& f, int most = 200) {
  double best = 1e300;
  double total = 0.0;
  for (int r = 0; r < repeats || (total < 0.5 && r < most); ++r) {
    const Clock::time_point start = Clock::now();
    f();
    const double seconds = since(start);
    best = std::min(best, seconds);
    total += seconds;
  }
  return best;
}

/// The 1-minute load average (/proc/loadavg), 0 where it cannot be read.
inline double load_average() {
  std::ifstream in("/proc/loadavg");
  double value = 0.0;
  in >> value;
  return value;
}

} // namespace nmm::bench
