// SPDX-License-Identifier: MIT
#include "mesh/parallel.hpp"

#include "mesh/error.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace nmm {

int available_cores() {
  int cores = 1;
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) == 0)
    cores = std::max(1, CPU_COUNT(&set));
  // cgroup v2: "max 100000" (no quota) or "<quota> <period>" in microseconds.
  std::ifstream cpu_max("/sys/fs/cgroup/cpu.max");
  std::string quota;
  double period = 0.0;
  if (cpu_max >> quota >> period && quota != "max" && period > 0.0) {
    try {
      const double allowed = std::stod(quota) / period;
      cores = std::min(cores, std::max(1, static_cast<int>(std::ceil(allowed))));
    } catch (const std::exception&) {
      // An unreadable quota leaves the affinity count in force.
    }
  }
  return cores;
}

namespace {
std::atomic<int> workers{0}; // 0: not set, available_cores()
} // namespace

int worker_threads() {
  const int set = workers.load(std::memory_order_relaxed);
  if (set > 0)
    return set;
  static const int cores = available_cores();
  return cores;
}

void set_worker_threads(int n) {
  NMM_ASSERT(n >= 1, "thread count must be positive");
  workers.store(n, std::memory_order_relaxed);
}

// Threads are started for each call and joined before it returns: the loops it serves take
// milliseconds (a step's contact kinematics, a product with a matrix of a million entries),
// against tens of microseconds to start a thread, and nothing outlives the call.
void parallel_for(std::size_t n,
                  std::size_t min_chunk,
                  const std::function<void(std::size_t, std::size_t, int)>& body) {
  const std::size_t most = std::max<std::size_t>(1, n / std::max<std::size_t>(1, min_chunk));
  const auto chunks =
      static_cast<int>(std::min<std::size_t>(static_cast<std::size_t>(worker_threads()), most));
  if (chunks <= 1 || n / 2 < min_chunk) { // (n / 2: no overflow for any min_chunk)
    if (n > 0)
      body(0, n, 0);
    return;
  }
  std::vector<std::exception_ptr> failed(static_cast<std::size_t>(chunks));
  auto run = [&](int c) {
    const std::size_t first = n * static_cast<std::size_t>(c) / static_cast<std::size_t>(chunks);
    const std::size_t last = n * static_cast<std::size_t>(c + 1) / static_cast<std::size_t>(chunks);
    try {
      body(first, last, c);
    } catch (...) {
      failed[static_cast<std::size_t>(c)] = std::current_exception();
    }
  };
  {
    std::vector<std::jthread> threads;
    threads.reserve(static_cast<std::size_t>(chunks) - 1);
    for (int c = 1; c < chunks; ++c)
      threads.emplace_back(run, c);
    run(0);
  } // joined
  for (const std::exception_ptr& e : failed) {
    if (e)
      std::rethrow_exception(e);
  }
}

} // namespace nmm
