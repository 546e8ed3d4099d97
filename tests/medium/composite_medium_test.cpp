#include "obscura/medium/composite_medium.h"

#include <gtest/gtest.h>

#include <cmath>

#include "medium/test_grids.h"
#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/emission_absorption/emission_absorption.h"

namespace obscura {
namespace {

std::shared_ptr<HomogeneousMedium> box(BBox3 b, double sa, double ss, double g, double t,
                                       double wavelength_um = 10.0) {
  return std::make_shared<HomogeneousMedium>(b, std::vector<double>{wavelength_um},
                                             std::vector<double>{sa}, std::vector<double>{ss},
                                             std::vector<double>{g}, t);
}

TEST(Cubic, ShiftIsExact) {
  const Cubic p{{0.3, -1.2, 0.7, 2.5}};
  for (double d : {-1.5, 0.0, 0.25, 3.0})
    for (double s : {0.0, 0.4, 1.7}) EXPECT_NEAR(p.shifted(d)(s), p(s + d), 1e-12);
}

// Optical depth is additive over overlapping media, whatever their layout.
TEST(CompositeMedium, OpticalDepthAdds) {
  auto a = std::make_shared<GridMedium>(testing::random_grid({5, 6, 7}, 1, 3));
  auto b = std::make_shared<GridMedium>(
      testing::random_grid({4, 4, 4}, 1, 8, rotation_from_euler_deg({0, 20, 45})));
  auto c = box(BBox3({-1, 0, 1}, {1.5, 2, 3}), 0.3, 0.2, 0.5, 300, 3.0);  // random_grid's 3 µm
  const CompositeMedium all({a, b, c});
  Rng rng(1, 0);
  for (int r = 0; r < 200; ++r) {
    const Vec3 target(-1 + 2 * rng.uniform(), 0.5 + 2 * rng.uniform(), 2 + 2 * rng.uniform());
    const Vec3 dir = normalize(Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
    const Ray ray{target - dir * 20.0, dir};
    const double expected = a->optical_depth(ray, 0, 1e9)[0] + b->optical_depth(ray, 0, 1e9)[0] +
                            c->optical_depth(ray, 0, 1e9)[0];
    EXPECT_NEAR(all.optical_depth(ray, 0, 1e9)[0], expected, 1e-9 * (1 + expected));
  }
}

// Two isothermal absorbers filling the same slab at different temperatures:
// L = (σ1 B(T1) + σ2 B(T2)) / (σ1 + σ2) · (1 − e^{−(σ1+σ2) L}), not B of any single T.
TEST(CompositeMedium, OverlappingMediaEmitAtTheirOwnTemperatures) {
  const BBox3 slab({-50, -50, 0}, {50, 50, 2});
  const CompositeMedium m({box(slab, 0.3, 0.0, 0.0, 280.0), box(slab, 0.5, 0.0, 0.0, 400.0)});
  const SpectralNodes nodes(BandQuadrature(Band::flat("mono", 10.0 - 1e-6, 10.0 + 1e-6), 1, 0.0),
                            m.wavelengths_um());
  double l = 0, tr = 1;
  integrate_emission_absorption(&m, Ray{{0, 0, 5}, {0, 0, -1}}, 100, nodes, 1e-9, &l, &tr);
  const double b1 = planck_radiance(10.0, 280.0), b2 = planck_radiance(10.0, 400.0);
  const double expected = (0.3 * b1 + 0.5 * b2) / 0.8 * -std::expm1(-0.8 * 2.0);
  EXPECT_NEAR(tr, std::exp(-1.6), 1e-12);
  EXPECT_NEAR(l / expected, 1.0, 1e-8);
}

TEST(CompositeMedium, PointCoefficientsAddAndWeightG) {
  const BBox3 b({0, 0, 0}, {1, 1, 1});
  const CompositeMedium m({box(b, 0.1, 0.3, 0.8, 300.0), box(b, 0.2, 0.1, -0.4, 300.0)});
  MediumPoint p;
  m.coefficients_at({0.5, 0.5, 0.5}, p);
  EXPECT_NEAR(p.sigma_a[0], 0.3, 1e-12);
  EXPECT_NEAR(p.sigma_s[0], 0.4, 1e-12);
  EXPECT_NEAR(p.g[0], (0.3 * 0.8 + 0.1 * -0.4) / 0.4, 1e-12);
  EXPECT_NEAR(p.temperature_k, 300.0, 1e-12);
}

TEST(CompositeMedium, MismatchedWavelengthsAreAnError) {
  auto a = box(BBox3({0, 0, 0}, {1, 1, 1}), 0.1, 0.0, 0.0, 300);
  auto b = std::make_shared<HomogeneousMedium>(
      BBox3({0, 0, 0}, {1, 1, 1}), std::vector<double>{4.0}, std::vector<double>{0.1},
      std::vector<double>{0.0}, std::vector<double>{0.0}, 300.0);
  try {
    CompositeMedium({a, b}, "scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("clouds/1"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace obscura
