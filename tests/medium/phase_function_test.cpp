#include "obscura/medium/phase_function.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <vector>

#include "obscura/core/error.h"
#include "support/chi2.h"

namespace obscura {
namespace {

using testing::chi2_passes;

constexpr double kPi = std::numbers::pi;

// Every g the consistency tests run: both signs, isotropic, near-isotropic and
// the extremes (pbrt-v4 media_test.cpp runs a similar list).
const std::vector<double> kGs{-0.999, -0.9, -0.3, -1e-9, 0.0, 1e-9, 1e-4, 0.5, 0.9, 0.99, 0.999};

// A non-axis-aligned incoming direction, so the frame code is exercised.
const Vec3 kIncoming = normalize(Vec3{0.3, -0.5, 0.81});

// Edges in cos θ that resolve a peak at either pole down to 1 − |cos θ| = 1e-10
// (the HG peak has width (1 − |g|)² / (2|g|) ≈ 5e-7 in 1 − cos θ at |g| = 0.999).
const std::vector<double> kFineEdges = testing::pole_refined_cos_theta_edges(40, 1e-10);

// 2π ∫_{−1}^{c} f(x) dx over the fine edges (exact at the edges' pieces).
double integrate_cos(const std::function<double(double)>& f, double c = 1.0) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < kFineEdges.size() && kFineEdges[i] < c; ++i)
    sum += testing::integrate_1d(f, kFineEdges[i], std::min(c, kFineEdges[i + 1]));
  return 2.0 * kPi * sum;
}

TEST(HenyeyGreenstein, RejectsInvalidAsymmetry) {
  for (double g : {1.0, -1.0, 1.5, -7.0, std::numeric_limits<double>::quiet_NaN(),
                   std::numeric_limits<double>::infinity()})
    EXPECT_THROW(HenyeyGreenstein{g}, Error) << g;
  EXPECT_NO_THROW(HenyeyGreenstein{0.999999});
  EXPECT_NO_THROW(HenyeyGreenstein{-0.999999});
}

TEST(HenyeyGreenstein, IsotropicAtZero) {
  const HenyeyGreenstein hg(0.0);
  for (double c : {-1.0, -0.3, 0.0, 0.7, 1.0}) EXPECT_DOUBLE_EQ(hg.eval(c), 0.25 / kPi);
  for (double u : {0.0, 0.1, 0.5, 0.9, 1.0}) EXPECT_DOUBLE_EQ(hg.sample_cos_theta(u), 2 * u - 1);
}

TEST(HenyeyGreenstein, NormalisedWithMeanCosineG) {
  for (double g : kGs) {
    const HenyeyGreenstein hg(g);
    EXPECT_NEAR(integrate_cos([&](double c) { return hg.eval(c); }), 1.0, 1e-6) << "g = " << g;
    EXPECT_NEAR(integrate_cos([&](double c) { return hg.eval(c) * c; }), g, 1e-6) << "g = " << g;
  }
}

// Eval at the peaks against closed forms: at cos θ = 1, 1 + g² − 2g = (1 − g)², so
// p = (1 + g) / (4π (1 − g)²); at cos θ = −1, p = (1 − g) / (4π (1 + g)²).
TEST(HenyeyGreenstein, EvalAtPeaks) {
  for (double g : kGs) {
    const HenyeyGreenstein hg(g);
    EXPECT_NEAR(hg.eval(1.0) / ((1 + g) / (4 * kPi * (1 - g) * (1 - g))), 1.0, 1e-14);
    EXPECT_NEAR(hg.eval(-1.0) / ((1 - g) / (4 * kPi * (1 + g) * (1 + g))), 1.0, 1e-14);
  }
}

// The closed-form CDF against quadrature of eval: an independent check of cdf,
// which the round-trip test below then uses to check the sampling.
TEST(HenyeyGreenstein, CdfMatchesIntegralOfEval) {
  for (double g : kGs) {
    const HenyeyGreenstein hg(g);
    EXPECT_EQ(hg.cdf(-1.0), 0.0);
    EXPECT_EQ(hg.cdf(1.0), 1.0);
    double previous = 0.0;
    for (double c : {-1.0 + 1e-9, -0.999, -0.9, -0.5, 0.0, 0.3, 0.9, 0.99, 0.9999, 1.0 - 1e-9}) {
      const double expected = integrate_cos([&](double x) { return hg.eval(x); }, c);
      EXPECT_NEAR(hg.cdf(c), expected, 1e-9) << "g = " << g << ", c = " << c;
      EXPECT_GE(hg.cdf(c), previous);
      previous = hg.cdf(c);
    }
  }
}

