// The kernels' launch geometry (gpu/launch_geometry.h), on the CPU: every
// item goes to exactly one thread of the grid-stride loop, the block count is
// the fewest that give each thread one item, and it stays within CUDA's grid
// limit for any item count.
#include "obscura/gpu/launch_geometry.h"

#include <gtest/gtest.h>

#include <vector>

namespace obscura {
namespace {

TEST(LaunchGeometry, EveryItemGoesToExactlyOneThread) {
  for (const std::uint64_t items : {1ull, 127ull, 128ull, 129ull, 1000ull, 4097ull})
    for (const std::uint32_t max_blocks : {1u, 3u, kMaxGridBlocks}) {
      const LaunchGeometry g = launch_geometry(items, 128, max_blocks);
      const std::uint64_t threads = static_cast<std::uint64_t>(g.blocks) * g.threads;
      // The kernels' loop, item = thread, thread + stride, …
      std::vector<int> seen(items, 0);
      std::uint64_t counted = 0;
      for (std::uint64_t t = 0; t < threads; ++t) {
        for (std::uint64_t item = t; item < items; item += threads) ++seen[item];
        counted += items_of_thread(g, t, items);
      }
      for (const int s : seen) ASSERT_EQ(s, 1) << items << " items, " << max_blocks << " blocks";
      EXPECT_EQ(counted, items);
    }
}

TEST(LaunchGeometry, TheFewestBlocksThatGiveEachThreadOneItem) {
  EXPECT_EQ(launch_geometry(1).blocks, 1u);
  EXPECT_EQ(launch_geometry(1).threads, kThreadsPerBlock);
  EXPECT_EQ(launch_geometry(kThreadsPerBlock).blocks, 1u);
  EXPECT_EQ(launch_geometry(kThreadsPerBlock + 1).blocks, 2u);
  // The demo frame's largest march: 1024 × 512 rays at 2 nodes.
  EXPECT_EQ(launch_geometry(1024ull * 512 * 2).blocks, 1024u * 512 * 2 / kThreadsPerBlock);
  EXPECT_EQ(launch_geometry(0).blocks, 0u);  // nothing to launch
}

TEST(LaunchGeometry, ManyItemsStayWithinTheGridLimit) {
  // 2^40 items: more than 2^31 − 1 blocks of 128 threads could hold one each.
  const std::uint64_t items = 1ull << 40;
  const LaunchGeometry g = launch_geometry(items);
  EXPECT_EQ(g.blocks, kMaxGridBlocks);
  const std::uint64_t threads = static_cast<std::uint64_t>(g.blocks) * g.threads;
  EXPECT_EQ(items_of_thread(g, 0, items), (items + threads - 1) / threads);
  EXPECT_EQ(items_of_thread(g, threads - 1, items), items / threads);
  EXPECT_EQ(items_of_thread(g, items, items), 0u);
}

}  // namespace
}  // namespace obscura
