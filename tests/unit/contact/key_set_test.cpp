// SPDX-License-Identifier: MIT
#include "contact/key_set.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_set>

namespace nmm {
namespace {

TEST(KeySet, HoldsWhatAStandardSetHoldsThroughGrowth) {
  // Keys shaped like the detection's (two indices in fixed bit fields), many repeated, from
  // an empty table of 16 slots through ten doublings: every insert answers as
  // std::unordered_set does, and so does every lookup of a key in or out.
  std::mt19937_64 random(7);
  std::uniform_int_distribution<std::uint32_t> index(0, 3000);
  KeySet keys;
  std::unordered_set<std::uint64_t> reference;
  for (int k = 0; k < 20000; ++k) {
    const std::uint64_t key = static_cast<std::uint64_t>(index(random)) << 32U | index(random);
    ASSERT_EQ(keys.insert(key), reference.insert(key).second) << k;
  }
  EXPECT_EQ(keys.size(), reference.size());
  for (int k = 0; k < 20000; ++k) {
    const std::uint64_t key = static_cast<std::uint64_t>(index(random)) << 32U | index(random);
    ASSERT_EQ(keys.contains(key), reference.count(key) != 0) << k;
  }
  for (const std::uint64_t key : reference)
    ASSERT_TRUE(keys.contains(key));
}

TEST(KeySet, AReservedSetTakesItsKeysAndKeyZero) {
  KeySet keys(1000);
  EXPECT_FALSE(keys.contains(0));
  EXPECT_TRUE(keys.insert(0));
  EXPECT_FALSE(keys.insert(0));
  EXPECT_TRUE(keys.contains(0));
  for (std::uint64_t key = 1; key <= 1000; ++key)
    EXPECT_TRUE(keys.insert(key << 33U));
  EXPECT_EQ(keys.size(), 1001U);
}

} // namespace
} // namespace nmm
