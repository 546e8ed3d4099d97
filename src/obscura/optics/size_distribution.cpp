#include "obscura/optics/size_distribution.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/optics/mie.h"

namespace obscura {
namespace {

constexpr double kPi = std::numbers::pi;

// Standard-normal quantile: the z with P(Z > z) = tail, by bisection on erfc.
double normal_upper_quantile(double tail) {
  double lo = 0.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(mid / std::sqrt(2.0)) > tail ? lo : hi) = mid;
  }
  return hi;
}

// Modified gamma in t = b r^γ: the r^k-weighted distribution of t is a gamma
// distribution with shape κ_k = (α + 1 + k)/γ, density t^{κ−1} e^{−t} / Γ(κ).
double gamma_shape(const ModifiedGammaDistribution& d, double k) {
  return (d.alpha + 1.0 + k) / d.gamma;
}
double gamma_rate(const ModifiedGammaDistribution& d) {  // b, in µm^{−γ}
  return d.alpha / (d.gamma * std::pow(d.mode_radius_um, d.gamma));
}

// Smallest t beyond which the gamma(κ) distribution holds less than `tail`.
// For t ≥ 2(κ − 1) the density falls at least as fast as e^{−t/2}, so the
// tail is at most 2 t^{κ−1} e^{−t} / Γ(κ); that bound is inverted by bisection.
double gamma_upper_t(double kappa, double tail) {
  const double log_target = std::log(tail);
  auto log_bound = [&](double t) {
    return std::log(2.0) + (kappa - 1.0) * std::log(t) - t - std::lgamma(kappa);
  };
  double lo = std::max({2.0 * (kappa - 1.0), kappa, 1.0});
  if (log_bound(lo) <= log_target) return lo;
  double hi = 2.0 * lo;
  while (log_bound(hi) > log_target) hi *= 2.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (log_bound(mid) > log_target ? lo : hi) = mid;
  }
  return hi;
}

// Largest t below which the gamma(κ) distribution holds less than `tail`:
// ∫₀ᵗ s^{κ−1} e^{−s} ds ≤ t^κ/κ, so the lower tail is at most t^κ / Γ(κ + 1).
double gamma_lower_t(double kappa, double tail) {
  return std::exp((std::log(tail) + std::lgamma(kappa + 1.0)) / kappa);
}

// ln of the density of u = ln r: p(u) = n(r) r, so that ∫ f n dr = ∫ f p du.
double log_density_in_ln_r(const SizeDistribution& dist, double u) {
  if (const auto* l = std::get_if<LognormalDistribution>(&dist)) {
    const double s = std::log(l->geometric_std), z = (u - std::log(l->median_radius_um)) / s;
    return -0.5 * z * z - std::log(s * std::sqrt(2.0 * kPi));
  }
  const auto& g = std::get<ModifiedGammaDistribution>(dist);
  const double b = gamma_rate(g), kappa = gamma_shape(g, 0.0);
  // ln a = ln γ + κ ln b − ln Γ(κ), and n r = a r^{α+1} e^{−b r^γ}.
  return std::log(g.gamma) + kappa * std::log(b) - std::lgamma(kappa) + (g.alpha + 1.0) * u -
         b * std::exp(g.gamma * u);
}

// The u interval holding all but `tail` of the r^k-weighted distribution on
// each side.
LnRadiusInterval moment_interval(const SizeDistribution& dist, double k, double tail) {
  if (const auto* l = std::get_if<LognormalDistribution>(&dist)) {
    // r^k n(r) dr is again lognormal in r, centred at ln r_g + k ln²σ_g.
    const double s = std::log(l->geometric_std), z = normal_upper_quantile(tail);
    const double centre = std::log(l->median_radius_um) + k * s * s;
    return {centre - z * s, centre + z * s};
  }
  const auto& g = std::get<ModifiedGammaDistribution>(dist);
  const double log_b = std::log(gamma_rate(g)), kappa = gamma_shape(g, k);
  return {(std::log(gamma_lower_t(kappa, tail)) - log_b) / g.gamma,
          (std::log(gamma_upper_t(kappa, tail)) - log_b) / g.gamma};
}

// The tail left outside the interval for a requested tolerance: a thousandth
// of it, and never above 1e-7 or below 1e-16.
double tail_for_tolerance(double relative_tolerance) {
  return std::clamp(1e-3 * relative_tolerance, 1e-16, 1e-7);
}

void require(bool ok, const char* field, const std::string& what) {
  if (!ok) throw InputError("", field, what);
}

}  // namespace

