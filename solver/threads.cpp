// SPDX-License-Identifier: MIT
#include "solver/threads.hpp"

#include "mesh/error.hpp"

#include <cblas.h>
#include <omp.h>
#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <string>

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

void limit_threads(int n) {
  NMM_ASSERT(n >= 1, "thread count must be positive");
  omp_set_num_threads(n);
  // The only OpenMP regions are CHOLMOD's, with num_threads(4) compiled in (threads.hpp):
  // none active, so that they never run beside OpenBLAS's threads.
  omp_set_max_active_levels(0);
  openblas_set_num_threads(n);
}

int blas_threads() { return openblas_get_num_threads(); }

SingleBlasThread::SingleBlasThread()
    : previous_(openblas_get_num_threads()), previous_levels_(omp_get_max_active_levels()) {
  if (previous_ > 1)
    openblas_set_num_threads(1);
  // CHOLMOD's supernodal factorisation zeroes and scatters large supernodes in OpenMP loops
  // with num_threads(4) compiled in (CHOLMOD_OMP_NUM_THREADS), which omp_set_num_threads()
  // does not cap; no active level makes every parallel region run on this thread alone.
  omp_set_max_active_levels(0);
}

SingleBlasThread::~SingleBlasThread() {
  if (previous_ > 1)
    openblas_set_num_threads(previous_);
  omp_set_max_active_levels(previous_levels_);
}

std::string blas_description() {
  return std::string(openblas_get_config()) + " (" + std::to_string(blas_threads()) + " threads)";
}

} // namespace nmm

extern "C" void
GOMP_parallel(void (*body)(void*), void* data, unsigned /*threads*/, unsigned /*flags*/) {
  body(data);
}
