// The march's view of a lattice (render/lattice/lattice_view.h) places points
// and finds blocks exactly as its NodeLattice does.
#include "obscura/render/lattice/lattice_view.h"

#include <gtest/gtest.h>

#include "medium/test_grids.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/lattice/lattice_volume.h"

namespace obscura {
namespace {

TEST(LatticeView, PlacesPointsAndFindsBlocksAsItsLattice) {
  const auto grid = testing::random_grid({21, 9, 17}, 1, 3, rotation_from_euler_deg({20, -35, 70}));
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  const LatticeVolume volume(lattice, {SpectralLerp{}}, record::kMediumStride, grid.get(), 1, "t");
  const LatticeView view = volume.view();
  Rng rng(2, 0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p(20 * rng.uniform() - 10, 20 * rng.uniform() - 10, 20 * rng.uniform() - 10);
    EXPECT_EQ(view.to_lattice(p), lattice.to_lattice(p));  // bit for bit
    EXPECT_EQ(view.to_lattice_direction(p), lattice.to_lattice_direction(p));
  }
  const std::array<int, 3>& b = lattice.block_dims();
  for (int z = 0; z < b[2]; ++z)
    for (int y = 0; y < b[1]; ++y)
      for (int x = 0; x < b[0]; ++x)
        EXPECT_EQ(view.block_first_slot(x, y, z), lattice.block_first_slot(x, y, z));
  EXPECT_EQ(view.zero_slot, volume.zero_slot());
  EXPECT_EQ(view.occupied, volume.occupied());
  EXPECT_EQ(view.domain.lo, volume.domain().lo);
  EXPECT_EQ(view.domain.hi, volume.domain().hi);
  for (int a = 0; a < 3; ++a) EXPECT_EQ(view.dims[a], lattice.dims()[a]);
}

}  // namespace
}  // namespace obscura