LognormalDistribution LognormalDistribution::from_mass_median_diameter(double mmd_um,
                                                                       double geometric_std) {
  require(std::isfinite(mmd_um) && mmd_um > 0, "mass_median_diameter_um",
          fmt::format("must be a finite diameter > 0 µm, got {}", mmd_um));
  LognormalDistribution d{0.5 * mmd_um, geometric_std};
  validate_size_distribution(d);  // σ_g first: the conversion needs it
  const double s = std::log(geometric_std);
  d.median_radius_um = 0.5 * mmd_um * std::exp(-3.0 * s * s);
  return d;
}

void validate_size_distribution(const SizeDistribution& dist) {
  if (const auto* l = std::get_if<LognormalDistribution>(&dist)) {
    require(std::isfinite(l->median_radius_um) && l->median_radius_um > 0,
            "lognormal.median_radius_um",
            fmt::format("must be a finite radius > 0 µm, got {}", l->median_radius_um));
    require(std::isfinite(l->geometric_std) && l->geometric_std > 1.0, "lognormal.geometric_std",
            fmt::format("must be a finite number > 1, got {}", l->geometric_std));
    return;
  }
  const auto& g = std::get<ModifiedGammaDistribution>(dist);
  require(std::isfinite(g.mode_radius_um) && g.mode_radius_um > 0, "modified_gamma.mode_radius_um",
          fmt::format("must be a finite radius > 0 µm, got {}", g.mode_radius_um));
  require(
      std::isfinite(g.alpha) && g.alpha > 0, "modified_gamma.alpha",
      fmt::format("must be a finite number > 0 (the distribution needs a mode), got {}", g.alpha));
  require(std::isfinite(g.gamma) && g.gamma > 0, "modified_gamma.gamma",
          fmt::format("must be a finite number > 0, got {}", g.gamma));
}

double number_density_per_um(const SizeDistribution& dist, double radius_um) {
  validate_size_distribution(dist);
  if (!(radius_um > 0)) return 0.0;
  return std::exp(log_density_in_ln_r(dist, std::log(radius_um))) / radius_um;
}

double radius_moment_um(const SizeDistribution& dist, double k) {
  validate_size_distribution(dist);
  if (const auto* l = std::get_if<LognormalDistribution>(&dist)) {
    const double s = std::log(l->geometric_std);
    return std::pow(l->median_radius_um, k) * std::exp(0.5 * k * k * s * s);
  }
  const auto& g = std::get<ModifiedGammaDistribution>(dist);
  return std::exp(std::lgamma(gamma_shape(g, k)) - std::lgamma(gamma_shape(g, 0.0)) -
                  k / g.gamma * std::log(gamma_rate(g)));
}

LnRadiusInterval integration_interval(const SizeDistribution& dist, double wavelength_um,
                                      double tail) {
  validate_size_distribution(dist);
  require(tail > 0 && tail < 0.5, "tail", fmt::format("must lie in (0, 0.5), got {}", tail));
  require(std::isfinite(wavelength_um) && wavelength_um > 0, "wavelength_um",
          fmt::format("must be a finite wavelength > 0 µm, got {}", wavelength_um));
  const LnRadiusInterval r2 = moment_interval(dist, 2.0, tail),
                         r3 = moment_interval(dist, 3.0, tail),
                         r6 = moment_interval(dist, 6.0, tail);
  // u where x = 2πr/λ = 10: beyond it Q no longer grows like x⁴, and the
  // integrands are bounded by a constant times r² n, covered by the r³ tail.
  const double u_x10 = std::log(10.0 * wavelength_um / (2.0 * kPi));
  return {r2.lo, std::max(r3.hi, std::min(r6.hi, u_x10))};
}

RadiusQuadrature radius_quadrature(const SizeDistribution& dist, double wavelength_um,
                                   int intervals, double tail) {
  require(intervals >= 1, "intervals", fmt::format("must be at least 1, got {}", intervals));
  const LnRadiusInterval iv = integration_interval(dist, wavelength_um, tail);
  const double h = (iv.hi - iv.lo) / intervals;
  RadiusQuadrature q;
  q.radius_um.resize(intervals + 1);
  q.weight.resize(intervals + 1);
  for (int i = 0; i <= intervals; ++i) {
    const double u = iv.lo + h * i;
    q.radius_um[i] = std::exp(u);
    // ∫ f n dr = ∫ f(e^u) p(u) du, trapezoid weights h (h/2 at the ends).
    q.weight[i] =
        ((i == 0 || i == intervals) ? 0.5 * h : h) * std::exp(log_density_in_ln_r(dist, u));
  }
  return q;
}

