// SPDX-License-Identifier: MIT
// solver/threads.hpp — thread counts of the parallel libraries under the linear solver.
#pragma once

#include "mesh/parallel.hpp"

#include <string>

namespace nmm {

/// Caps OpenMP (CHOLMOD), OpenBLAS and nmm's own loops (parallel_for(), available_cores()
/// by default: mesh/parallel.hpp) to @p n threads. Uncapped, Debian's CHOLMOD runs 3-5x
/// slower on this 2-core machine kind (DESIGN.md "Measured facts"). OpenMP parallel regions
/// then run on one thread: the only ones are in CHOLMOD's supernodal factorisation, which
/// zeroes and scatters supernodes with num_threads(4) compiled in (CHOLMOD_OMP_NUM_THREADS,
/// beyond omp_set_num_threads()), and beside OpenBLAS's threads they oversubscribe the cores
/// (docs/benchmarks.md, "CHOLMOD threads"). @pre n >= 1.
void limit_threads(int n);

/// Threads OpenBLAS runs on now.
[[nodiscard]] int blas_threads();

/// Runs OpenBLAS and OpenMP (CHOLMOD's own loops) on one thread while it lives (then
/// restores the previous counts): for small factorizations, whose supernodes are too small
/// for a second thread to pay for waking it (docs/benchmarks.md, "CHOLMOD threads").
class SingleBlasThread {
public:
  SingleBlasThread();
  ~SingleBlasThread();
  SingleBlasThread(const SingleBlasThread&) = delete;
  SingleBlasThread& operator=(const SingleBlasThread&) = delete;
  SingleBlasThread(SingleBlasThread&&) = delete;
  SingleBlasThread& operator=(SingleBlasThread&&) = delete;

private:
  int previous_;
  int previous_levels_;
};

/// The BLAS actually linked, e.g. "OpenBLAS 0.3.21 ... (2 threads)".
[[nodiscard]] std::string blas_description();

} // namespace nmm

/// libgomp's entry to an OpenMP parallel region, defined by nmm so that it runs the region's
/// body on the calling thread at once. nmm runs every OpenMP region on one thread anyway
/// (limit_threads(), SingleBlasThread: the only ones are CHOLMOD's), but libgomp still builds a
/// team for each, with a malloc and a futex system call at its end, and CHOLMOD's supernodal
/// factorisation opens two or more regions per supernode, and for a factorisation of a few
/// hundred unknowns those system calls are a large part of its time (docs/benchmarks.md,
/// "Blocks: DDA, VEM, NMM and conjugate gradients"). The executable's definition takes precedence
/// over libgomp's for every shared library (the dynamic linker looks in the executable first). The
/// body sees the same as in an inactive region: omp_get_num_threads() 1, omp_get_thread_num() 0;
/// worksharing constructs in it run as orphaned ones, on this thread alone.
extern "C" void GOMP_parallel(void (*body)(void*), void* data, unsigned threads, unsigned flags);
