// Delta tracking samples real collisions with density σt(t) e^{−τ(0,t)} and
// lets rays through with probability e^{−τ}; ratio tracking estimates e^{−τ}
// without bias. Checked against the exact optical depth of the same media
// (closed form for a box, exact cubic integration for grids) with the shared
// chi-square harness and z-tests.
#include "obscura/medium/tracking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "medium/test_grids.h"
#include "obscura/medium/composite_medium.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "support/chi2.h"

namespace obscura {
namespace {

constexpr int kSamples = 200000;

// The mean of n ratio-tracking estimates along `ray` over [0, 20] against
// e^{−τ}, within 4 standard errors of the mean, and a standard error below
// 1 % of the answer (so a test has the power to see a 4 % bias). Every
// estimate lies in [0, 1].
void expect_unbiased_transmittance(const Medium& medium, const Ray& ray, const SpectralLerp& lambda,
                                   Rng& rng, int n, int label) {
  const double exact = std::exp(-medium.optical_depth(ray, 0.0, 20.0)[0]);
  MediumPoint scratch;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double t = estimate_transmittance(medium, ray, 20.0, lambda, rng, scratch);
    ASSERT_GE(t, 0.0);
    ASSERT_LE(t, 1.0);
    sum += t;
    sum2 += t * t;
  }
  const double mean = sum / n;
  const double stderr_mean = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / (n - 1));
  EXPECT_NEAR(mean, exact, 4.0 * stderr_mean + 1e-12) << "ray " << label << " exact " << exact;
  EXPECT_LT(stderr_mean, 0.01 * exact) << "ray " << label << ": the test lacks power";
}

// Chi-square of free-flight distances along `ray` over [0, t_max]: bins in
// [0, t_max] plus the "escaped" cell, against σt(t) e^{−τ(0,t)}.
testing::Chi2Result free_flight_chi2(const Medium& m, const Ray& ray, double t_max,
                                     double lambda_um, std::uint64_t seed) {
  const SpectralLerp lambda = SpectralLerp::at(m.wavelengths_um(), lambda_um);
  MediumPoint scratch, p;
  auto sampler = [&](Rng& rng) {
    const auto t = sample_free_flight(m, ray, t_max, lambda, rng, scratch);
    return t ? *t : t_max + 1.0;  // escaped: the outside cell
  };
  auto pdf = [&](double t) {
    m.coefficients_at(ray.at(t), p);
    const double sigma_t = lambda(p.sigma_a.data()) + lambda(p.sigma_s.data());
    const std::vector<double> tau = m.optical_depth(ray, 0.0, t);
    return sigma_t * std::exp(-lambda(tau.data()));
  };
  // Bin edges on the medium's cell faces would be ideal; 40 equal bins keep the
  // pdf's kinks inside bins, which the adaptive quadrature handles.
  return testing::chi2_1d(sampler, pdf, 0.0, t_max, 40, kSamples, seed);
}

TEST(DeltaTracking, HomogeneousSlabFollowsBeerLambert) {
  const HomogeneousMedium m(BBox3({-10, -10, 0}, {10, 10, 2}), {10.0}, {0.3}, {0.5}, {0.0}, 300.0);
  const Ray ray{{0, 0, 3}, {0, 0, -1}};
  EXPECT_TRUE(testing::chi2_passes("homogeneous slab", free_flight_chi2(m, ray, 10.0, 10.0, 1)));
}

TEST(DeltaTracking, HeterogeneousMediaFollowTheirOpticalDepth) {
  const int cases = 3;
  const double threshold = testing::sidak_threshold(cases);
  // A rotated random grid with two spectral samples, sampled between them.
  auto grid = std::make_shared<GridMedium>(
      testing::random_grid({7, 6, 5}, 2, 11, rotation_from_euler_deg({10, 20, 30})), 2);
  const BBox3 b = grid->bounds();
  const Ray ray{b.center() - Vec3(1, 0.2, 0.1) * 10.0, normalize(Vec3(1, 0.2, 0.1))};
  EXPECT_TRUE(
      testing::chi2_passes("grid at 3 µm", free_flight_chi2(*grid, ray, 20.0, 3.0, 2), threshold));
  EXPECT_TRUE(testing::chi2_passes("grid at 3.4 µm", free_flight_chi2(*grid, ray, 20.0, 3.4, 3),
                                   threshold));
  // The grid overlapped by a box: majorants add.
  auto box = std::make_shared<HomogeneousMedium>(
      BBox3(b.center() - Vec3(0.5, 0.5, 0.5), b.center() + Vec3(0.5, 0.5, 0.5)),
      std::vector<double>{3.0, 4.0}, std::vector<double>{0.8, 0.6}, std::vector<double>{0.2, 0.1},
      std::vector<double>{0.0, 0.0}, 300.0);
  const CompositeMedium both({grid, box});
  EXPECT_TRUE(
      testing::chi2_passes("grid + box", free_flight_chi2(both, ray, 20.0, 3.7, 4), threshold));
}

