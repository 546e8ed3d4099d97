// Planck's law against values computed at 50 significant digits from the exact
// 2019 SI constants (docs/domain.md §5.2; Python decimal, independent of this code),
// Wien's displacement law and the Stefan–Boltzmann law.
#include "obscura/core/planck.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "obscura/core/band.h"

namespace obscura {
namespace {

struct PlanckCase {
  double wavelength_um, temperature_k, radiance;
};

TEST(Planck, MatchesHighPrecisionValues) {
  const PlanckCase cases[] = {
      {10.0, 300.0, 9.9240333301e+00},  {4.0, 300.0, 7.2197642257e-01},
      {0.55, 5778.0, 2.5857643225e+07}, {1.064, 1000.0, 1.1709615401e+02},
      {3.8, 2000.0, 2.6651546531e+04},  {12.0, 250.0, 3.9882464193e+00},
      {0.5, 150.0, 1.8508146591e-74},   {9.0, 3000.0, 2.8657965606e+03},
  };
  for (const auto& c : cases) {
    const double b = planck_radiance(c.wavelength_um, c.temperature_k);
    EXPECT_NEAR(b / c.radiance, 1.0, 1e-9) << c.wavelength_um << " µm, " << c.temperature_k << " K";
  }
  // The headline value, to the 1e-4 it states.
  EXPECT_NEAR(planck_radiance(10.0, 300.0), 9.9240, 9.9240 * 1e-4);
}

TEST(Planck, ZeroAtZeroKelvin) { EXPECT_EQ(planck_radiance(10.0, 0.0), 0.0); }

TEST(Planck, PeakFollowsWienDisplacement) {
  // λ_max T = b = 2897.771955 µm K (CODATA 2018, exact from the SI constants).
  for (double t : {300.0, 1000.0, 5778.0}) {
    const double peak = 2897.771955 / t;
    // The derivative in λ changes sign at the peak.
    EXPECT_GT(planck_radiance(peak, t), planck_radiance(peak * 0.999, t));
    EXPECT_GT(planck_radiance(peak, t), planck_radiance(peak * 1.001, t));
  }
}

TEST(Planck, TemperatureDerivativeMatchesFiniteDifference) {
  for (double lam : {0.6, 4.0, 10.0})
    for (double t : {200.0, 300.0, 1500.0}) {
      const double h = 1e-5 * t;  // central differences: error ~ (h x / T)² with x = c₂/λT
      const double fd = (planck_radiance(lam, t + h) - planck_radiance(lam, t - h)) / (2 * h);
      EXPECT_NEAR(planck_radiance_dT(lam, t) / fd, 1.0, 1e-6);
    }
}

TEST(Planck, WideBandMatchesStefanBoltzmann) {
  // ∫₀^∞ B_λ dλ = σ T⁴ / π. A band from 0.05 to 10⁴ µm misses less than 1e-9 of it at 300–3000 K.
  const Band wide = Band::flat("wide", 0.05, 1.0e4);
  const BandQuadrature q = BandQuadrature::accurate(wide);
  for (double t : {300.0, 1000.0, 3000.0}) {
    const double expected = kStefanBoltzmann * std::pow(t, 4) / std::numbers::pi;
    EXPECT_NEAR(q.blackbody_radiance(t) / expected, 1.0, 1e-7) << t << " K";
  }
}

TEST(Planck, PublishedBandRadiances) {
  // docs/domain.md §5.3, flat unit response, blackbody; values as printed (3–4 digits).
  const BandQuadrature mwir = BandQuadrature::accurate(Band::preset("mwir"));
  const BandQuadrature lwir = BandQuadrature::accurate(Band::preset("lwir"));
  const double temps[] = {260, 280, 300, 320, 350};
  const double mwir_l[] = {0.355, 0.861, 1.866, 3.70, 8.97};
  const double lwir_l[] = {18.2, 27.2, 38.5, 52.4, 78.0};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(mwir.blackbody_radiance(temps[i]), mwir_l[i], 0.0051 * mwir_l[i]) << temps[i];
    EXPECT_NEAR(lwir.blackbody_radiance(temps[i]), lwir_l[i], 0.0031 * lwir_l[i]) << temps[i];
  }
  EXPECT_NEAR(mwir.blackbody_radiance_dT(300), 0.0677, 0.00006);
  EXPECT_NEAR(lwir.blackbody_radiance_dT(300), 0.630, 0.0006);
}

}  // namespace
}  // namespace obscura
