#include "obscura/optics/size_distribution.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/optics/mie.h"

namespace obscura {
namespace {

using cdouble = std::complex<double>;
constexpr double kPi = std::numbers::pi;

// ∫ f(r) dr over r = e^u, u in [lo, hi], by a dense trapezoid in u written
// here independently of radius_quadrature (for integrands that vanish at both
// ends the trapezoid in u is spectrally accurate).
double integrate_ln_r(const std::function<double(double)>& f, double lo, double hi, int n = 20000) {
  const double h = (hi - lo) / n;
  double sum = 0;
  for (int i = 0; i <= n; ++i) {
    const double r = std::exp(lo + h * i);
    sum += (i == 0 || i == n ? 0.5 : 1.0) * f(r) * r;
  }
  return sum * h;
}

// Standard normal CDF.
double phi(double z) { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }

const std::vector<LognormalDistribution> kLognormals{
    {0.3, 1.6}, {2.0, 2.2}, {0.01, 1.2}, {5.0, 1.05}};
// Deirmendjian (1969) haze M, haze H and cloud C.1, and a narrow one.
const std::vector<ModifiedGammaDistribution> kGammas{
    {0.05, 1, 0.5}, {0.1, 2, 1}, {4, 6, 1}, {1, 8, 3}};

// ---------------------------------------------------------------------------
// Distributions.

// ∫ r^k n dr of a lognormal is r_g^k exp(k² ln²σ_g / 2) (r^k n is itself
// lognormal about ln r_g + k ln²σ_g). For the moments the optics integrate
// (k = 2 … 3) the rule must reproduce both the closed form truncated to its
// interval and the full moment to rounding. (Other k are not covered to
// their tails by this interval, so their truncation is not negligible.)
TEST(SizeDistribution, LognormalQuadratureReproducesAnalyticMoments) {
  for (const auto& d : kLognormals) {
    const double tail = 1e-15;
    const LnRadiusInterval iv = integration_interval(d, 0.55, tail);
    const RadiusQuadrature q = radius_quadrature(d, 0.55, 256, tail);
    const double s = std::log(d.geometric_std), mu = std::log(d.median_radius_um);
    for (double k : {2.0, 2.5, 3.0}) {
      double sum = 0;
      for (std::size_t i = 0; i < q.radius_um.size(); ++i)
        sum += q.weight[i] * std::pow(q.radius_um[i], k);
      const double full = std::pow(d.median_radius_um, k) * std::exp(0.5 * k * k * s * s);
      for (double j : {0.0, 1.0, 6.0})  // the closed form itself, any k
        EXPECT_NEAR(radius_moment_um(d, j) /
                        (std::pow(d.median_radius_um, j) * std::exp(0.5 * j * j * s * s)),
                    1.0, 1e-14);
      const double centre = mu + k * s * s;
      const double truncated = full * (phi((iv.hi - centre) / s) - phi((iv.lo - centre) / s));
      EXPECT_NEAR(sum / truncated, 1.0, 1e-12) << "r_g " << d.median_radius_um << " k " << k;
      EXPECT_NEAR(sum / full, 1.0, 1e-12) << k;
    }
  }
}

// The count median splits the number in half, and from_mass_median_diameter
// puts half the mass (r³ n) below MMD/2 (Hatch–Choate).
TEST(SizeDistribution, LognormalMediansAndNormalisation) {
  for (double sg : {1.3, 1.6, 2.5}) {
    const auto d = LognormalDistribution::from_mass_median_diameter(0.6, sg);
    const auto n = [&](double r) { return number_density_per_um(d, r); };
    const double lo = std::log(d.median_radius_um) - 12 * std::log(sg);
    const double hi =
        std::log(d.median_radius_um) + 12 * std::log(sg) + 3 * std::pow(std::log(sg), 2);
    EXPECT_NEAR(integrate_ln_r(n, lo, hi), 1.0, 1e-12);
    EXPECT_NEAR(integrate_ln_r(n, lo, std::log(d.median_radius_um)), 0.5, 1e-9);
    const auto mass = [&](double r) { return r * r * r * n(r); };
    EXPECT_NEAR(integrate_ln_r(mass, lo, std::log(0.3)) / integrate_ln_r(mass, lo, hi), 0.5, 1e-9)
        << sg;
  }
}

// n(r) = a r^α exp(−b r^γ) with b = α/(γ r_c^γ): unit total number, its mode
// at r_c, and moments b^{−k/γ} Γ((α+1+k)/γ)/Γ((α+1)/γ), checked against an
// independent integration of the density.
TEST(SizeDistribution, ModifiedGammaNormalisationModeAndMoments) {
  for (const auto& d : kGammas) {
    const auto n = [&](double r) { return number_density_per_um(d, r); };
    const double b = d.alpha / (d.gamma * std::pow(d.mode_radius_um, d.gamma));
    // From where r^{α+1} is 1e-40 of its value at r_c to where b r^γ = 300.
    const double lo = std::log(d.mode_radius_um) - 92.0 / (d.alpha + 1.0);
    const double hi = std::log(300.0 / b) / d.gamma;
    for (double k : {0.0, 1.0, 2.0, 3.0, 6.0}) {
      const double brute =
          integrate_ln_r([&](double r) { return std::pow(r, k) * n(r); }, lo, hi, 40000);
      EXPECT_NEAR(radius_moment_um(d, k) / brute, 1.0, 1e-10) << d.mode_radius_um << " k " << k;
    }
    const double rc = d.mode_radius_um, e = 1e-4;
    const double slope = (n(rc * (1 + e)) - n(rc * (1 - e))) / (2 * e * rc);
    EXPECT_LT(std::abs(slope) * rc / n(rc), 1e-6);
    EXPECT_GT(n(rc), n(rc * 1.05));
    EXPECT_GT(n(rc), n(rc / 1.05));
    // And the rule bulk_optics uses reproduces the moments it needs.
    const RadiusQuadrature q = radius_quadrature(d, 0.55, 512, 1e-15);
    for (double k : {2.0, 3.0}) {
      double sum = 0;
      for (std::size_t i = 0; i < q.radius_um.size(); ++i)
        sum += q.weight[i] * std::pow(q.radius_um[i], k);
      EXPECT_NEAR(sum / radius_moment_um(d, k), 1.0, 1e-12) << d.mode_radius_um << " k " << k;
    }
  }
}

// ---------------------------------------------------------------------------
// Bulk optics.

// α_ext of a monodisperse population of radius r: (3/(4ρ)) Q_ext / r, in
// m²/g for r in µm and ρ in g/cm³.
TEST(BulkOptics, NarrowLognormalEqualsSingleSphere) {
  for (const cdouble m : {cdouble(1.48, 0), cdouble(1.75, 0.44), cdouble(1.33, 1e-3)}) {
    const double r = 0.3, lambda = 0.55, rho = 0.9;
    const MieEfficiencies q = mie_sphere(2 * kPi * r / lambda, m);
    const BulkOptics b = bulk_optics(LognormalDistribution{r, 1.00001}, lambda, m, rho,
                                     {.relative_tolerance = 1e-8});
    // σ_g = 1.00001 spreads ln r by 1e-5: the result moves by O(1e-10).
    const double scale = 3.0 / (4.0 * rho * r);
    EXPECT_NEAR(b.mass_extinction_m2_g / (scale * q.qext), 1.0, 1e-8) << m;
    EXPECT_NEAR(b.mass_scattering_m2_g / (scale * q.qsca), 1.0, 1e-8) << m;
    EXPECT_NEAR(b.mass_absorption_m2_g, scale * q.qabs, 1e-8 * scale * q.qext) << m;
    EXPECT_NEAR(b.asymmetry, q.g, 1e-8) << m;
    EXPECT_NEAR(b.single_scattering_albedo, q.qsca / q.qext, 1e-8) << m;
  }
}

// Small absorbing particles: Q_abs = 4x Im L, L = (m² − 1)/(m² + 2), so
//   α_abs = (3/(4ρ)) ∫ 4 (2πr/λ) Im L r² n dr / ∫ r³ n dr = 6π Im L / (ρ λ),
// whatever the sizes; and Q_sca = (8/3) x⁴ |L|² gives
//   α_sca = (3/(4ρ)) (8/3) (2π/λ)⁴ |L|² M₆/M₃ (Bohren & Huffman §5.2).
TEST(BulkOptics, RayleighRegimeMassAbsorptionIsSizeIndependent) {
  const cdouble m(1.75, 0.44);  // soot-like
  const cdouble l = (m * m - 1.0) / (m * m + 2.0);
  const double lambda_um = 10.0, rho_g_cm3 = 1.8;
  // In SI: ρ in g/m³ and λ in m give m²/g.
  const double expected_m2_g = 6.0 * kPi * l.imag() / ((rho_g_cm3 * 1e6) * (lambda_um * 1e-6));
  const std::vector<SizeDistribution> dists{LognormalDistribution{0.0005, 1.5},
                                            LognormalDistribution{0.001, 1.8},
                                            ModifiedGammaDistribution{0.001, 2, 1}};
  for (const auto& d : dists) {
    const BulkOptics b = bulk_optics(d, lambda_um, m, rho_g_cm3, {.relative_tolerance = 1e-8});
    EXPECT_NEAR(b.mass_absorption_m2_g / expected_m2_g, 1.0, 1e-4);
    const double k = 2 * kPi / lambda_um;
    const double sca = 3.0 / (4.0 * rho_g_cm3) * (8.0 / 3.0) * std::pow(k, 4) * std::norm(l) *
                       radius_moment_um(d, 6) / radius_moment_um(d, 3);
    // The neglected terms are O(x²) relative, x ≲ 0.005 here: ~1e-5.
    EXPECT_NEAR(b.mass_scattering_m2_g / sca, 1.0, 1e-4);
    EXPECT_LT(std::abs(b.asymmetry), 1e-4);
  }
}

// Convergence of the size integral (trapezoid in ln r, step halved until two
// successive halvings agree): halving once more from the returned estimate
// changes every quantity by less than 1e-4 relative, for the smokes, fogs and
// the soot of docs/domain.md §2, across the bands.
struct ConvergenceCase {
  const char* name;
  SizeDistribution dist;
  double lambda_um;
  cdouble m;
  double rho;
};

TEST(BulkOptics, DoublingTheNodesChangesTheResultBelow1e4) {
  const auto fog_oil = LognormalDistribution::from_mass_median_diameter(0.6, 1.6);
  const auto water_fog = LognormalDistribution::from_mass_median_diameter(10, 1.6);
  const std::vector<ConvergenceCase> cases{
      {"fog oil 0.55", fog_oil, 0.55, {1.48, 0}, 0.9},
      {"fog oil 1.064", fog_oil, 1.064, {1.47, 0}, 0.9},
      {"fog oil 10", fog_oil, 10.0, {1.47, 5e-3}, 0.9},
      {"water fog 0.55", water_fog, 0.55, {1.333, 1.96e-9}, 1.0},
      {"water fog 10", water_fog, 10.0, {1.218, 0.0508}, 1.0},
      {"soot 0.55", LognormalDistribution{0.05, 1.8}, 0.55, {1.61, 0.28}, 1.8},
      {"haze M 0.55", ModifiedGammaDistribution{0.05, 1, 0.5}, 0.55, {1.5, 0}, 1.7},
  };
  for (const auto& c : cases) {
    const BulkOptics b = bulk_optics(c.dist, c.lambda_um, c.m, c.rho);
    EXPECT_LT(b.relative_change, 1e-4) << c.name;
    const BulkOptics d =
        bulk_optics(c.dist, c.lambda_um, c.m, c.rho, {.fixed_intervals = 2 * b.intervals});
    EXPECT_NEAR(d.mass_extinction_m2_g / b.mass_extinction_m2_g, 1.0, 1e-4) << c.name;
    EXPECT_NEAR(d.mass_scattering_m2_g / b.mass_scattering_m2_g, 1.0, 1e-4) << c.name;
    if (b.mass_absorption_m2_g > 1e-3 * b.mass_extinction_m2_g) {
      EXPECT_NEAR(d.mass_absorption_m2_g / b.mass_absorption_m2_g, 1.0, 1e-4) << c.name;
    }
    EXPECT_NEAR(d.asymmetry, b.asymmetry, 1e-4) << c.name;
    EXPECT_NEAR(b.mass_scattering_m2_g + b.mass_absorption_m2_g, b.mass_extinction_m2_g,
                1e-12 * b.mass_extinction_m2_g)
        << c.name;
  }
}

// For absorbing particles the integrand is smooth and the trapezoid in ln r
// converges geometrically: a tight tolerance is reached in few halvings and
// the next halving confirms it.
TEST(BulkOptics, AbsorbingParticlesConvergeGeometrically) {
  const LognormalDistribution soot{0.05, 1.8};
  const BulkOptics b = bulk_optics(soot, 0.55, {1.61, 0.28}, 1.8, {.relative_tolerance = 1e-10});
  EXPECT_LE(b.intervals, 4096);
  const BulkOptics d =
      bulk_optics(soot, 0.55, {1.61, 0.28}, 1.8,
                  {.relative_tolerance = 1e-10, .fixed_intervals = 2 * b.intervals});
  EXPECT_NEAR(d.mass_extinction_m2_g / b.mass_extinction_m2_g, 1.0, 1e-10);
  EXPECT_NEAR(d.asymmetry, b.asymmetry, 1e-10);
}

TEST(BulkOptics, ResultDoesNotDependOnThreadCount) {
  const auto d = LognormalDistribution::from_mass_median_diameter(0.6, 1.6);
  const BulkOptics one = bulk_optics(d, 0.55, {1.48, 0}, 0.9, {.threads = 1});
  const BulkOptics two = bulk_optics(d, 0.55, {1.48, 0}, 0.9, {.threads = 2});
  EXPECT_EQ(one.mass_extinction_m2_g, two.mass_extinction_m2_g);
  EXPECT_EQ(one.asymmetry, two.asymmetry);
  EXPECT_EQ(one.intervals, two.intervals);
}

// Cross-check against the Mie values of docs/domain.md §2.3 (computed elsewhere
// for lognormal droplets, σ_g = 1.6, given by mass median diameter, printed to
// two figures): within half a unit of the last printed digit.
TEST(BulkOptics, AgreesWithDomainTable) {
  struct Row {
    double mmd_um, lambda_um, n, rho, alpha_m2_g, half_unit;
  };
  const std::vector<Row> rows{
      // fog oil, n = 1.48, ρ 0.90, at 0.55 µm
      {0.3, 0.55, 1.48, 0.9, 5.8, 0.05},
      {0.5, 0.55, 1.48, 0.9, 7.9, 0.05},
      {0.7, 0.55, 1.48, 0.9, 7.6, 0.05},
      {1.0, 0.55, 1.48, 0.9, 5.8, 0.05},
      {2.0, 0.55, 1.48, 0.9, 2.4, 0.05},
      // H₃PO₄ solution, n = 1.42, ρ 1.6, at 0.55 µm
      {0.3, 0.55, 1.42, 1.6, 2.6, 0.05},
      {0.5, 0.55, 1.42, 1.6, 3.8, 0.05},
      {0.7, 0.55, 1.42, 1.6, 3.9, 0.05},
      {1.0, 0.55, 1.42, 1.6, 3.2, 0.05},
      {2.0, 0.55, 1.42, 1.6, 1.4, 0.05},
      // water, n = 1.333 at 0.55 µm and 1.326 at 1.064 µm (docs/domain.md §2.5), ρ 1.0
      {0.3, 0.55, 1.333, 1.0, 2.7, 0.05},
      {0.5, 0.55, 1.333, 1.0, 4.4, 0.05},
      {0.7, 0.55, 1.333, 1.0, 4.9, 0.05},
      {1.0, 0.55, 1.333, 1.0, 4.6, 0.05},
      {2.0, 0.55, 1.333, 1.0, 2.3, 0.05},
      {0.3, 1.064, 1.326, 1.0, 0.46, 0.005},
      {0.5, 1.064, 1.326, 1.0, 1.1, 0.05},
      {0.7, 1.064, 1.326, 1.0, 1.7, 0.05},
      {1.0, 1.064, 1.326, 1.0, 2.2, 0.05},
      {2.0, 1.064, 1.326, 1.0, 2.3, 0.05},
  };
  for (const auto& r : rows) {
    const BulkOptics b =
        bulk_optics(LognormalDistribution::from_mass_median_diameter(r.mmd_um, 1.6), r.lambda_um,
                    {r.n, 0}, r.rho);
    EXPECT_NEAR(b.mass_extinction_m2_g, r.alpha_m2_g, r.half_unit)
        << "MMD " << r.mmd_um << " λ " << r.lambda_um << " n " << r.n;
  }
}

// ---------------------------------------------------------------------------

std::string field_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.field();
  }
  return "(no error)";
}

