#include "obscura/core/band.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/error.h"
#include "obscura/core/planck.h"

namespace obscura {
namespace {

TEST(Band, PresetsHaveTheDocumentedLimits) {
  EXPECT_DOUBLE_EQ(Band::preset("visible").lo_um(), 0.4);
  EXPECT_DOUBLE_EQ(Band::preset("visible").hi_um(), 0.7);
  EXPECT_NEAR(0.5 * (Band::preset("laser1064").lo_um() + Band::preset("laser1064").hi_um()), 1.064,
              1e-12);
  EXPECT_DOUBLE_EQ(Band::preset("mwir").lo_um(), 3.0);
  EXPECT_DOUBLE_EQ(Band::preset("mwir").hi_um(), 5.0);
  EXPECT_DOUBLE_EQ(Band::preset("lwir").lo_um(), 8.0);
  EXPECT_DOUBLE_EQ(Band::preset("lwir").hi_um(), 12.0);
}

TEST(Band, ParsesRangesAndRejectsNonsense) {
  const Band b = Band::parse("3.7:4.8");
  EXPECT_DOUBLE_EQ(b.lo_um(), 3.7);
  EXPECT_DOUBLE_EQ(b.hi_um(), 4.8);
  EXPECT_THROW(Band::parse("5:3"), InputError);
  EXPECT_THROW(Band::parse("abc"), InputError);
  EXPECT_THROW(Band::parse("3:x"), InputError);
  EXPECT_THROW(Band::parse("-1:2"), InputError);
  try {
    Band::parse("uv");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--band"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("lwir"), std::string::npos);
  }
}

TEST(Band, TabulatedResponseInterpolatesLinearly) {
  const Band b = Band::tabulated("tri", {{1.0, 0.0}, {2.0, 1.0}, {3.0, 0.0}});
  EXPECT_DOUBLE_EQ(b.response(1.5), 0.5);
  EXPECT_DOUBLE_EQ(b.response(2.0), 1.0);
  EXPECT_DOUBLE_EQ(b.response(0.5), 0.0);
  EXPECT_DOUBLE_EQ(b.response(3.5), 0.0);
  // ∫ R dλ of the triangle is 1 µm, exact for Gauss–Legendre on each linear piece.
  EXPECT_NEAR(BandQuadrature(b, 2, 0.0).response_integral(), 1.0, 1e-14);
  EXPECT_THROW(Band::tabulated("bad", {{1.0, 1.0}, {1.0, 1.0}}), InputError);
  EXPECT_THROW(Band::tabulated("bad", {{1.0, -1.0}, {2.0, 1.0}}), InputError);
  EXPECT_THROW(Band::tabulated("bad", {{1.0, 0.0}, {2.0, 0.0}}), InputError);
}

TEST(GaussLegendre, IntegratesPolynomialsExactly) {
  for (int n : {1, 2, 3, 5, 8, 12, 20}) {
    std::vector<double> x, w;
    gauss_legendre(n, x, w);
    // Exact for degree 2n − 1: ∫₋₁¹ t^k dt = 2/(k+1) for even k, 0 for odd.
    for (int k = 0; k <= 2 * n - 1; ++k) {
      double sum = 0;
      for (int i = 0; i < n; ++i) sum += w[i] * std::pow(x[i], k);
      const double expected = (k % 2 == 0) ? 2.0 / (k + 1) : 0.0;
      EXPECT_NEAR(sum, expected, 1e-13) << "n=" << n << " k=" << k;
    }
  }
}

TEST(ApparentTemperature, RoundTripsToAMillikelvin) {
  // Over 150–3000 K in every preset band: band radiance of T, inverted, gives T back.
  for (const auto& name : Band::preset_names()) {
    const BandQuadrature q = BandQuadrature::accurate(Band::preset(name));
    for (double t = 150.0; t <= 3000.0; t *= 1.07) {
      const double l = q.blackbody_radiance(t);
      ASSERT_GT(l, 0.0) << name << " " << t;
      EXPECT_NEAR(q.apparent_temperature(l), t, 1e-3) << name << " " << t;
    }
  }
}

TEST(ApparentTemperature, ConvergesToItsStatedRelativeAccuracy) {
  // The inversion stops at 1e-12 relative steps: the temperature is right to
  // 1e-9 relative (its documented accuracy) from 20 K to 10⁵ K; the radiance
  // and its derivative taken together equal the separate sums.
  for (const auto& name : Band::preset_names()) {
    const BandQuadrature q = BandQuadrature::accurate(Band::preset(name));
    for (double t = 20.0; t <= 1e5; t *= 1.31) {
      const double l = q.blackbody_radiance(t);
      if (!(l > 1e-300)) continue;  // below what a double holds in this band
      EXPECT_NEAR(q.apparent_temperature(l), t, 1e-9 * t) << name << " " << t;
      double d_dt = 0;
      EXPECT_NEAR(q.blackbody_radiance_and_dT(t, d_dt), l, 1e-14 * l) << name << " " << t;
      EXPECT_TRUE(std::isfinite(d_dt) && d_dt > 0.0) << name << " " << t;
      // (Below 1e-100 the separate derivative's (eˣ − 1)² overflows.)
      if (l > 1e-100)
        EXPECT_NEAR(d_dt, q.blackbody_radiance_dT(t), 1e-13 * d_dt) << name << " " << t;
    }
  }
}

TEST(ApparentTemperature, AccurateAgainstIndependentBandIntegral) {
  // Band radiance from a 20000-panel midpoint rule (independent of the Gauss–Legendre
  // quadrature), inverted: the temperature must come back within 1 mK.
  const Band lwir = Band::preset("lwir");
  const BandQuadrature q = BandQuadrature::accurate(lwir);
  for (double t : {150.0, 300.0, 1000.0, 3000.0}) {
    const int n = 20000;
    double l = 0;
    for (int i = 0; i < n; ++i) {
      const double lam = 8.0 + (i + 0.5) * 4.0 / n;
      l += planck_radiance(lam, t) * 4.0 / n;
    }
    EXPECT_NEAR(q.apparent_temperature(l), t, 1e-3) << t;
  }
}

TEST(ApparentTemperature, NonPositiveRadianceGivesZero) {
  const BandQuadrature q = BandQuadrature::accurate(Band::preset("lwir"));
  EXPECT_EQ(q.apparent_temperature(0.0), 0.0);
  EXPECT_EQ(q.apparent_temperature(-1.0), 0.0);
}

}  // namespace
}  // namespace obscura
