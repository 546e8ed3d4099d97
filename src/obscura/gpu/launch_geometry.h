#pragma once
// How many thread blocks of how many threads a kernel over `items`
// independent items is launched with (docs/gpu.md). The kernels loop over
// their items with a grid stride (item += blocks · threads), so any item count
// fits a grid of at most max_blocks blocks; the block count is the fewest that
// give every thread at most one item when that fits. Host code only; tested
// on the CPU (tests/gpu/launch_geometry_test.cpp).
#include <algorithm>
#include <cstdint>

namespace obscura {

struct LaunchGeometry {
  std::uint32_t blocks = 0;   // 0: nothing to launch
  std::uint32_t threads = 0;  // per block
};

// Threads per block for the march and sun kernels: double-precision
// marches with many live registers, so blocks of 128 (4 warps) let the
// scheduler fill a multiprocessor with several blocks.
inline constexpr std::uint32_t kThreadsPerBlock = 128;
// CUDA's limit on a one-dimensional grid (blocks along x).
inline constexpr std::uint32_t kMaxGridBlocks = 2147483647u;

constexpr LaunchGeometry launch_geometry(std::uint64_t items,
                                         std::uint32_t threads = kThreadsPerBlock,
                                         std::uint32_t max_blocks = kMaxGridBlocks) {
  if (items == 0 || threads == 0 || max_blocks == 0) return {};
  const std::uint64_t needed = (items + threads - 1) / threads;
  return {static_cast<std::uint32_t>(std::min<std::uint64_t>(needed, max_blocks)), threads};
}

// The items thread `thread` of a grid of `geometry` runs: thread,
// thread + stride, … below `items` (what the kernels' loop does).
constexpr std::uint64_t items_of_thread(const LaunchGeometry& geometry, std::uint64_t thread,
                                        std::uint64_t items) {
  const std::uint64_t stride = static_cast<std::uint64_t>(geometry.blocks) * geometry.threads;
  return thread >= items || stride == 0 ? 0 : (items - thread + stride - 1) / stride;
}

}  // namespace obscura
