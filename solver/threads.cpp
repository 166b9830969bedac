// SPDX-License-Identifier: MIT
#include "solver/threads.hpp"

#include "mesh/error.hpp"

#include <cblas.h>
#include <omp.h>

#include <string>

namespace nmm {

void limit_threads(int n) {
  NMM_ASSERT(n >= 1, "thread count must be positive");
  omp_set_num_threads(n);
  // The only OpenMP regions are CHOLMOD's, with num_threads(4) compiled in (threads.hpp):
  // none active, so that they never run beside OpenBLAS's threads.
  omp_set_max_active_levels(0);
  openblas_set_num_threads(n);
  set_worker_threads(n);
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
