// SPDX-License-Identifier: MIT
#include "mesh/parallel.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <utility>
#include <vector>

namespace nmm {
namespace {

// The chunks of one call: (first, last, chunk) in the order they ran into the list.
std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> chunks_of(std::size_t n,
                                                                           std::size_t min_chunk) {
  std::mutex mutex;
  std::vector<std::pair<std::pair<std::size_t, std::size_t>, int>> chunks;
  parallel_for(n, min_chunk, [&](std::size_t first, std::size_t last, int chunk) {
    const std::lock_guard<std::mutex> lock(mutex);
    chunks.push_back({{first, last}, chunk});
  });
  std::sort(chunks.begin(), chunks.end(),
            [](const auto& a, const auto& b) { return a.second < b.second; });
  return chunks;
}

TEST(ParallelFor, CoversTheRangeOnceInContiguousChunksNumberedInOrder) {
  EXPECT_EQ(worker_threads(), available_cores()); // until set
  for (const std::size_t n : {1UL, 7UL, 100UL, 10007UL}) {
    const auto chunks = chunks_of(n, 1);
    ASSERT_FALSE(chunks.empty());
    EXPECT_LE(chunks.size(), static_cast<std::size_t>(worker_threads()));
    std::size_t next = 0;
    for (std::size_t c = 0; c < chunks.size(); ++c) {
      EXPECT_EQ(chunks[c].second, static_cast<int>(c));
      EXPECT_EQ(chunks[c].first.first, next); // contiguous, in chunk order
      EXPECT_LT(chunks[c].first.first, chunks[c].first.second);
      next = chunks[c].first.second;
    }
    EXPECT_EQ(next, n);
  }
  // Every index once, whatever the threads (an atomic count per index).
  std::vector<std::atomic<int>> visits(5000);
  parallel_for(visits.size(), 10, [&](std::size_t first, std::size_t last, int) {
    for (std::size_t i = first; i < last; ++i)
      ++visits[i];
  });
  for (const auto& v : visits)
    ASSERT_EQ(v.load(), 1);
}

TEST(ParallelFor, RunsOnTheThreadsItIsGiven) {
  set_worker_threads(3);
  EXPECT_EQ(worker_threads(), 3);
  EXPECT_EQ(chunks_of(300, 1).size(), 3U);   // more threads than cores: still three chunks
  EXPECT_EQ(chunks_of(300, 120).size(), 2U); // no chunk under 120
  set_worker_threads(1);
  EXPECT_EQ(chunks_of(300, 1).size(), 1U);
  set_worker_threads(available_cores());
}

TEST(ParallelFor, SmallRangesRunOnceOnTheCallingThreadAndEmptyOnesNotAtAll) {
  const std::thread::id caller = std::this_thread::get_id();
  int calls = 0;
  parallel_for(99, 50, [&](std::size_t first, std::size_t last, int chunk) {
    ++calls;
    EXPECT_EQ(std::this_thread::get_id(), caller);
    EXPECT_EQ(first, 0U);
    EXPECT_EQ(last, 99U);
    EXPECT_EQ(chunk, 0);
  });
  EXPECT_EQ(calls, 1);
  parallel_for(0, 1, [&](std::size_t, std::size_t, int) { ++calls; });
  EXPECT_EQ(calls, 1);
}

TEST(ParallelFor, AnExceptionInAChunkReachesTheCallerAfterEveryChunkEnded) {
  std::atomic<int> ended{0};
  EXPECT_THROW(parallel_for(1000, 1,
                            [&](std::size_t first, std::size_t, int) {
                              ++ended;
                              if (first == 0)
                                throw std::runtime_error("chunk 0");
                            }),
               std::runtime_error);
  EXPECT_EQ(ended.load(), static_cast<int>(chunks_of(1000, 1).size()));
}

} // namespace
} // namespace nmm
