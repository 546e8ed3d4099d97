// The real spherical harmonics and the Henyey–Greenstein convolution of
// render/radiance_cache/spherical_harmonics.h against numerical integrals
// over the sphere.
#include "obscura/render/radiance_cache/spherical_harmonics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "obscura/core/band.h"
#include "obscura/core/rng.h"
#include "obscura/render/radiance_cache/cache_source.h"

namespace obscura {
namespace {

// ∫ f(ω) dω by Gauss–Legendre in μ = cos θ and the midpoint rule in φ
// (n_mu × n_phi points; exact for the harmonics' products up to degree
// 2 n_mu − 1 in μ and n_phi − 1 in φ).
double over_sphere(const std::function<double(const Vec3&)>& f, int n_mu = 800, int n_phi = 400) {
  std::vector<double> nodes, weights;
  gauss_legendre(n_mu, nodes, weights);
  double sum = 0.0;
  for (int i = 0; i < n_mu; ++i) {
    const double mu = nodes[i], s = std::sqrt(1 - mu * mu);
    double ring = 0.0;
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * std::numbers::pi / n_phi;
      ring += f(Vec3(s * std::cos(phi), s * std::sin(phi), mu));
    }
    sum += weights[i] * ring;
  }
  return sum * (2.0 * std::numbers::pi / n_phi);
}

// Every pair of harmonics to degree 6 (the explicit degrees 0–3 and the
// recurrence's 4–6) in one pass over a rule exact for their products.
TEST(SphericalHarmonics, AreOrthonormal) {
  constexpr int n_mu = 16, n_phi = 32, count = kMaxShCoefficients;
  static_assert(kMaxShDegree == 6);
  std::vector<double> nodes, weights;
  gauss_legendre(n_mu, nodes, weights);
  std::vector<double> gram(count * count, 0.0);
  std::array<double, kMaxShCoefficients> y;
  for (int i = 0; i < n_mu; ++i) {
    const double mu = nodes[i], s = std::sqrt(1 - mu * mu);
    for (int j = 0; j < n_phi; ++j) {
      const double phi = (j + 0.5) * 2.0 * std::numbers::pi / n_phi;
      spherical_harmonics(Vec3(s * std::cos(phi), s * std::sin(phi), mu), y, kMaxShDegree);
      for (int a = 0; a < count; ++a)
        for (int b = a; b < count; ++b) gram[a * count + b] += weights[i] * y[a] * y[b];
    }
  }
  const double cell = 2.0 * std::numbers::pi / n_phi;
  for (int a = 0; a < count; ++a)
    for (int b = a; b < count; ++b)
      EXPECT_NEAR(gram[a * count + b] * cell, a == b ? 1.0 : 0.0, 1e-12) << "Y" << a << " Y" << b;
}

// The harmonics of degree l span the functions P_l(ω·w) of the angle to
// any direction w (the addition theorem the convolution rests on):
// Σ_m Y_lm(ω) Y_lm(w) = (2l + 1)/(4π) P_l(ω·w), P_l from its closed form.
TEST(SphericalHarmonics, SatisfyTheAdditionTheorem) {
  const auto legendre = [](int l, double x) {
    const double x2 = x * x;
    switch (l) {
      case 4:
        return (35 * x2 * x2 - 30 * x2 + 3) / 8;
      case 5:
        return x * (63 * x2 * x2 - 70 * x2 + 15) / 8;
      default:
        return (231 * x2 * x2 * x2 - 315 * x2 * x2 + 105 * x2 - 5) / 16;
    }
  };
  Rng rng(7, 0);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 a = normalize(Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
    const Vec3 b = normalize(Vec3(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5));
    std::array<double, kMaxShCoefficients> ya, yb;
    spherical_harmonics(a, ya, 6);
    spherical_harmonics(b, yb, 6);
    for (int l = 4; l <= 6; ++l) {
      double sum = 0.0;
      for (int i = l * l; i < (l + 1) * (l + 1); ++i) sum += ya[i] * yb[i];
      EXPECT_NEAR(sum, (2 * l + 1) / (4 * std::numbers::pi) * legendre(l, dot(a, b)), 1e-12)
          << "degree " << l;
    }
  }
}

double hg(double g, double mu) {
  return (1 - g * g) / (4 * std::numbers::pi * std::pow(1 + g * g - 2 * g * mu, 1.5));
}

TEST(SphericalHarmonics, HenyeyGreensteinConvolutionIsExactPerBand) {
  // L of degree ≤ 6: ∫ p(ω'·ω) L(ω') dω' = Σ_l g^l Σ_m Y_lm(ω) c_lm exactly,
  // as p's Legendre coefficients are g^l (the higher ones meet nothing in L).
  std::array<float, kMaxShCoefficients> c;
  for (int i = 0; i < kMaxShCoefficients; ++i)
    c[i] = static_cast<float>(0.3 + 0.17 * i - 0.02 * i * i);
  auto radiance = [&](const Vec3& d) {
    std::array<double, kMaxShCoefficients> y;
    spherical_harmonics(d, y, kMaxShDegree);
    double l = 0;
    for (int i = 0; i < kMaxShCoefficients; ++i) l += c[i] * y[i];
    return l;
  };
  for (const double g : {-0.5, 0.0, 0.4, 0.7})
    for (const Vec3& w :
         {Vec3(0, 0, 1), normalize(Vec3(0.3, -0.5, 0.8)), normalize(Vec3(-1, 0.2, -0.1))}) {
      const double numeric =
          over_sphere([&](const Vec3& d) { return hg(g, dot(d, w)) * radiance(d); }, 1600, 800);
      std::array<double, kMaxShCoefficients> y;
      spherical_harmonics(w, y, kMaxShDegree);
      EXPECT_NEAR(hg_convolved(c.data(), y, g, kMaxShDegree), numeric,
                  1e-4 * (1 + std::abs(numeric)))
          << "g = " << g;
    }
}

TEST(SphericalHarmonics, TruncationKeepsTheLowerBands) {
  // Degree 0 keeps c00 Y00 (the mean radiance) whatever g; degree 1 adds g c1m Y1m.
  std::array<float, kMaxShCoefficients> c{};
  c[0] = 2.0f;
  c[2] = 1.0f;
  std::array<double, kMaxShCoefficients> y;
  spherical_harmonics(Vec3(0, 0, 1), y, 1);
  EXPECT_NEAR(hg_convolved(c.data(), y, 0.6, 0), 2.0 * y[0], 1e-12);
  EXPECT_NEAR(hg_convolved(c.data(), y, 0.6, 1), 2.0 * y[0] + 0.6 * y[2], 1e-7);
}

// The CPU march's float form (HgConvolution) against hg_convolved, for every
// degree, random directions, g and coefficients: to float rounding (1e-6 of
// the sum of the terms' magnitudes); the coefficients beyond the degree, in
// the group of four it reads, change nothing.
TEST(SphericalHarmonics, TheFloatConvolutionAgreesWithTheDoubleOne) {
  Rng rng(12345, 0);
  auto uniform = [&] { return rng.uniform(); };
  for (int degree = 0; degree <= kMaxShDegree; ++degree)
    for (int trial = 0; trial < 200; ++trial) {
      const Vec3 w = normalize(Vec3(uniform() - 0.5, uniform() - 0.5, uniform() - 0.5));
      std::array<double, kMaxShCoefficients> y;
      spherical_harmonics(w, y, degree);
      std::array<float, kMaxShCoefficients + 4> c{};
      const int count = sh_coefficient_count(degree);
      for (int i = 0; i < count; ++i) c[i] = static_cast<float>(100.0 * (uniform() - 0.3));
      for (int i = count; i < HgConvolution::readable(degree); ++i) c[i] = 1e3f;
      const double g = 2.0 * uniform() - 1.0;
      double magnitude = 0.0;
      for (int i = 0; i < count; ++i) magnitude += std::abs(y[i] * c[i]);
      std::array<float, kMaxShCoefficients + 4> exact = c;
      for (int i = count; i < static_cast<int>(exact.size()); ++i) exact[i] = 0.0f;
      EXPECT_NEAR(HgConvolution(y, degree)(c.data(), g), hg_convolved(exact.data(), y, g, degree),
                  1e-6 * magnitude)
          << "degree " << degree << ", g " << g;
      // Delta-M's weights g^l − f: the convolution less f times the plain sum.
      const double f = g > 0.0 ? std::pow(g, degree + 1) : 0.0;
      const double delta_m =
          hg_convolved(exact.data(), y, g, degree) - f * hg_convolved(exact.data(), y, 1.0, degree);
      EXPECT_NEAR(hg_convolved(exact.data(), y, g, degree, f), delta_m, 1e-12 * magnitude);
      EXPECT_NEAR(HgConvolution(y, degree)(c.data(), g, f), delta_m, 1e-6 * magnitude)
          << "degree " << degree << ", g " << g;
    }
}

// The forward peak the radiance cache splats towards a sensor
// (hg_beyond_degree, cache_source.h) is the HG phase function less its
// Legendre expansion to the cache's degree: over the sphere it has no
// component on P_l for l ≤ degree, and on P_{degree+1} the HG's own
// coefficient g^{degree+1} (∫ p_HG P_l dΩ = g^l).
TEST(SphericalHarmonics, TheHgPeakBeyondTheDegreeHoldsOnlyTheHigherBands) {
  const auto legendre = [](int l, double mu) {
    const double m2 = mu * mu;
    const double p[8] = {1.0,
                         mu,
                         0.5 * (3 * m2 - 1),
                         0.5 * mu * (5 * m2 - 3),
                         (35 * m2 * m2 - 30 * m2 + 3) / 8.0,
                         mu * (63 * m2 * m2 - 70 * m2 + 15) / 8.0,
                         (231 * m2 * m2 * m2 - 315 * m2 * m2 + 105 * m2 - 5) / 16.0,
                         mu * (429 * m2 * m2 * m2 - 693 * m2 * m2 + 315 * m2 - 35) / 16.0};
    return p[l];
  };
  for (const double g : {-0.4, 0.0, 0.5, 0.75})
    for (int degree = 0; degree <= kMaxShDegree; ++degree)
      for (int l = 0; l <= degree + 1; ++l) {
        // ∫ q(μ) P_l(μ) 2π dμ by the midpoint rule on a fine grid in μ.
        const int n = 400000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
          const double mu = -1.0 + (i + 0.5) * 2.0 / n;
          sum += hg_beyond_degree(g, mu, degree) * legendre(l, mu);
        }
        sum *= 2.0 * std::numbers::pi * 2.0 / n;
        const double expected = l <= degree ? 0.0 : std::pow(g, l);
        EXPECT_NEAR(sum, expected, 2e-5) << "g " << g << " degree " << degree << " l " << l;
      }
  // Isotropic scattering leaves nothing beyond degree 0.
  EXPECT_NEAR(hg_beyond_degree(0.0, 0.3, 0), 0.0, 1e-15);
}

}  // namespace
}  // namespace obscura
