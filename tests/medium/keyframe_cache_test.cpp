#include "obscura/medium/keyframe_cache.h"

#include <gtest/gtest.h>

#include <map>

namespace obscura {
namespace {

// A loader that counts how often each file is read and how many grids it has
// handed out that are still alive.
struct CountingLoader {
  std::map<std::string, int> reads;
  std::shared_ptr<int> alive = std::make_shared<int>(0);
  KeyframeCache::Loader loader() {
    return [this](const std::filesystem::path& p) {
      ++reads[p.string()];
      ++*alive;
      auto counter = alive;
      return std::shared_ptr<const VoxelGrid>(new VoxelGrid({1, 1, 1}, {}, {10.0}),
                                              [counter](const VoxelGrid* g) {
                                                --*counter;
                                                delete g;
                                              });
    };
  }
};

TEST(KeyframeCache, KeepsAtMostCapacityAndReusesRecentOnes) {
  CountingLoader counting;
  KeyframeCache cache(2, counting.loader());
  cache.get("a");
  cache.get("b");
  cache.get("a");  // hit
  EXPECT_EQ(counting.reads["a"], 1);
  EXPECT_EQ(cache.hits(), 1u);
  cache.get("c");  // evicts b, the least recently used
  EXPECT_EQ(cache.resident(), 2u);
  EXPECT_EQ(*counting.alive, 2);
  cache.get("a");
  EXPECT_EQ(counting.reads["a"], 1);
  cache.get("b");
  EXPECT_EQ(counting.reads["b"], 2);
  EXPECT_EQ(cache.loads(), 4u);
}

TEST(KeyframeCache, SweepingALongSequenceKeepsMemoryBounded) {
  CountingLoader counting;
  KeyframeCache cache(3, counting.loader());
  int peak = 0;
  for (int k = 0; k + 1 < 200; ++k) {
    auto a = cache.get("k" + std::to_string(k));
    auto b = cache.get("k" + std::to_string(k + 1));
    peak = std::max(peak, *counting.alive);
  }
  EXPECT_LE(peak, 3);
  EXPECT_EQ(cache.loads(), 200u);  // each keyframe read once
}

}  // namespace
}  // namespace obscura
