// The box of cells whose light a radiance cache makes for pinhole sensors
// (light_region.h): every cell a camera ray can cross lies in it, at least
// the margin inside where the lattice does not clip it, and a narrow view
// of a wide cloud keeps a small part of the lattice.
#include "obscura/render/radiance_cache/light_region.h"

#include <gtest/gtest.h>

#include "medium/test_grids.h"
#include "obscura/core/rng.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/lattice_walker.h"

namespace obscura {
namespace {

TEST(LightRegion, EveryCellACameraRayCrossesIsInsideTheMargin) {
  const GridMedium medium(
      testing::random_grid({72, 24, 12}, 1, 5, rotation_from_euler_deg({5, 0, 10})));
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  const Vec3 c = medium.bounds().center();
  const CellBox all = all_cells(lattice);
  for (const double fov_deg : {3.0, 8.0}) {
    for (const Vec3& from : {Vec3{-3, -40, 1}, Vec3{30, -25, 6}, Vec3{-2, 0.5, 30}}) {
      const PinholeCamera camera(c + from, c + Vec3{-3, 0, 0}, {0.3, 0, 1}, fov_deg, 32, 20);
      constexpr int kMargin = 3;
      const CellBox box = cells_in_view(lattice, {&camera}, kMargin);
      ASSERT_FALSE(box.empty());
      // Head-on, the view is a small part of the cloud's width.
      if (from.y < -39 && fov_deg < 5) {
        EXPECT_LT(box.count(), all.count() / 2) << "fov " << fov_deg;
      }
      EXPECT_LT(box.count(), all.count()) << "fov " << fov_deg;
      // Rays through random image points, walked through the lattice's
      // cells (those with a held block: the others hold no light).
      Rng rng(3, 0);
      int crossed = 0;
      for (int i = 0; i < 4000; ++i) {
        const double x = i < 4 ? (i & 1) * 32.0 : 32.0 * rng.uniform();
        const double y = i < 4 ? (i >> 1) * 20.0 : 20.0 * rng.uniform();
        const Ray ray = camera.generate_ray(x, y);
        const Vec3 o = lattice.to_lattice(ray.origin),
                   d = lattice.to_lattice_direction(ray.direction);
        double t0 = 0, t1 = 1e3;
        const BBox3 cells_box({0, 0, 0}, {all.hi[0] + 1.0, all.hi[1] + 1.0, all.hi[2] + 1.0});
        if (!cells_box.intersect(Ray{o, d}, t0, t1)) continue;
        LatticeWalker walker(o, d, t0, t1, 1.0, all.lo, all.hi);
        std::array<int, 3> cell;
        double ta, tb;
        while (walker.next(cell, ta, tb)) {
          if (!(tb > ta)) continue;
          if (lattice.block_first_slot(cell[0] / 8, cell[1] / 8, cell[2] / 8) ==
              NodeLattice::kNoSlot)
            continue;
          ++crossed;
          for (int a = 0; a < 3; ++a) {
            EXPECT_GE(cell[a], box.lo[a] == all.lo[a] ? all.lo[a] : box.lo[a] + kMargin)
                << "axis " << a;
            EXPECT_LE(cell[a], box.hi[a] == all.hi[a] ? all.hi[a] : box.hi[a] - kMargin)
                << "axis " << a;
          }
        }
      }
      EXPECT_GT(crossed, 1000);
    }
  }
}

TEST(LightRegion, NoCameraNoCellsAndAPeriodicLatticeAll) {
  const GridMedium medium(testing::random_grid({20, 20, 6}, 1, 5));
  const NodeLattice lattice(medium, 0.0, 0.0, 1u << 30);
  EXPECT_TRUE(cells_in_view(lattice, {}, 2).empty());
  // Looking away from the cloud.
  const Vec3 c = medium.bounds().center();
  const PinholeCamera away(c + Vec3{0, -40, 0}, c + Vec3{0, -80, 0}, {0, 0, 1}, 10.0, 8, 8);
  EXPECT_TRUE(cells_in_view(lattice, {&away}, 2).empty());
  const NodeLattice periodic(medium, 0.0, 2.0, 1u << 30);
  const CellBox all = all_cells(periodic);
  const CellBox box = cells_in_view(periodic, {&away}, 2);
  EXPECT_EQ(box.lo, all.lo);
  EXPECT_EQ(box.hi, all.hi);
}

}  // namespace
}  // namespace obscura
