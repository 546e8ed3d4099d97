// The sun's optical depths by marching the frame's own records
// (gpu/sun_depth_job.h), on the CPU's threads, against the radiance cache's
// own (RadianceCache with SunDepths::kHere sums the same records' cells over
// one walk shared by all nodes, render/lattice/parallel_depths.h): the same
// cells and Simpson rule, so equal up to rounding; the other channels
// untouched.
#include "obscura/gpu/sun_depth_job.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/gpu/host_executor.h"
#include "obscura/render/radiance_cache/radiance_cache.h"
#include "support/frame_lattice.h"
#include "support/sunlit_grid.h"

namespace obscura {
namespace {

TEST(SunDepthJob, EqualsTheCachesOwnOpticalDepthsToTheSun) {
  for (const int degree : {0, 2, 3}) {
    const Scene scene = testing::sunlit_grid_scene(degree, 500);
    const SpectralNodes band(BandQuadrature(Band::flat("b", 3.2, 4.9), 3, 0.0),
                             scene.medium->wavelengths_um());
    const std::vector<SpectralNode> nodes(band.nodes());
    const RadianceCache here(scene, nodes);
    const RadianceCache by_caller(scene, nodes, single_process(),
                                  RadianceCache::SunDepths::kByCaller);
    const LatticeVolume& volume = by_caller.volume();
    HostExecutor executor(2);
    executor.load(testing::frame_of(volume, nodes, &scene));
    executor.sun_depths(scene.sun.direction());
    const int stride = volume.stride();
    const NodeLattice& lattice = by_caller.lattice();
    int deep = 0, shaded = 0;
    for (int u = 0; u < 3; ++u) {
      const std::vector<float> records = executor.records(u);
      const float* expected = here.volume().records(u);
      const float* before = volume.records(u);
      for (std::size_t slot = 0; slot < lattice.slot_count(); ++slot) {
        const float* r = records.data() + slot * stride;
        const float* e = expected + slot * stride;
        // Left for the caller: zero until the executor fills it.
        ASSERT_EQ(before[slot * stride + record::kTauSun], 0.0f);
        if (lattice.slot_inside(slot)) {
          ASSERT_NEAR(r[record::kTauSun], e[record::kTauSun],
                      2e-6 * std::abs(e[record::kTauSun]) + 1e-6)
              << "node " << u << " slot " << slot;
        } else {
          ASSERT_EQ(r[record::kTauSun], 0.0f);
        }
        deep += e[record::kTauSun] > 1.0f;
        shaded += r[record::kSunVisibility] == 0.0f;
        for (int c = 0; c < stride; ++c) {
          if (c == record::kTauSun) continue;
          ASSERT_EQ(r[c], before[slot * stride + c]) << "channel " << c;
        }
      }
    }
    EXPECT_GT(deep, 100) << "degree " << degree;  // the sun crosses real medium
    EXPECT_GT(shaded, 100);                       // the ground shades some nodes
  }
}

TEST(SunDepthJob, ASlotHoldsTheNodeOfItsBlock) {
  const Scene scene = testing::sunlit_grid_scene(1, 100);
  const NodeLattice lattice(*scene.medium, 0.0, 0.0, 1u << 30);
  const LatticeView view = lattice.view();
  for (std::size_t slot = 0; slot < lattice.slot_count(); slot += 7)
    ASSERT_EQ(slot_node(view, slot), lattice.slot_node(slot)) << "slot " << slot;
}

}  // namespace
}  // namespace obscura
