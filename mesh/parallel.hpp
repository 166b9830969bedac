// SPDX-License-Identifier: MIT
// mesh/parallel.hpp — a loop over index ranges on the machine's cores.
#pragma once

#include <cstddef>
#include <functional>

namespace nmm {

/// Cores this process may really use: the CPU affinity mask, further limited by a cgroup
/// CPU quota when one is set (a container may see more CPUs than it may run on).
[[nodiscard]] int available_cores();

/// The number of threads parallel_for() runs on: the last set_worker_threads(), else
/// available_cores().
[[nodiscard]] int worker_threads();

/// Sets worker_threads() (`nmm --threads N`, through limit_threads()). @pre n >= 1.
void set_worker_threads(int n);

/// Calls body(first, last, chunk) for contiguous chunks [first, last) that cover [0, n) in
/// order, chunk = 0, 1, ... (at most worker_threads() chunks, none under min_chunk indices):
/// each on its own thread when n is at least 2 * min_chunk, else once, on this thread, as
/// body(0, n, 0). Each chunk runs on one
/// thread; when body writes only what belongs to its indices (and per-chunk scratch), the
/// results do not depend on the number of threads. An exception thrown by a chunk is rethrown
/// here once every chunk has ended (that of the first chunk that threw).
void parallel_for(std::size_t n,
                  std::size_t min_chunk,
                  const std::function<void(std::size_t, std::size_t, int)>& body);

} // namespace nmm
