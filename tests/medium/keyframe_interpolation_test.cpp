#include "obscura/medium/keyframe_interpolation.h"

#include <gtest/gtest.h>

#include <cstring>

#include "medium/test_grids.h"
#include "obscura/core/error.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

bool identical(const VoxelGrid& x, const VoxelGrid& y) {
  if (!(x.dims() == y.dims()) || x.channel_count() != y.channel_count()) return false;
  for (int c = 0; c < x.channel_count(); ++c)
    if (std::memcmp(x.channel(c), y.channel(c), x.dims().count() * sizeof(float)) != 0)
      return false;
  return true;
}

TEST(KeyframeInterpolation, AtKeyframeTimesTheStateIsTheKeyframe) {
  const auto a = testing::random_grid({5, 4, 3}, 2, 1);
  const auto b = testing::random_grid({5, 4, 3}, 2, 2);
  EXPECT_TRUE(identical(interpolate_keyframes(*a, *b, 0.0), *a));
  EXPECT_TRUE(identical(interpolate_keyframes(*a, *b, 1.0), *b));
}

TEST(KeyframeInterpolation, MidwayCoefficientsAreTheAverage) {
  const auto a = testing::random_grid({5, 4, 3}, 2, 1);
  const auto b = testing::random_grid({5, 4, 3}, 2, 2);
  const VoxelGrid m = interpolate_keyframes(*a, *b, 0.5);
  for (int s = 0; s < 2; ++s)
    for (std::size_t v = 0; v < 60; ++v) {
      EXPECT_EQ(m.sigma_a(s)[v],
                static_cast<float>(0.5 * a->sigma_a(s)[v] + 0.5 * b->sigma_a(s)[v]));
      EXPECT_EQ(m.sigma_s(s)[v],
                static_cast<float>(0.5 * a->sigma_s(s)[v] + 0.5 * b->sigma_s(s)[v]));
    }
}

TEST(KeyframeInterpolation, AsymmetryIsScatteringWeighted) {
  VoxelGrid a({1, 1, 1}, {}, {10.0}), b({1, 1, 1}, {}, {10.0});
  a.sigma_s(0)[0] = 0.3f;
  a.g(0)[0] = 0.8f;
  b.sigma_s(0)[0] = 0.1f;
  b.g(0)[0] = -0.4f;
  a.temperature()[0] = b.temperature()[0] = 300.0f;
  const VoxelGrid m = interpolate_keyframes(a, b, 0.25);
  const double ws_a = 0.75 * 0.3f, ws_b = 0.25 * 0.1f;
  EXPECT_NEAR(m.g(0)[0], (ws_a * 0.8f + ws_b * -0.4f) / (ws_a + ws_b), 1e-7);
}

TEST(KeyframeInterpolation, TemperatureIsLinearButEmptyVoxelsDoNotCountAsCold) {
  VoxelGrid a({2, 1, 1}, {}, {10.0}), b({2, 1, 1}, {}, {10.0});
  // Voxel 0: both hold smoke, 300 K and 340 K. Voxel 1: only b holds smoke.
  a.sigma_a(0)[0] = b.sigma_a(0)[0] = 0.5f;
  a.temperature()[0] = 300.0f;
  b.temperature()[0] = 340.0f;
  b.sigma_a(0)[1] = 0.5f;
  a.temperature()[1] = 0.0f;
  b.temperature()[1] = 350.0f;
  const VoxelGrid m = interpolate_keyframes(a, b, 0.25);
  EXPECT_FLOAT_EQ(m.temperature()[0], 310.0f);
  EXPECT_FLOAT_EQ(m.temperature()[1], 350.0f);
  EXPECT_FLOAT_EQ(m.sigma_a(0)[1], 0.125f);
}

// Keyframes of different extent and resolution are resampled onto their union.
TEST(KeyframeInterpolation, DifferentExtentsAreResampledOntoTheUnion) {
  GridPlacement pa, pb;
  pa.voxel_size_m = 1.0;
  pb.voxel_size_m = 0.5;
  pb.origin_m = {1, 1, 1};
  auto a = std::make_shared<VoxelGrid>(GridDims{4, 4, 4}, pa, std::vector<double>{10.0});
  auto b = std::make_shared<VoxelGrid>(GridDims{8, 8, 8}, pb, std::vector<double>{10.0});
  Rng rng(5, 0);
  for (std::size_t v = 0; v < 64; ++v) {
    a->sigma_a(0)[v] = static_cast<float>(rng.uniform());
    a->temperature()[v] = 300.0f;
  }
  for (std::size_t v = 0; v < 512; ++v) {
    b->sigma_a(0)[v] = static_cast<float>(rng.uniform());
    b->temperature()[v] = 300.0f;
  }
  const VoxelGrid m = interpolate_keyframes(*a, *b, 0.5);
  EXPECT_EQ(m.dims(), (GridDims{10, 10, 10}));  // [0, 5] m at 0.5 m
  EXPECT_EQ(m.placement().voxel_size_m, 0.5);
  const GridMedium ma(a), mb(b);
  MediumPoint pa_point, pb_point;
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 10; ++j)
      for (int i = 0; i < 10; ++i) {
        const Vec3 p = m.placement().index_to_world(Vec3(i, j, k));
        ma.coefficients_at(p, pa_point);
        mb.coefficients_at(p, pb_point);
        EXPECT_NEAR(m.sigma_a(0)[m.index(i, j, k)],
                    0.5 * (pa_point.sigma_a[0] + pb_point.sigma_a[0]), 1e-6);
      }
}

TEST(KeyframeInterpolation, MismatchedWavelengthsOrRotationsAreErrors) {
  VoxelGrid a({1, 1, 1}, {}, {10.0}), b({1, 1, 1}, {}, {4.0});
  EXPECT_THROW(interpolate_keyframes(a, b, 0.5, "cloud.json"), InputError);
  GridPlacement rotated;
  rotated.rotation = rotation_from_euler_deg({0, 0, 30});
  rotated.origin_m = {1, 0, 0};
  VoxelGrid c({1, 1, 1}, rotated, {10.0});
  EXPECT_THROW(interpolate_keyframes(a, c, 0.5, "cloud.json"), InputError);
}

}  // namespace
}  // namespace obscura
