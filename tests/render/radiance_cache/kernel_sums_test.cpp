// The kernels' σs sums by three 1-D passes (render/radiance_cache/
// kernel_sums.h) equal the sums over every neighbour, with the lattice's
// edges, blocks it does not hold, kernels of radius 1 and 2, two samples and
// either thread count.
#include "obscura/render/radiance_cache/kernel_sums.h"

#include <gtest/gtest.h>

#include <cmath>

#include "medium/test_grids.h"
#include "obscura/core/rng.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

TEST(KernelSums, EqualTheSumOverEveryNeighbour) {
  // A grid whose voxels beyond x ≥ 20 are empty: the lattice leaves blocks out.
  auto grid = testing::random_grid({37, 11, 14}, 2, 9);
  for (int z = 0; z < 14; ++z)
    for (int y = 0; y < 11; ++y)
      for (int x = 20; x < 37; ++x)
        for (int s = 0; s < 2; ++s) {
          grid->sigma_a(s)[grid->index(x, y, z)] = 0.0f;
          grid->sigma_s(s)[grid->index(x, y, z)] = 0.0f;
        }
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  ASSERT_TRUE(kernel_sums_fit(lattice));
  const std::array<int, 3>& n = lattice.dims();
  int absent = 0;
  for (int z = 0; z < lattice.block_dims()[2]; ++z)
    for (int y = 0; y < lattice.block_dims()[1]; ++y)
      for (int x = 0; x < lattice.block_dims()[0]; ++x)
        absent += lattice.block_first_slot(x, y, z) == NodeLattice::kNoSlot;
  ASSERT_GT(absent, 0);
  constexpr int kSamples = 2;
  Rng rng(4, 0);
  std::vector<float> sigma_s(lattice.slot_count() * kSamples);
  for (float& v : sigma_s) v = static_cast<float>(rng.uniform());
  for (const int r : {1, 2}) {
    const std::size_t span = 2 * static_cast<std::size_t>(r) + 1;
    std::array<AxisOverlaps, 3> axes;
    for (int a = 0; a < 3; ++a)
      for (int i = 0; i < n[a] * static_cast<int>(span); ++i) {
        axes[a].weight.push_back(rng.uniform());
        axes[a].moment.push_back(rng.uniform() - 0.5);
      }
    std::vector<float> by_passes(lattice.slot_count() * kSamples * 4, 0.0f);
    kernel_sums(lattice, r, axes, sigma_s, kSamples, 2, by_passes);
    std::vector<float> one_thread(by_passes.size(), 0.0f);
    kernel_sums(lattice, r, axes, sigma_s, kSamples, 1, one_thread);
    EXPECT_EQ(one_thread, by_passes);  // bit for bit
    int checked = 0;
    for (std::size_t slot = 0; slot < lattice.slot_count(); ++slot) {
      if (!lattice.slot_inside(slot)) continue;
      const std::array<int, 3> at = lattice.slot_node(slot);
      for (int k = 0; k < kSamples; ++k) {
        double sum[4] = {0, 0, 0, 0};
        for (int dz = -r; dz <= r; ++dz)
          for (int dy = -r; dy <= r; ++dy)
            for (int dx = -r; dx <= r; ++dx) {
              const std::size_t m = lattice.slot_of(at[0] + dx, at[1] + dy, at[2] + dz);
              if (m == NodeLattice::kNoSlot) continue;
              const double s = sigma_s[m * kSamples + k];
              const std::size_t ix = at[0] * span + (dx + r), iy = at[1] * span + (dy + r),
                                iz = at[2] * span + (dz + r);
              const double ox = axes[0].weight[ix], oy = axes[1].weight[iy],
                           oz = axes[2].weight[iz];
              sum[0] += ox * oy * oz * s;
              sum[1] += axes[0].moment[ix] * oy * oz * s;
              sum[2] += ox * axes[1].moment[iy] * oz * s;
              sum[3] += ox * oy * axes[2].moment[iz] * s;
            }
        for (int q = 0; q < 4; ++q)
          ASSERT_NEAR(by_passes[(slot * kSamples + k) * 4 + q], sum[q],
                      1e-5 * (1.0 + std::abs(sum[q])))
              << "slot " << slot << " sample " << k << " value " << q << " radius " << r;
        ++checked;
      }
    }
    EXPECT_GT(checked, 5000);
  }
}

TEST(KernelSums, ASparseLatticesBoxDoesNotFit) {
  // Two small clouds far apart: the lattice's box is mostly blocks it does
  // not hold, so the passes' dense arrays would not fit.
  auto grid = testing::random_grid({200, 16, 16}, 1, 3);
  for (int z = 0; z < 16; ++z)
    for (int y = 0; y < 16; ++y)
      for (int x = 8; x < 192; ++x) {
        grid->sigma_a(0)[grid->index(x, y, z)] = 0.0f;
        grid->sigma_s(0)[grid->index(x, y, z)] = 0.0f;
      }
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  EXPECT_FALSE(kernel_sums_fit(lattice))
      << lattice.slot_count() << " slots, box " << lattice.dims()[0] << " " << lattice.dims()[1]
      << " " << lattice.dims()[2];
}

}  // namespace
}  // namespace obscura
