// Majorant pieces along rays bound the extinction everywhere and cover every
// place where the medium is non-zero, for grids, boxes and their composites.
#include <gtest/gtest.h>

#include "medium/test_grids.h"
#include "obscura/medium/composite_medium.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

void expect_bounds_and_cover(const Medium& m, std::uint64_t seed) {
  Rng rng(seed, 0);
  MediumPoint p;
  const BBox3 b = m.bounds();
  int checked = 0;
  for (int r = 0; r < 200; ++r) {
    const Vec3 target(b.lo.x + b.extent().x * rng.uniform(), b.lo.y + b.extent().y * rng.uniform(),
                      b.lo.z + b.extent().z * rng.uniform());
    const Vec3 dir = normalize(Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
    const Ray ray{target - dir * 30.0, dir};
    std::vector<std::pair<double, double>> pieces;
    m.trace_majorants(ray, 0.0, 1e9, [&](const MajorantSegment& s) {
      pieces.push_back({s.t_begin, s.t_end});
      for (int i = 0; i < 5; ++i) {
        const double t = s.t_begin + (s.t_end - s.t_begin) * rng.uniform();
        m.coefficients_at(ray.at(t), p);
        // To rounding: a block of one value is bounded by that value itself.
        for (int k = 0; k < s.spectral_count; ++k) {
          EXPECT_LE(p.sigma_a[k] + p.sigma_s[k], s.sigma_majorant[k] * (1.0 + 1e-12));
          if (s.sigma_minorant) {
            EXPECT_GE(p.sigma_a[k] + p.sigma_s[k], s.sigma_minorant[k] * (1.0 - 1e-12));
            EXPECT_LE(s.sigma_minorant[k], s.sigma_majorant[k]);
          }
        }
        ++checked;
      }
      return true;
    });
    // Every point where the medium is non-zero lies in a piece.
    m.trace_segments(ray, 0.0, 1e9, [&](const MediumSegment& seg) {
      const double t = 0.5 * (seg.t_begin + seg.t_end);
      m.coefficients_at(ray.at(t), p);
      if (p.sigma_a[0] + p.sigma_s[0] > 0) {
        bool inside = false;
        for (auto& [a, c] : pieces) inside = inside || (t >= a && t <= c);
        EXPECT_TRUE(inside) << "t=" << t;
      }
      return true;
    });
  }
  EXPECT_GT(checked, 500);
}

TEST(MajorantSegments, GridBoundsAndCovers) {
  expect_bounds_and_cover(
      GridMedium(testing::random_grid({9, 7, 8}, 2, 4, rotation_from_euler_deg({15, 25, 35})), 3),
      1);
  // No empty voxels: the minorants are positive and bound σt from below.
  auto full = testing::random_grid({9, 7, 8}, 2, 6);
  for (int s = 0; s < 2; ++s)
    for (std::size_t v = 0; v < full->dims().count(); ++v) full->sigma_a(s)[v] += 0.5f;
  const GridMedium medium(full, 3);
  expect_bounds_and_cover(medium, 2);
  int positive = 0;
  medium.trace_majorants(Ray{medium.bounds().center() - Vec3(0, 0, 20), Vec3(0, 0, 1)}, 0, 1e9,
                         [&](const MajorantSegment& s) {
                           positive += s.sigma_minorant && s.sigma_minorant[0] > 0.5 * 0.999;
                           return true;
                         });
  EXPECT_GT(positive, 1);
}

TEST(MajorantSegments, HomogeneousIsExact) {
  const HomogeneousMedium m(BBox3({0, 0, 0}, {1, 2, 3}), {4.0}, {0.3}, {0.2}, {0.0}, 300.0);
  expect_bounds_and_cover(m, 2);
  int pieces = 0;
  m.trace_majorants(Ray{{-1, 0.5, 0.5}, {1, 0, 0}}, 0, 1e9, [&](const MajorantSegment& s) {
    EXPECT_DOUBLE_EQ(s.sigma_majorant[0], 0.5);
    EXPECT_TRUE(s.sigma_minorant && s.sigma_minorant[0] == s.sigma_majorant[0]);
    EXPECT_DOUBLE_EQ(s.t_begin, 1.0);
    EXPECT_DOUBLE_EQ(s.t_end, 2.0);
    return ++pieces, true;
  });
  EXPECT_EQ(pieces, 1);
}

TEST(MajorantSegments, CompositeSumsItsChildren) {
  auto a = std::make_shared<GridMedium>(testing::random_grid({6, 6, 6}, 1, 7), 2);
  auto b = std::make_shared<HomogeneousMedium>(
      BBox3({-1, 0.5, 2.5}, {1, 2, 4}), std::vector<double>{3.0}, std::vector<double>{0.4},
      std::vector<double>{0.1}, std::vector<double>{0.0}, 300.0);
  expect_bounds_and_cover(CompositeMedium({a, b}), 3);
}

}  // namespace
}  // namespace obscura