namespace {

// Integrals over u = ln r of p(u) r² (Q_ext, Q_sca, Q_abs, g Q_sca).
using Sums = std::array<double, 4>;

void add_scaled(Sums& s, const Sums& v, double weight) {
  for (int i = 0; i < 4; ++i) s[i] += weight * v[i];
}

// Checks bulk_optics' arguments; returns the integration interval in ln r.
LnRadiusInterval checked_interval(const SizeDistribution& dist, double wavelength_um,
                                  std::complex<double> m, double density_g_cm3,
                                  const BulkOpticsOptions& options) {
  require(options.relative_tolerance > 0 && options.relative_tolerance < 1, "relative_tolerance",
          fmt::format("must lie in (0, 1), got {}", options.relative_tolerance));
  const LnRadiusInterval iv = integration_interval(
      dist, wavelength_um, tail_for_tolerance(options.relative_tolerance));  // validates both
  require(std::isfinite(density_g_cm3) && density_g_cm3 > 0, "density_g_cm3",
          fmt::format("must be a finite density > 0 g/cm³, got {}", density_g_cm3));
  require(std::isfinite(m.real()) && m.real() > 0, "refractive_index.real",
          fmt::format("must be a finite number > 0, got {}", m.real()));
  require(std::isfinite(m.imag()) && m.imag() >= 0, "refractive_index.imag",
          fmt::format("must be a finite number >= 0 (k >= 0 is absorbing), got {}", m.imag()));
  require(options.fixed_intervals >= 0, "fixed_intervals",
          fmt::format("must be >= 0, got {}", options.fixed_intervals));
  return iv;
}

// Trapezoidal rule in u with nested halving: T_{2M} = T_M / 2 + h_{2M} Σ f(new
// midpoints), so every evaluation is reused. `node_sum` is Σ' f (end nodes
// weighted ½) over the current nodes; the estimate is h · node_sum. The
// nodes of a level are evaluated in parallel and summed in index order, so
// the result does not depend on the thread count.
class NestedTrapezoid {
 public:
  NestedTrapezoid(const SizeDistribution& dist, std::complex<double> m, double size_factor,
                  double x_max, const LnRadiusInterval& iv, int threads)
      : dist_(dist),
        m_(m),
        size_factor_(size_factor),
        lo_(iv.lo),
        width_(iv.hi - iv.lo),
        threads_(threads),
        // Threads pay off only for levels with enough work: starting a
        // parallel loop costs tens of µs, a Mie evaluation ~50 ns per term. The
        // bound uses the largest size parameter, so it overestimates the work.
        terms_per_node_(mie_term_count(x_max)) {}

  // The first level: `intervals` equal intervals.
  void start(int intervals) {
    add_nodes(intervals + 1,
              [&](std::size_t i) { return lo_ + width_ * static_cast<double>(i) / intervals; });
    // The end nodes carry half weight (the integrands are negligible there anyway).
    add_scaled(node_sum_, values_.front(), -0.5);
    add_scaled(node_sum_, values_.back(), -0.5);
    intervals_ = intervals;
    for (int i = 0; i < 4; ++i) estimate_[i] = node_sum_[i] * width_ / intervals_;
  }

  // The next level: the midpoints of the current intervals added.
  void halve() {
    const double h_new = width_ / (2 * intervals_);
    add_nodes(intervals_, [&](std::size_t i) { return lo_ + h_new * (2.0 * i + 1.0); });
    intervals_ *= 2;
    for (int i = 0; i < 4; ++i) estimate_[i] = node_sum_[i] * h_new;
  }

  int intervals() const { return intervals_; }
  const Sums& estimate() const { return estimate_; }

 private:
  // Integrand at u: p(u) r² (Q_ext, Q_sca, Q_abs, g Q_sca).
  Sums integrand(double u) const {
    const double r = std::exp(u);
    const double w = std::exp(log_density_in_ln_r(dist_, u)) * r * r;
    if (w == 0.0) return {0, 0, 0, 0};  // underflowed far tail: Mie not needed
    const MieEfficiencies q = mie_sphere(size_factor_ * r, m_);
    return {w * q.qext, w * q.qsca, w * q.qabs, w * q.g * q.qsca};
  }

  template <class UOf>
  void add_nodes(int count, UOf u_of) {
    values_.assign(count, Sums{});
    auto body = [&](std::size_t i) { values_[i] = integrand(u_of(i)); };
    if (count * terms_per_node_ > 2e5) {
      parallel_for(count, threads_, body);
    } else {
      for (int i = 0; i < count; ++i) body(i);
    }
    for (const Sums& v : values_) add_scaled(node_sum_, v, 1.0);
  }