// Ratio tracking: the mean of N estimates against e^{−τ}
// (expect_unbiased_transmittance).
TEST(RatioTracking, EstimatesTransmittanceWithoutBias) {
  auto grid = std::make_shared<GridMedium>(
      testing::random_grid({8, 8, 8}, 1, 21, rotation_from_euler_deg({0, 30, 60})), 2);
  const BBox3 b = grid->bounds();
  Rng dirs(5, 0);
  const SpectralLerp lambda = SpectralLerp::at(grid->wavelengths_um(), 3.0);
  for (int r = 0; r < 5; ++r) {
    const Vec3 d =
        normalize(Vec3(dirs.uniform() - 0.5, dirs.uniform() - 0.5, dirs.uniform() - 0.5));
    Rng rng(7, r);
    expect_unbiased_transmittance(*grid, Ray{b.center() - d * 10.0, d}, lambda, rng, 100000, r);
  }
}

// Residual ratio tracking's control (the pieces' minorants): where the
// medium is constant along a piece the estimate is the exact transmittance
// every time, a box's and a constant grid's alike; where it varies (a grid
// without empty voxels, minorants > 0) it stays unbiased.
TEST(RatioTracking, ConstantMediaGiveTheExactTransmittanceEveryTime) {
  const HomogeneousMedium box(BBox3({0, 0, 0}, {2, 2, 2}), {0.5}, {0.2}, {1.8}, {0.5}, 0.0);
  auto grid =
      std::make_shared<VoxelGrid>(GridDims{8, 8, 8}, GridPlacement{}, std::vector<double>{0.5});
  std::fill_n(grid->sigma_a(0), grid->dims().count(), 0.2f);
  std::fill_n(grid->sigma_s(0), grid->dims().count(), 1.8f);
  const GridMedium constant_grid(grid, 4);
  const SpectralLerp lambda{0, 0, 0.0};
  MediumPoint scratch;
  Rng rng(3, 0);
  for (const Medium* m :
       {static_cast<const Medium*>(&box), static_cast<const Medium*>(&constant_grid)})
    for (int i = 0; i < 200; ++i) {
      const Vec3 d = normalize(Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
      const Ray ray{m->bounds().center() - d * 0.3 * rng.uniform(), d};
      const double exact = std::exp(-m->optical_depth(ray, 0.0, 1e9)[0]);
      EXPECT_NEAR(estimate_transmittance(*m, ray, 1e9, lambda, rng, scratch), exact,
                  1e-9 * exact + 1e-15);
    }
}

TEST(RatioTracking, ResidualTrackingIsUnbiasedWhereTheMediumVaries) {
  auto full = testing::random_grid({8, 8, 8}, 1, 22, rotation_from_euler_deg({10, 20, 30}));
  for (std::size_t v = 0; v < full->dims().count(); ++v) {  // thinner, and nowhere empty
    full->sigma_a(0)[v] = 0.3f * full->sigma_a(0)[v] + 0.05f;
    full->sigma_s(0)[v] *= 0.3f;
  }
  const GridMedium grid(full, 2);
  const BBox3 b = grid.bounds();
  const SpectralLerp lambda{0, 0, 0.0};
  Rng dirs(6, 0);
  for (int r = 0; r < 4; ++r) {
    const Vec3 d =
        normalize(Vec3(dirs.uniform() - 0.5, dirs.uniform() - 0.5, dirs.uniform() - 0.5));
    Rng rng(8, r);
    expect_unbiased_transmittance(grid, Ray{b.center() - d * 10.0, d}, lambda, rng, 50000, r);
  }
}

TEST(SpectralLerp, InterpolatesAndClamps) {
  const std::vector<double> w = {3.0, 4.0, 6.0};
  const double v[] = {1.0, 3.0, 7.0};
  EXPECT_DOUBLE_EQ(SpectralLerp::at(w, 2.0)(v), 1.0);
  EXPECT_DOUBLE_EQ(SpectralLerp::at(w, 3.5)(v), 2.0);
  EXPECT_DOUBLE_EQ(SpectralLerp::at(w, 5.0)(v), 5.0);
  EXPECT_DOUBLE_EQ(SpectralLerp::at(w, 9.0)(v), 7.0);
  EXPECT_DOUBLE_EQ(SpectralLerp::at({10.0}, 4.0)(v), 1.0);
}

}  // namespace
}  // namespace obscura