TEST(BulkOptics, BadInputsNameTheirField) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const LognormalDistribution ok{0.3, 1.6};
  auto bulk = [](SizeDistribution d, double lambda, cdouble m, double rho,
                 BulkOpticsOptions o = {}) { return [=] { bulk_optics(d, lambda, m, rho, o); }; };
  for (double sg : {1.0, 0.5, nan, -2.0})
    EXPECT_EQ(field_of(bulk(LognormalDistribution{0.3, sg}, 0.55, 1.5, 1.0)),
              "lognormal.geometric_std")
        << sg;
  for (double rg : {0.0, -0.3, nan})
    EXPECT_EQ(field_of(bulk(LognormalDistribution{rg, 1.6}, 0.55, 1.5, 1.0)),
              "lognormal.median_radius_um");
  EXPECT_EQ(field_of(bulk(ModifiedGammaDistribution{0.0, 1, 0.5}, 0.55, 1.5, 1.0)),
            "modified_gamma.mode_radius_um");
  EXPECT_EQ(field_of(bulk(ModifiedGammaDistribution{0.05, 0, 0.5}, 0.55, 1.5, 1.0)),
            "modified_gamma.alpha");
  EXPECT_EQ(field_of(bulk(ModifiedGammaDistribution{0.05, 1, -1}, 0.55, 1.5, 1.0)),
            "modified_gamma.gamma");
  EXPECT_EQ(field_of(bulk(ok, 0.0, 1.5, 1.0)), "wavelength_um");
  EXPECT_EQ(field_of(bulk(ok, nan, 1.5, 1.0)), "wavelength_um");
  EXPECT_EQ(field_of(bulk(ok, 0.55, 1.5, 0.0)), "density_g_cm3");
  EXPECT_EQ(field_of(bulk(ok, 0.55, {0.0, 0}, 1.0)), "refractive_index.real");
  EXPECT_EQ(field_of(bulk(ok, 0.55, {1.5, -0.1}, 1.0)), "refractive_index.imag");
  EXPECT_EQ(field_of(bulk(ok, 0.55, 1.5, 1.0, {.relative_tolerance = 0})), "relative_tolerance");
  EXPECT_EQ(field_of(bulk(ok, 0.55, 1.5, 1.0, {.fixed_intervals = -1})), "fixed_intervals");
  // So wide that the tail reaches size parameters beyond the Mie limit.
  EXPECT_EQ(field_of(bulk(LognormalDistribution{1.0, 30.0}, 0.55, 1.5, 1.0)),
            "lognormal.geometric_std");
  EXPECT_EQ(field_of([] { LognormalDistribution::from_mass_median_diameter(-1, 1.6); }),
            "mass_median_diameter_um");
  EXPECT_EQ(field_of([] {
              radius_quadrature(LognormalDistribution{0.3, 1.6}, 0.55, 0, 1e-9);
            }),
            "intervals");
  EXPECT_EQ(field_of(bulk(ok, 0.55, 1.5, 1.0)), "(no error)");
}

// Refinement that cannot reach its tolerance within max_intervals says so.
TEST(BulkOptics, NonConvergenceIsAnError) {
  const auto fog = LognormalDistribution::from_mass_median_diameter(10, 1.6);
  EXPECT_THROW(
      bulk_optics(fog, 0.55, {1.333, 0}, 1.0, {.relative_tolerance = 1e-9, .max_intervals = 1024}),
      Error);
}

}  // namespace
}  // namespace obscura
