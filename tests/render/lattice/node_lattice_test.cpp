// The radiance cache's lattice (render/lattice/node_lattice.h): where
// its nodes are, how a point finds its eight, and which blocks exist.
#include "obscura/render/lattice/node_lattice.h"

#include <gtest/gtest.h>

#include <cmath>

#include "medium/test_grids.h"
#include "obscura/core/error.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

std::shared_ptr<HomogeneousMedium> box(const BBox3& b) {
  return std::make_shared<HomogeneousMedium>(b, std::vector<double>{1.0}, std::vector<double>{0.1},
                                             std::vector<double>{1.0}, std::vector<double>{0.0},
                                             300.0);
}

TEST(NodeLattice, AtAGridsVoxelSizeItsNodesAreTheVoxelCentres) {
  const Mat3 r = rotation_from_euler_deg({0, 0, 30});
  auto grid = testing::random_grid({10, 9, 4}, 1, 3, r);
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  EXPECT_DOUBLE_EQ(lattice.spacing_m(), 0.37);
  EXPECT_EQ(lattice.dims()[0], 12);  // the voxels plus a rim node each side
  EXPECT_EQ(lattice.dims()[2], 6);
  const GridPlacement& p = grid->placement();
  // Node (1, 1, 1) is the centre of voxel (0, 0, 0).
  const Vec3 centre = p.origin_m + r * Vec3(0.5, 0.5, 0.5) * p.voxel_size_m;
  const Vec3 u = lattice.to_lattice(centre);
  EXPECT_NEAR(u.x, 1.0, 1e-12);
  EXPECT_NEAR(u.y, 1.0, 1e-12);
  EXPECT_NEAR(u.z, 1.0, 1e-12);
}

