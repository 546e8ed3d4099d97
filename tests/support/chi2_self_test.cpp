// The chi-square harness tested on itself: it must pass correct samplers with
// calibrated p-values, and it must fail wrong ones (the evidence that a
// passing sampler test means something).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"
#include "support/chi2.h"

namespace obscura {
namespace {

using testing::chi2_1d;
using testing::chi2_passes;
using testing::chi2_sphere;

// Free-flight distance in a homogeneous medium: pdf σ e^{−σ x} on [0, ∞).
double sample_exponential(Rng& rng, double sigma) { return -std::log1p(-rng.uniform()) / sigma; }

TEST(Chi2Harness, SidakThreshold) {
  EXPECT_DOUBLE_EQ(testing::sidak_threshold(1), 1e-3);
  EXPECT_NEAR(testing::sidak_threshold(6), 1.0 - std::pow(0.999, 1.0 / 6.0), 1e-15);
  EXPECT_LT(testing::sidak_threshold(6), 1e-3 / 6 * 1.001);
}

TEST(Chi2Harness, SphereQuadratureIsExact) {
  EXPECT_NEAR(testing::integrate_sphere([](const Vec3&) { return 1.0; }), 4 * std::numbers::pi,
              1e-12);
  // ∫ z² dΩ = 4π/3, about a tilted axis.
  EXPECT_NEAR(testing::integrate_sphere([](const Vec3& d) { return d.z * d.z; },
                                        testing::uniform_cos_theta_edges(3), {1, 2, 3}),
              4 * std::numbers::pi / 3, 1e-12);
}

TEST(Chi2Harness, EdgeHelpers) {
  for (const auto& e :
       {testing::uniform_cos_theta_edges(7), testing::pole_refined_cos_theta_edges(12, 1e-8),
        testing::cone_cos_theta_edges(std::cos(0.00465), 10),
        testing::cone_cos_theta_edges(-1.0, 4)}) {
    EXPECT_EQ(e.front(), -1.0);
    EXPECT_EQ(e.back(), 1.0);
    for (std::size_t i = 0; i + 1 < e.size(); ++i) EXPECT_LT(e[i], e[i + 1]);
  }
  EXPECT_THROW(
      chi2_sphere(
          [](Rng&) {
            return Vec3{0, 0, 1};
          },
          [](const Vec3&) { return 1.0; }, 10, std::vector<double>{-1.0, 0.5, 0.2, 1.0}, 4, 1),
      std::invalid_argument);
}

TEST(Chi2Harness, CorrectOneDimensionalSamplersPass) {
  const double threshold = testing::sidak_threshold(2);
  const auto uniform = chi2_1d([](Rng& rng) { return rng.uniform(); }, [](double) { return 1.0; },
                               0.0, 1.0, 50, 200000, 11);
  EXPECT_TRUE(chi2_passes("1-D uniform", uniform, threshold));
  // Distances beyond 3/σ land in the outside cell (expected mass e^{−6}).
  const double sigma = 2.0;
  const auto flight =
      chi2_1d([&](Rng& rng) { return sample_exponential(rng, sigma); },
              [&](double x) { return sigma * std::exp(-sigma * x); }, 0.0, 3.0, 60, 200000, 12);
  EXPECT_TRUE(chi2_passes("1-D exponential free flight", flight, threshold));
  EXPECT_NEAR(flight.pdf_integral, -std::expm1(-6.0), 1e-9);
}

// Many cells with expected counts below 5: they are pooled, the test still
// passes, and the degrees of freedom drop below cells − 1.
TEST(Chi2Harness, PoolsSparseCells) {
  const auto r = chi2_1d([](Rng& rng) { return sample_exponential(rng, 1.0); },
                         [](double x) { return std::exp(-x); }, 0.0, 20.0, 400, 20000, 13);
  EXPECT_TRUE(chi2_passes("1-D exponential, sparse tail", r));
  EXPECT_LT(r.dof, 400);
  EXPECT_GT(r.dof, 50);
}

// Over independent seeds the p-value of a correct sampler is uniform on [0, 1]:
// its mean is 1/2 (σ = 1/√(12·40) ≈ 0.046 for 40 runs), and p < 0.1 happens
// about 4 times in 40. Loose bounds (over 4σ): this checks calibration, not luck.
TEST(Chi2Harness, PValuesOfCorrectSamplersAreCalibrated) {
  constexpr int kRuns = 40;
  double mean = 0.0;
  int small = 0;
  for (int s = 0; s < kRuns; ++s) {
    const auto r = chi2_1d([](Rng& rng) { return sample_exponential(rng, 1.0); },
                           [](double x) { return std::exp(-x); }, 0.0, 4.0, 20, 5000, 1000 + s);
    mean += r.p_value / kRuns;
    small += r.p_value < 0.1;
  }
  std::printf("[ chi2     ] calibration: mean p over %d seeds = %.3f, %d below 0.1\n", kRuns, mean,
              small);
  EXPECT_NEAR(mean, 0.5, 0.2);
  EXPECT_LE(small, 14);
}

// --- The harness must fail wrong samplers -----------------------------------

constexpr double kFail = 1e-6;

TEST(Chi2Harness, FailsHenyeyGreensteinWithTheWrongG) {
  const HenyeyGreenstein sampled(0.5), claimed(0.55);
  const Vec3 axis = normalize(Vec3{0.3, -0.5, 0.81});
  const auto r = chi2_sphere(
      [&](Rng& rng) {
        const double u1 = rng.uniform(), u2 = rng.uniform();
        return sampled.sample(axis, u1, u2, nullptr);
      },
      [&](const Vec3& d) { return claimed.eval(axis, d); }, 200000,
      testing::pole_refined_cos_theta_edges(16, 1e-6), 8, 21, axis);
  std::printf("[ chi2     ] wrong g (0.5 sampled, 0.55 claimed): chi2 = %.4g, dof = %d, p = %.3g\n",
              r.statistic, r.dof, r.p_value);
  EXPECT_LT(r.p_value, kFail) << r.table;
  EXPECT_TRUE(std::isfinite(r.statistic));  // failed by the statistic, not outright
}

TEST(Chi2Harness, FailsUniformSphereAgainstCosinePdf) {
  const auto r =
      chi2_sphere([](Rng& rng) { return sample_uniform_sphere(rng.uniform(), rng.uniform()); },
                  [](const Vec3& d) { return cosine_hemisphere_pdf(d.z); }, 100000, 10, 10, 22);
  std::printf("[ chi2     ] uniform sphere vs cosine pdf: p = %.3g\n", r.p_value);
  EXPECT_LT(r.p_value, kFail);
  EXPECT_NE(r.table.find("pdf integrates to 0"), std::string::npos) << r.table;
}

// Cosine-hemisphere samples against the uniform-hemisphere pdf 1/(2π): same
// support, so only the statistic can catch it.
TEST(Chi2Harness, FailsCosineHemisphereAgainstUniformHemisphere) {
  const auto r = chi2_sphere(
      [](Rng& rng) { return sample_cosine_hemisphere(rng.uniform(), rng.uniform()); },
      [](const Vec3& d) { return d.z > 0 ? 0.5 * std::numbers::inv_pi : 0.0; }, 100000, 10, 10, 23);
  std::printf("[ chi2     ] cosine vs uniform hemisphere: chi2 = %.4g, dof = %d, p = %.3g\n",
              r.statistic, r.dof, r.p_value);
  EXPECT_LT(r.p_value, kFail);
  EXPECT_TRUE(std::isfinite(r.statistic));
}

TEST(Chi2Harness, FailsPdfOffByFivePercent) {
  const auto r = chi2_sphere(
      [](Rng& rng) { return sample_uniform_sphere(rng.uniform(), rng.uniform()); },
      [](const Vec3&) { return 1.05 * obscura::uniform_sphere_pdf(); }, 200000, 10, 20, 24);
  std::printf("[ chi2     ] pdf scaled by 1.05: chi2 = %.4g, dof = %d, p = %.3g\n", r.statistic,
              r.dof, r.p_value);
  EXPECT_LT(r.p_value, kFail);
  EXPECT_NEAR(r.pdf_integral, 1.05, 1e-9);
}

TEST(Chi2Harness, FailsFreeFlightWithTheWrongCoefficient) {
  const auto r =
      chi2_1d([](Rng& rng) { return sample_exponential(rng, 1.0); },
              [](double x) { return 1.05 * std::exp(-1.05 * x); }, 0.0, 6.0, 60, 100000, 25);
  std::printf("[ chi2     ] free flight sigma 1 vs 1.05: chi2 = %.4g, dof = %d, p = %.3g\n",
              r.statistic, r.dof, r.p_value);
  EXPECT_LT(r.p_value, kFail);
}

TEST(Chi2Harness, FailsSamplesOutsideTheSupport) {
  const auto r = chi2_1d([](Rng& rng) { return 1.1 * rng.uniform(); }, [](double) { return 1.0; },
                         0.0, 1.0, 20, 10000, 26);
  EXPECT_LT(r.p_value, kFail) << r.table;
}

TEST(Chi2Harness, FailsInvalidSamples) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int i = 0;
  const auto one_nan = chi2_1d([&](Rng& rng) { return ++i == 500 ? nan : rng.uniform(); },
                               [](double) { return 1.0; }, 0.0, 1.0, 20, 10000, 27);
  EXPECT_EQ(one_nan.p_value, 0.0);
  int j = 0;
  const auto one_long = chi2_sphere(
      [&](Rng& rng) {
        const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
        return ++j == 500 ? d * 1.01 : d;
      },
      [](const Vec3&) { return uniform_sphere_pdf(); }, 10000, 5, 5, 28);
  EXPECT_EQ(one_long.p_value, 0.0);
  EXPECT_NE(one_long.table.find("not unit length"), std::string::npos);
}

}  // namespace
}  // namespace obscura
