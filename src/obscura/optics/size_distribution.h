#pragma once
// Number size distributions of obscurant particles, and the bulk optics of a
// population of homogeneous spheres: mass extinction, scattering and
// absorption coefficients (m²/g) and the asymmetry g, by Mie theory (mie.h)
// integrated over the distribution. Formulas, units and the quadrature's
// convergence are in docs/optics.md.
//
// Radii are in µm throughout; every distribution is normalised to one
// particle, ∫ n(r) dr = 1, so n is in 1/µm (the bulk optics are ratios and do
// not depend on the number concentration).
#include <complex>
#include <variant>
#include <vector>

namespace obscura {

// Lognormal number distribution (Hinds 1999, "Aerosol Technology", eq. 4.39):
//   n(r) = exp(−(ln r − ln r_g)² / (2 ln²σ_g)) / (√(2π) r ln σ_g).
struct LognormalDistribution {
  double median_radius_um = 0;  // count median radius r_g, µm (> 0)
  double geometric_std = 0;     // geometric standard deviation σ_g (> 1)

  // From the mass median diameter, as docs/domain.md §2.2–2.3 quote smoke sizes:
  // r_g = (MMD/2) exp(−3 ln²σ_g) (Hatch & Choate 1929; Hinds eq. 4.52).
  static LognormalDistribution from_mass_median_diameter(double mmd_um, double geometric_std);
};

// Modified gamma distribution (Deirmendjian 1969, "Electromagnetic Scattering
// on Spherical Polydispersions", eq. 4.1):
//   n(r) = a r^α exp(−b r^γ),
// parameterised by its mode radius r_c (dn/dr = 0 there, so b = α/(γ r_c^γ)),
// with a = γ b^{(α+1)/γ} / Γ((α+1)/γ) for unit total number. Deirmendjian's
// haze M is r_c = 0.05 µm, α = 1, γ = 0.5; cloud C.1 is r_c = 4 µm, α = 6, γ = 1.
struct ModifiedGammaDistribution {
  double mode_radius_um = 0;  // r_c, µm (> 0)
  double alpha = 0;           // α (> 0: a mode exists)
  double gamma = 0;           // γ (> 0)
};

using SizeDistribution = std::variant<LognormalDistribution, ModifiedGammaDistribution>;

// Throws InputError naming the field ("lognormal.median_radius_um",
// "lognormal.geometric_std", "modified_gamma.mode_radius_um",
// "modified_gamma.alpha", "modified_gamma.gamma") unless every parameter is
// finite and in range.
void validate_size_distribution(const SizeDistribution& distribution);

// n(r) in 1/µm (∫ n dr = 1).
double number_density_per_um(const SizeDistribution& distribution, double radius_um);

// Closed-form moment ∫ r^k n(r) dr in µm^k:
//   lognormal       r_g^k exp(k² ln²σ_g / 2)
//   modified gamma  b^{−k/γ} Γ((α+1+k)/γ) / Γ((α+1)/γ).
double radius_moment_um(const SizeDistribution& distribution, double k);

// The interval of u = ln(r / 1 µm) that the bulk-optics quadrature covers.
struct LnRadiusInterval {
  double lo = 0, hi = 0;
};

// Chosen so that, outside it, each integrand of bulk_optics holds less than
// about `tail` of its integral on either side:
//   below lo: the r² n tail (the integrands are Q r² n with Q falling
//     towards small r);
//   above hi: the r³ n tail (Q r² n with Q bounded, or Q ∝ x in the
//     absorbing Rayleigh regime), and the r⁶ n tail up to x = 10 (Rayleigh
//     scattering, Q ∝ x⁴) at the given wavelength.
// Lognormal tails are exact (erfc); modified-gamma tails are upper bounds.
// bulk_optics uses tail = 1e-3 × its relative tolerance, within [1e-16, 1e-7].
LnRadiusInterval integration_interval(const SizeDistribution& distribution, double wavelength_um,
                                      double tail);

// The trapezoidal rule in u = ln r with `intervals` equal steps over
// integration_interval: Σ weight_i f(radius_i) ≈ ∫ f(r) n(r) dr. The
// integrands decay smoothly to nothing at both ends, so the rule converges
// geometrically once the step resolves them (Trefethen & Weideman 2014,
// SIAM Review 56, 385, §5).
struct RadiusQuadrature {
  std::vector<double> radius_um, weight;
};
RadiusQuadrature radius_quadrature(const SizeDistribution& distribution, double wavelength_um,
                                   int intervals, double tail);

struct BulkOpticsOptions {
  // Stop halving the step when two successive halvings each change every
  // quantity (α_ext, α_sca, α_abs and g) by less than this: relative for
  // α_ext; for α_sca and α_abs relative, or relative to 1e-3 α_ext when
  // smaller; absolute for g. Absorbing particles converge geometrically; for
  // non-absorbing or weakly absorbing droplets with x ≳ 30 the Mie ripple
  // makes the last digits converge erratically, so tolerances much below 1e-5
  // cost tens of thousands of Mie evaluations (docs/optics.md).
  double relative_tolerance = 1e-4;
  // 0: refine as above. > 0: exactly this many trapezoid intervals, no
  // refinement (for convergence studies).
  int fixed_intervals = 0;
  // Refinement gives up (throws obscura::Error) beyond this many intervals.
  int max_intervals = 1 << 17;
  // Threads for the Mie evaluations (0: all cores). The result is the same
  // for any count.
  int threads = 0;
};

struct BulkOptics {
  double mass_extinction_m2_g = 0;      // α_ext: extinction cross-section per gram of particles
  double mass_scattering_m2_g = 0;      // α_sca
  double mass_absorption_m2_g = 0;      // α_abs
  double single_scattering_albedo = 0;  // α_sca / α_ext
  double asymmetry = 0;                 // g = ∫ g Q_sca r² n dr / ∫ Q_sca r² n dr
  int intervals = 0;                    // trapezoid intervals of the returned estimate
  double relative_change = 0;           // last two changes under halving, larger (0 if fixed)
};

// Bulk optics of spheres of index m (= n + ik, k ≥ 0 absorbing) and material
// density ρ (g/cm³) distributed as `distribution`, at vacuum wavelength λ (µm)
// in air (index 1):
//   α_ext = (3 / (4ρ)) ∫ Q_ext(2πr/λ) r² n dr / ∫ r³ n dr,
// and likewise α_sca, α_abs. With r in µm and ρ in g/cm³ the ratio is in
// cm³/(g·µm) = 1 m²/g exactly, so no conversion factor appears.
// Throws InputError naming "wavelength_um", "density_g_cm3",
// "refractive_index.real", "refractive_index.imag" or the distribution's
// field (also when the distribution reaches size parameters beyond
// kMaxMieSizeParameter); obscura::Error if refinement does not converge.
BulkOptics bulk_optics(const SizeDistribution& distribution, double wavelength_um,
                       std::complex<double> m, double density_g_cm3,
                       const BulkOpticsOptions& options = {});

}  // namespace obscura
