#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/bbox.h"
#include "obscura/core/mat3.h"
#include "obscura/core/rng.h"

namespace obscura {
namespace {

TEST(BBox3, SlabTestClipsTheRay) {
  const BBox3 box({0, 0, 0}, {1, 2, 3});
  double t0 = 0, t1 = 100;
  ASSERT_TRUE(box.intersect(Ray{{-1, 0.5, 0.5}, {1, 0, 0}}, t0, t1));
  EXPECT_DOUBLE_EQ(t0, 1.0);
  EXPECT_DOUBLE_EQ(t1, 2.0);
  t0 = 0;
  t1 = 100;
  EXPECT_FALSE(box.intersect(Ray{{-1, 5, 0.5}, {1, 0, 0}}, t0, t1));
}

TEST(Mat3, EulerRotationIsOrthonormalAndRightHanded) {
  Rng rng(3, 0);
  for (int i = 0; i < 50; ++i) {
    const Vec3 deg(360 * rng.uniform(), 360 * rng.uniform(), 360 * rng.uniform());
    const Mat3 r = rotation_from_euler_deg(deg);
    const Mat3 i3 = r * r.transposed();
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) EXPECT_NEAR(i3.m[a][b], a == b ? 1.0 : 0.0, 1e-12);
    const Vec3 x = r * Vec3(1, 0, 0), y = r * Vec3(0, 1, 0), z = r * Vec3(0, 0, 1);
    EXPECT_NEAR(dot(cross(x, y), z), 1.0, 1e-12);
  }
  // 90° about z takes x to y.
  const Vec3 v = rotation_from_euler_deg({0, 0, 90}) * Vec3(1, 0, 0);
  EXPECT_NEAR(v.y, 1.0, 1e-15);
}

TEST(Frame, IsOrthonormalAndRoundTrips) {
  Rng rng(5, 0);
  for (int i = 0; i < 100; ++i) {
    const double z = 2 * rng.uniform() - 1, phi = 2 * M_PI * rng.uniform();
    const double r = std::sqrt(1 - z * z);
    const Vec3 n(r * std::cos(phi), r * std::sin(phi), z);
    const Frame f = Frame::from_normal(n);
    EXPECT_NEAR(dot(f.s, f.t), 0, 1e-12);
    EXPECT_NEAR(dot(f.s, f.n), 0, 1e-12);
    EXPECT_NEAR(length(f.s), 1, 1e-12);
    EXPECT_NEAR(length(f.t), 1, 1e-12);
    const Vec3 v(0.3, -0.2, 0.9);
    const Vec3 back = f.to_world(f.to_local(v));
    EXPECT_NEAR(length(back - v), 0, 1e-12);
  }
}

}  // namespace
}  // namespace obscura
