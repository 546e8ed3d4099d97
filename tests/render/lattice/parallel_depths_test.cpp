// The shared walk of parallel rays (render/lattice/parallel_depths.h): every
// node's optical depth equals its own march's (lattice_view_march.h) to the
// rounding of the cell fractions, and so does the depth from the box's point
// nearest a rim node, for directions along and between the axes,
// with blocks the lattice does not hold, several spectral nodes, and against
// the grid medium's own optical depth (the exact trilinear σt).
#include "obscura/render/lattice/parallel_depths.h"

#include <gtest/gtest.h>

#include <cmath>

#include "medium/test_grids.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/lattice/lattice_view_march.h"
#include "obscura/render/lattice/lattice_volume.h"

namespace obscura {
namespace {

// A random grid whose voxels beyond x ≥ 20 are empty, so that the lattice
// leaves whole blocks out (their nodes read the zero record).
std::shared_ptr<VoxelGrid> grid_with_a_gap(int samples) {
  auto grid =
      testing::random_grid({37, 11, 14}, samples, 5, rotation_from_euler_deg({10, -25, 40}));
  const GridDims& d = grid->dims();
  for (int z = 0; z < d.nz; ++z)
    for (int y = 0; y < d.ny; ++y)
      for (int x = 20; x < d.nx; ++x)
        for (int s = 0; s < samples; ++s) {
          grid->sigma_a(s)[grid->index(x, y, z)] = 0.0f;
          grid->sigma_s(s)[grid->index(x, y, z)] = 0.0f;
        }
  return grid;
}

TEST(ParallelDepths, EveryNodesDepthIsItsOwnMarchs) {
  constexpr int kStride = record::light_stride(9);
  const auto grid = grid_with_a_gap(2);
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  // Two spectral nodes: the grid's two samples.
  const LatticeVolume volume(lattice, {SpectralLerp{0, 0, 0.0}, SpectralLerp{1, 1, 0.0}}, kStride,
                             grid.get(), 1, "t");
  ASSERT_TRUE(volume.has_medium());
  int absent = 0;  // blocks the lattice leaves out
  for (int z = 0; z < lattice.block_dims()[2]; ++z)
    for (int y = 0; y < lattice.block_dims()[1]; ++y)
      for (int x = 0; x < lattice.block_dims()[0]; ++x)
        absent += lattice.block_first_slot(x, y, z) == LatticeView::kNoSlot;
  ASSERT_GT(absent, 0);
  const LatticeView view = volume.view();
  const float* records[2] = {volume.records(0), volume.records(1)};
  const double h = lattice.spacing_m();
  for (const Vec3& dir : {Vec3(0, 0, 1), Vec3(-1, 0, 0), Vec3(0.3, -0.5, 0.81),
                          Vec3(-0.6, 0.64, -0.48), normalize(Vec3(1, 1, 1))}) {
    const Vec3 d = view.to_lattice_direction(normalize(dir));
    const ParallelDepths parallel(view, records, 2, kStride, d);
    const ParallelDepths parallel_one(view, records, 1, kStride, d);
    EXPECT_GT(parallel.cell_count(), 0u);
    int compared = 0, rim = 0;
    double largest = 0.0;
    for (int z = 0; z < lattice.dims()[2]; ++z)
      for (int y = 0; y < lattice.dims()[1]; ++y)
        for (int x = 0; x < lattice.dims()[0]; ++x) {
          const Vec3 node(x, y, z);
          // A rim node: from the box's point nearest it, ½ from node
          // `below` along the axes it is beyond the box on.
          Vec3 from = node;
          std::array<int, 3> below = {x, y, z};
          int half = 0;
          if (rim_face(view.domain, node, from)) {
            for (int a = 0; a < 3; ++a)
              if (from[a] != node[a]) {
                half |= 1 << a;
                below[a] = static_cast<int>(std::floor(from[a]));
              }
            ++rim;
          }
          double shared[2] = {0.0, 0.0}, own[2] = {0.0, 0.0};
          parallel.add(below, half, shared);
          for (int j = 0; j < 2; ++j)
            own[j] = lattice_optical_depth<kStride>(view, records[j], Ray{from, d},
                                                    std::numeric_limits<double>::infinity());
          double one = 0.0;
          parallel_one.add(below, half, &one);
          EXPECT_EQ(one, shared[0]);  // each spectral node's sums its own
          for (int j = 0; j < 2; ++j) {
            EXPECT_NEAR(shared[j], own[j], 2e-6 * (1.0 + own[j]))
                << "node " << x << " " << y << " " << z << ", direction " << dir.x << " " << dir.y
                << " " << dir.z;
            largest = std::max(largest, own[j]);
          }
          // The grid medium's own depth, per sample in double.
          if ((x + y + z) % 7 == 0) {
            double tau[2] = {0.0, 0.0};
            medium.add_optical_depth(
                Ray{lattice.origin() + lattice.rotation() * (from * h), normalize(dir)}, 0.0,
                std::numeric_limits<double>::infinity(), tau);
            for (int j = 0; j < 2; ++j) EXPECT_NEAR(shared[j], tau[j], 2e-5 * (1.0 + tau[j]));
          }
          ++compared;
        }
    EXPECT_GT(compared, 1000);
    EXPECT_GT(rim, 500);      // the templates from the box's faces, edges and corners
    EXPECT_GT(largest, 5.0);  // rays that cross much medium
  }
}

// A node whose ray leaves the box at once (on the box's top layer, the
// direction up) has a depth of half a cell at most; a direction of zero
// length has no template.
TEST(ParallelDepths, ARayLeavingAtOnceCrossesOnlyItsCutCell) {
  const auto grid = testing::random_grid({9, 9, 9}, 1, 3);
  const GridMedium medium(grid);
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  const LatticeVolume volume(lattice, {SpectralLerp{}}, record::kMediumStride, grid.get(), 1, "t");
  const LatticeView view = volume.view();
  const float* records[1] = {volume.records(0)};
  const Vec3 up = view.to_lattice_direction(lattice.rotation() * Vec3(0, 0, 1));
  const ParallelDepths parallel(view, records, 1, record::kMediumStride, up);
  const int top = lattice.dims()[2] - 2;  // the last node inside the box
  double tau = 0.0, own = 0.0;
  parallel.add({4, 4, top}, 0, &tau);
  own = lattice_optical_depth<record::kMediumStride>(view, records[0], Ray{Vec3(4, 4, top), up},
                                                     std::numeric_limits<double>::infinity());
  EXPECT_NEAR(tau, own, 1e-6 * (1.0 + own));
  // Half a spacing of at most σa + σs ≤ 3 /m.
  EXPECT_LE(tau, 0.5 * lattice.spacing_m() * 3.0 + 1e-9);
  EXPECT_EQ(ParallelDepths(view, records, 1, record::kMediumStride, Vec3(0, 0, 0)).cell_count(),
            0u);
}

}  // namespace
}  // namespace obscura
