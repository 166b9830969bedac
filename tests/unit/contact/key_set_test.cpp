// SPDX-License-Identifier: MIT
#include "contact/key_set.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>
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

TEST(KeyIndex, HoldsWhatAStandardMapHoldsThroughGrowthAndClearing) {
  // The same keys as above, each with a value: the first insert of a key sets it, a repeat
  // keeps it (as std::unordered_map::insert does); cleared, the table holds nothing and is
  // filled again the same way.
  std::mt19937_64 random(11);
  std::uniform_int_distribution<std::uint32_t> index(0, 3000);
  KeyIndex keys;
  for (int round = 0; round < 2; ++round) {
    std::unordered_map<std::uint64_t, int> reference;
    for (int k = 0; k < 20000; ++k) {
      const std::uint64_t key = static_cast<std::uint64_t>(index(random)) << 32U | index(random);
      ASSERT_EQ(keys.insert(key, k), reference.insert({key, k}).second) << k;
    }
    EXPECT_EQ(keys.size(), reference.size());
    for (const auto& [key, value] : reference)
      ASSERT_EQ(keys.find(key), value);
    for (int k = 0; k < 20000; ++k) {
      const std::uint64_t key = static_cast<std::uint64_t>(index(random)) << 32U | index(random);
      const auto it = reference.find(key);
      ASSERT_EQ(keys.find(key), it == reference.end() ? KeyIndex::none : it->second) << k;
    }
    keys.clear();
    EXPECT_EQ(keys.size(), 0U);
    for (const auto& [key, value] : reference)
      ASSERT_EQ(keys.find(key), KeyIndex::none);
  }
  EXPECT_EQ(KeyIndex().find(0), KeyIndex::none); // a new table
}

TEST(KeySet, ManyKeysWithOneHighPartAndNeighbouringIndicesStayExact) {
  // The table starts a key's probe near those of its neighbouring high parts; 20,000 keys with
  // one high part (one edge against every vertex of a long row) make a run far beyond the 64
  // probes after which it scatters them: every answer stays std::unordered_set's, for them
  // and for the keys of dense neighbouring indices (pairs, and contact keys: slave << 33).
  KeySet keys;
  std::unordered_set<std::uint64_t> reference;
  auto both = [&](std::uint64_t key) { ASSERT_EQ(keys.insert(key), reference.insert(key).second); };
  for (std::uint64_t v = 0; v < 2000; ++v) {
    for (std::uint64_t w = v + 1; w < v + 4; ++w)
      both(v << 32U | w);
    both(v << 33U | (v + 7) << 1U | 1U);
  }
  EXPECT_FALSE(keys.scattered()); // neighbouring indices make no long runs
  for (std::uint64_t k = 0; k < 20000; ++k)
    both(std::uint64_t{5} << 32U | (k * 7919U % 100000U));
  EXPECT_TRUE(keys.scattered());
  EXPECT_EQ(keys.size(), reference.size());
  for (const std::uint64_t key : reference)
    ASSERT_TRUE(keys.contains(key));
  for (std::uint64_t v = 0; v < 2000; ++v)
    ASSERT_EQ(keys.contains(v << 32U | (v + 5)), reference.count(v << 32U | (v + 5)) != 0);
}

TEST(KeyIndex, KeepsItsValuesWhenTheTableScattersItsKeys) {
  // A run of 1,000 keys with one high part turns the table to the scattering hash half way
  // through; the values inserted before and after are all found.
  KeyIndex keys;
  for (int k = 0; k < 1000; ++k)
    ASSERT_TRUE(keys.insert(std::uint64_t{3} << 32U | static_cast<std::uint64_t>(k), k));
  EXPECT_TRUE(keys.scattered());
  for (int k = 0; k < 1000; ++k)
    ASSERT_EQ(keys.find(std::uint64_t{3} << 32U | static_cast<std::uint64_t>(k)), k);
  EXPECT_EQ(keys.find(std::uint64_t{4} << 32U), KeyIndex::none);
}

} // namespace
} // namespace nmm