TEST(HenyeyGreenstein, SampleInvertsCdf) {
  for (double g : kGs) {
    const HenyeyGreenstein hg(g);
    double worst = 0.0;
    for (int i = 0; i <= 1000; ++i) {
      const double u = i / 1000.0;
      const double c = hg.sample_cos_theta(u);
      ASSERT_GE(c, -1.0);
      ASSERT_LE(c, 1.0);
      worst = std::max(worst, std::abs(hg.cdf(c) - u));
    }
    for (double u : {1e-12, 1e-9, 1e-6, 1.0 - 1e-6, 1.0 - 1e-9})
      worst = std::max(worst, std::abs(hg.cdf(hg.sample_cos_theta(u)) - u));
    EXPECT_LT(worst, 1e-9) << "g = " << g;
    std::printf("[ hg       ] g = %-7g worst |cdf(sample(u)) - u| = %.3g\n", g, worst);
  }
}

// sample_cos_theta against the root of cdf(c) = u found by bisection in long
// double: the inversion must not lose digits for tiny g (where the textbook
// (1 + g² − s²)/(2g) loses ~|log10 g| digits) nor near the peaks.
TEST(HenyeyGreenstein, SampleCosThetaIsAccurate) {
  for (double g : kGs) {
    const long double gl = g;
    auto cdf_ld = [&](long double c) {
      const long double d =
          gl >= 0 ? (1 - gl) * (1 - gl) + 2 * gl * (1 - c) : (1 + gl) * (1 + gl) - 2 * gl * (1 + c);
      const long double root = std::sqrt(d);
      return (1 - gl) * (1 + c) / (root * (1 + gl + root));
    };
    const HenyeyGreenstein hg(g);
    for (double u : {1e-9, 1e-3, 0.1, 0.25, 0.5, 0.75, 0.9, 0.999, 1.0 - 1e-9}) {
      long double lo = -1, hi = 1;
      for (int it = 0; it < 200; ++it) {
        const long double mid = 0.5L * (lo + hi);
        (cdf_ld(mid) < u ? lo : hi) = mid;
      }
      const double c = hg.sample_cos_theta(u);
      // A few ulps of 1, plus the reference's own error: cdf_ld is good to ~1e-19
      // in u, which is dc/du = 1/(2π p) in cos θ (large where p is small).
      const double tol = 3e-16 + 2e-19 / (2 * kPi * hg.eval(c));
      EXPECT_NEAR(c, static_cast<double>(lo), tol) << "g = " << g << " u = " << u;
    }
  }
}

TEST(HenyeyGreenstein, SampleReturnsEvalAsPdfAndInverts) {
  const std::vector<Vec3> incoming{kIncoming, {0, 0, 1}, {0, 0, -1}, {1, 0, 0}};
  for (double g : kGs) {
    const HenyeyGreenstein hg(g);
    for (const Vec3& wi : incoming)
      for (double u1 : {0.01, 0.2, 0.5, 0.8, 0.99})
        for (double u2 : {0.05, 0.3, 0.7, 0.95}) {
          double pdf = -1.0;
          const Vec3 wo = hg.sample(wi, u1, u2, &pdf);
          ASSERT_NEAR(length(wo), 1.0, 1e-14);
          EXPECT_NEAR(dot(wi, wo), hg.sample_cos_theta(u1), 1e-14);
          EXPECT_NEAR(pdf / hg.eval(wi, wo), 1.0, 1e-9) << "g = " << g;
          EXPECT_EQ(pdf, hg.eval(hg.sample_cos_theta(u1)));
          const SquareSample back = hg.invert(wi, wo);
          EXPECT_NEAR(back.u1, u1, 1e-9) << "g = " << g;
          EXPECT_NEAR(back.u2, u2, 1e-9) << "g = " << g;
        }
  }
}

// Chi-square, binned about the incoming direction; Šidák over the g values.
TEST(HenyeyGreenstein, ChiSquare) {
  const std::vector<double> gs{-0.999, -0.9, -0.3, 0.0, 1e-9, 0.5, 0.9, 0.99, 0.999};
  const double threshold = testing::sidak_threshold(static_cast<int>(gs.size()));
  const auto edges = testing::pole_refined_cos_theta_edges(16, 1e-8);
  std::uint64_t seed = 100;
  for (double g : gs) {
    const HenyeyGreenstein hg(g);
    const auto r = testing::chi2_sphere(
        [&](Rng& rng) {
          const double u1 = rng.uniform(), u2 = rng.uniform();
          return hg.sample(kIncoming, u1, u2, nullptr);
        },
        [&](const Vec3& wo) { return hg.eval(kIncoming, wo); }, 500000, edges, 8, seed++,
        kIncoming);
    char name[32];
    std::snprintf(name, sizeof name, "HG g = %g", g);
    EXPECT_TRUE(chi2_passes(name, r, threshold));
  }
}

}  // namespace
}  // namespace obscura