  const SizeDistribution& dist_;
  std::complex<double> m_;
  double size_factor_;  // x = size_factor · r
  double lo_, width_;   // the interval in u
  int threads_;
  double terms_per_node_;
  Sums node_sum_{0, 0, 0, 0};
  std::vector<Sums> values_;
  int intervals_ = 0;
  Sums estimate_{};
};

// Changes are relative, except that a scattering or absorption share below
// 1e-3 of extinction is converged in absolute terms against 1e-3 α_ext: the
// weak absorption of water or oil droplets in the visible (α_abs ~ 1e-7 α_ext)
// sits mostly in narrow Mie resonances that no affordable step resolves,
// while ω = 1 − α_abs/α_ext is then known far better than any use needs.
double relative_change(const Sums& now, const Sums& before) {
  double worst = 0;
  const double floor = 1e-3 * std::abs(now[0]);
  for (int i = 0; i < 3; ++i)
    worst = std::max(worst, std::abs(now[i] - before[i]) / std::max(std::abs(now[i]), floor));
  const double g_now = now[1] > 0 ? now[3] / now[1] : 0.0;
  const double g_before = before[1] > 0 ? before[3] / before[1] : 0.0;
  return std::max(worst, std::abs(g_now - g_before));
}

// Halves the step until two successive halvings both change every quantity
// by less than the tolerance; returns the larger of those two changes. One
// agreement is not enough: while the step does not yet resolve the Mie ripple
// (spacing Δx ≈ 1 in size parameter, Bohren & Huffman §11.4) successive
// estimates scatter, and two of them can agree by chance; two in a row rarely
// do.
double refine(NestedTrapezoid& t, const BulkOpticsOptions& options, double wavelength_um) {
  const int start_intervals = t.intervals();
  double change = 0, last_change = 0;
  for (;;) {
    if (2 * t.intervals() > options.max_intervals)
      throw Error(
          fmt::format("bulk optics at {} µm: the size integral did not converge to {:g} within {} "
                      "intervals (last change {:.2g})",
                      wavelength_um, options.relative_tolerance, options.max_intervals, change));
    const Sums previous = t.estimate();
    t.halve();
    last_change = change;
    change = relative_change(t.estimate(), previous);
    if (t.intervals() >= 4 * start_intervals &&
        std::max(change, last_change) < options.relative_tolerance)
      return std::max(change, last_change);
  }
}

}  // namespace

BulkOptics bulk_optics(const SizeDistribution& dist, double wavelength_um, std::complex<double> m,
                       double density_g_cm3, const BulkOpticsOptions& options) {
  const LnRadiusInterval iv = checked_interval(dist, wavelength_um, m, density_g_cm3, options);
  const double size_factor = 2.0 * kPi / wavelength_um;  // x = size_factor · r
  const double x_max = size_factor * std::exp(iv.hi);
  if (x_max > kMaxMieSizeParameter) {
    const char* field = std::holds_alternative<LognormalDistribution>(dist)
                            ? "lognormal.geometric_std"
                            : "modified_gamma.gamma";
    throw InputError("", field,
                     fmt::format("the distribution reaches r = {:.4g} µm (size parameter {:.4g} "
                                 "at {} µm), beyond the Mie limit {:g}: narrow it",
                                 std::exp(iv.hi), x_max, wavelength_um, kMaxMieSizeParameter));
  }

  NestedTrapezoid trapezoid(dist, m, size_factor, x_max, iv, options.threads);
  trapezoid.start(options.fixed_intervals > 0 ? options.fixed_intervals : 128);
  const double change =
      options.fixed_intervals == 0 ? refine(trapezoid, options, wavelength_um) : 0.0;
  const Sums& estimate = trapezoid.estimate();

  // α = (3/(4ρ)) ∫ Q r² n dr / ∫ r³ n dr; the denominator in closed form.
  const double scale = 3.0 / (4.0 * density_g_cm3 * radius_moment_um(dist, 3.0));
  BulkOptics out;
  out.mass_extinction_m2_g = scale * estimate[0];
  out.mass_scattering_m2_g = scale * estimate[1];
  out.mass_absorption_m2_g = scale * estimate[2];
  out.single_scattering_albedo = estimate[0] > 0 ? estimate[1] / estimate[0] : 0.0;
  out.asymmetry = estimate[1] > 0 ? estimate[3] / estimate[1] : 0.0;
  out.intervals = trapezoid.intervals();
  out.relative_change = change;
  return out;
}

}  // namespace obscura
