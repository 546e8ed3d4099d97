// The march's view of a lattice (render/lattice/lattice_view.h) places points
// and finds blocks exactly as its NodeLattice does; the march's trilinear
// interpolation (render/lattice/lattice_view_march.h) is trilinear.
#include "obscura/render/lattice/lattice_view.h"

#include <gtest/gtest.h>

#include "medium/test_grids.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/lattice/lattice_view_march.h"
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

// The march's two forms of the trilinear interpolation (corner weights and
// lerps, four floats at a time) against the trilinear formula in double, to
// float rounding; the weights give a corner's record exactly at that corner.
TEST(LatticeMarchInterpolation, IsTrilinearAndExactAtTheCorners) {
  constexpr int kStride = 8;
  Rng rng(7, 0);
  std::vector<float> records(8 * kStride);
  const std::array<std::size_t, 8> slot = {0, 1, 2, 3, 4, 5, 6, 7};
  for (int trial = 0; trial < 500; ++trial) {
    for (float& r : records) r = static_cast<float>(100.0 * rng.uniform() - 20.0);
    float f[3];
    for (int a = 0; a < 3; ++a)
      f[a] = trial < 8 ? static_cast<float>(trial >> a & 1) : static_cast<float>(rng.uniform());
    float out[kStride], by_lerps[kStride];
    lattice_march_detail::interpolate<kStride>(records.data(), slot,
                                               lattice_march_detail::corner_weights(f), out);
    lattice_march_detail::interpolate_lerps<kStride>(records.data(), slot, f, by_lerps);
    for (int i = 0; i < kStride; ++i) {
      double exact = 0.0;
      for (int c = 0; c < 8; ++c) {
        double w = 1.0;
        for (int a = 0; a < 3; ++a) w *= (c >> a & 1) ? f[a] : 1.0 - f[a];
        exact += w * records[c * kStride + i];
      }
      EXPECT_NEAR(out[i], exact, 1e-5 * 120.0) << "trial " << trial;
      EXPECT_NEAR(by_lerps[i], exact, 1e-5 * 120.0) << "trial " << trial;
      if (trial < 8) {
        EXPECT_EQ(out[i], records[trial * kStride + i]);
      }
    }
  }
}

// A point on a face of the cell: the face's bilinear interpolation (four
// corners) in both forms (lerps for a record of four floats, weights for
// longer ones) against the trilinear formula with the fraction across the
// face 0 or 1, for every face; the weights exact at the face's corners.
template <int Stride>
void expect_face_interpolation_is_trilinear() {
  Rng rng(11, 0);
  std::vector<float> records(8 * Stride);
  const std::array<std::size_t, 8> slot = {0, 1, 2, 3, 4, 5, 6, 7};
  for (int trial = 0; trial < 300; ++trial)
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        for (float& r : records) r = static_cast<float>(100.0 * rng.uniform() - 20.0);
        float f[3];
        for (int a = 0; a < 3; ++a)
          f[a] = trial < 8 ? static_cast<float>(trial >> a & 1) : static_cast<float>(rng.uniform());
        // The walk's fraction across the face is computed, not set: the
        // interpolation must not read it.
        f[axis] = side == 1 ? 0.99f : 0.01f;
        float out[Stride];
        lattice_march_detail::FaceInterpolation<Stride>(axis, side, f)(records.data(), slot, out);
        for (int i = 0; i < Stride; ++i) {
          double exact = 0.0;
          for (int c = 0; c < 8; ++c) {
            double w = 1.0;
            for (int a = 0; a < 3; ++a) {
              const double fa = a == axis ? side : f[a];
              w *= (c >> a & 1) ? fa : 1.0 - fa;
            }
            exact += w * records[c * Stride + i];
          }
          EXPECT_NEAR(out[i], exact, 1e-5 * 120.0)
              << "trial " << trial << " axis " << axis << " side " << side;
          if (Stride > 4 && trial < 8 && (trial >> axis & 1) == side) EXPECT_EQ(out[i], exact);
        }
      }
}

TEST(LatticeMarchInterpolation, OnAFaceIsTheFacesBilinear) {
  expect_face_interpolation_is_trilinear<4>();
  expect_face_interpolation_is_trilinear<8>();
}

}  // namespace
}  // namespace obscura