TEST(NodeLattice, CornerWeightsReproduceLinearFields) {
  const auto medium = box(BBox3({0, 0, 0}, {2, 1, 1}));
  const NodeLattice lattice(*medium, 0.25, 0.0, 1u << 30);
  Rng rng(3, 0);
  for (int i = 0; i < 200; ++i) {
    const Vec3 p(2 * rng.uniform(), rng.uniform(), rng.uniform());
    std::array<std::size_t, 8> slot;
    std::array<double, 8> w;
    ASSERT_TRUE(lattice.corners(p, slot, w));
    double sum = 0, x = 0;
    for (int c = 0; c < 8; ++c) {
      ASSERT_NE(slot[c], NodeLattice::kNoSlot);
      sum += w[c];
      x += w[c] * lattice.slot_position(slot[c]).x;
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    EXPECT_NEAR(x, p.x, 1e-12);
  }
  std::array<std::size_t, 8> slot;
  std::array<double, 8> w;
  EXPECT_FALSE(lattice.corners(Vec3(2.3, 0.5, 0.5), slot, w));
  EXPECT_TRUE(lattice.corners(Vec3(2.0, 1.0, 1.0), slot, w));  // the far corner
}

// A box's faces lie on the lattice's first and last node planes, and a point
// on one (a camera ray's entry) may come out of to_lattice a rounding error
// outside: it still finds its corners, on the plane. (It found none, and the
// cache's march read no light at the entry of every such ray: a conservative
// box, 1.25 mean free paths per cell, seen face-on under a uniform sky read
// −1.35 % instead of the sky; docs/validation.md.) A point clearly outside
// does not.
TEST(NodeLattice, APointARoundingErrorOutsideAFaceIsOnIt) {
  const auto medium = box(BBox3({-5, -5, 0}, {5, 5, 2}));
  const NodeLattice lattice(*medium, 0.3125, 0.0, 1u << 30);
  std::array<std::size_t, 8> slot;
  std::array<double, 8> w;
  for (const Vec3& p : {Vec3(0.3, std::nextafter(-5.0, -6.0), 1.0),
                        Vec3(std::nextafter(5.0, 6.0), 0.3, 1.0), Vec3(0.3, 0.2, -1e-12)}) {
    ASSERT_TRUE(lattice.corners(p, slot, w)) << p.x << " " << p.y << " " << p.z;
    double sum = 0;
    for (int c = 0; c < 8; ++c) sum += w[c];
    EXPECT_NEAR(sum, 1.0, 1e-12);
  }
  EXPECT_FALSE(lattice.corners(Vec3(0.3, -5.001, 1.0), slot, w));
  EXPECT_FALSE(lattice.corners(Vec3(0.3, 0.2, -1e-6), slot, w));
}

TEST(NodeLattice, PeriodicLatticeWrapsSideways) {
  const auto slab = box(BBox3({-1e3, -1e3, 0}, {1e3, 1e3, 1}));
  const NodeLattice lattice(*slab, 0.1, 1.0, 1u << 30);
  EXPECT_TRUE(lattice.periodic());
  EXPECT_EQ(lattice.dims()[0], 10);
  EXPECT_EQ(lattice.slot_of(-1, 3, 2), lattice.slot_of(9, 3, 2));
  EXPECT_EQ(lattice.slot_of(10, 13, 2), lattice.slot_of(0, 3, 2));
  EXPECT_EQ(lattice.slot_of(0, 0, -1), NodeLattice::kNoSlot);  // not in z
  std::array<std::size_t, 8> slot;
  std::array<double, 8> w;
  EXPECT_TRUE(lattice.corners(Vec3(57.31, -8.02, 0.5), slot, w));
}

// corners() finds each axis's two nodes once (not per corner, through
// slot_of's wraps): its slots are slot_of's for the eight nodes around the
// point, on a periodic slab (points far outside the period, either side)
// and on a lattice with missing blocks (slots kNoSlot where slot_of has none).
TEST(NodeLattice, CornersAreSlotOfTheEightNodesAround) {
  const auto slab = box(BBox3({-1e3, -1e3, 0}, {1e3, 1e3, 1}));
  const NodeLattice periodic(*slab, 0.1, 1.0, 1u << 30);
  GridPlacement place;
  place.voxel_size_m = 0.1;
  auto grid = std::make_shared<VoxelGrid>(GridDims{40, 30, 20}, place, std::vector<double>{1.0});
  grid->sigma_s(0)[grid->index(2, 3, 1)] = 1.0f;
  grid->sigma_s(0)[grid->index(37, 28, 18)] = 1.0f;
  const GridMedium sparse_medium(grid);
  const NodeLattice sparse(sparse_medium, 0.0, 0.0, 1u << 30);
  ASSERT_LT(sparse.block_count(), 27u);  // some blocks are missing
  Rng rng(5, 0);
  int missing = 0;
  for (const NodeLattice* lattice : {&periodic, &sparse}) {
    const BBox3 b = lattice == &periodic ? BBox3({-7, -9, 0}, {7, 9, 1}) : grid->world_bounds();
    for (int n = 0; n < 4000; ++n) {
      const Vec3 e = b.extent();
      const Vec3 p = b.lo + Vec3(e.x * rng.uniform(), e.y * rng.uniform(), e.z * rng.uniform());
      std::array<std::size_t, 8> slot;
      std::array<double, 8> w;
      if (!lattice->corners(p, slot, w)) continue;
      const Vec3 u = lattice->to_lattice(p);
      int i0[3];
      for (int a = 0; a < 3; ++a) {
        i0[a] = static_cast<int>(std::floor(u[a]));
        if (!(lattice->periodic() && a < 2) && i0[a] == lattice->dims()[a] - 1) --i0[a];
      }
      for (int c = 0; c < 8; ++c) {
        EXPECT_EQ(slot[c],
                  lattice->slot_of(i0[0] + (c & 1), i0[1] + (c >> 1 & 1), i0[2] + (c >> 2 & 1)))
            << n << " corner " << c;
        missing += slot[c] == NodeLattice::kNoSlot;
      }
    }
  }
  EXPECT_GT(missing, 100);
}

TEST(NodeLattice, BlocksExistOnlyNearTheMedium) {
  // A grid that is empty except one voxel in a corner: one block of 8³ nodes
  // (and its neighbours reaching it) instead of all of them.
  GridPlacement p;
  p.voxel_size_m = 0.1;
  auto grid = std::make_shared<VoxelGrid>(GridDims{64, 64, 64}, p, std::vector<double>{1.0});
  grid->sigma_s(0)[0] = 1.0f;
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  EXPECT_LE(lattice.block_count(), 8u);
  EXPECT_GE(lattice.block_count(), 1u);
  EXPECT_NE(lattice.slot_of(1, 1, 1), NodeLattice::kNoSlot);
  EXPECT_EQ(lattice.slot_of(40, 40, 40), NodeLattice::kNoSlot);
}

TEST(NodeLattice, RefusesMoreNodesThanItMayHold) {
  const auto medium = box(BBox3({0, 0, 0}, {10, 10, 10}));
  try {
    const NodeLattice lattice(*medium, 0.01, 0.0, 1000000);
    ADD_FAILURE() << "a 10⁹-node lattice was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "render/radiance_cache/voxel_m");
  }
}

}  // namespace
}  // namespace obscura
