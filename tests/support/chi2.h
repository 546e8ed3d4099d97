#pragma once
// One chi-square goodness-of-fit harness for every sampler (docs/conventions.md §5, after
// Mitsuba 3's chi2.py and pbrt-v4's bsdfs_test.cpp): directions on the sphere
// (phase functions, sun cone, sky) and 1-D variables (free-flight distances).
//
// The harness draws n samples, bins them, and compares the counts with the
// expected counts n ∫_cell pdf, which it integrates itself with adaptive
// Gauss–Kronrod quadrature (never from the sampler's own CDF). Cells whose
// expected count is below 5 are pooled into one cell (Pearson's rule; the
// pooling of chi2.py: cells taken in increasing expected count, the pool filled
// until it holds at least 5). A cell with expected count 0 and any observed
// sample fails outright, as do non-finite samples and non-unit directions.
//
// Pass criterion: p_value > kChi2Alpha = 1e-3 for a test with one case; a test
// with k cases uses the Šidák threshold sidak_threshold(k) = 1 − (1 − 1e-3)^{1/k}
// so the whole test has a 0.1 % false-failure rate.
//
// Binning: the sphere is binned in (cos θ, φ) about `axis`, in the frame of
// Frame::from_normal(axis). Equal cos θ widths are equal solid angles. A peaked
// pdf (HG g = 0.99, the sun cone) needs edges that resolve the peak: pass your
// own cos θ edges, e.g. pole_refined_cos_theta_edges or cone_cos_theta_edges.
// Put edges on the pdf's discontinuities (a cone's rim, the horizon): the
// quadrature then only sees smooth integrands.
//
// A new sampler needs a few lines:
//   const auto r = chi2_sphere([&](Rng& rng) { return sample(rng.uniform(), rng.uniform()); },
//                              [&](const Vec3& d) { return pdf(d); }, 1000000, 20, 40, 7);
//   EXPECT_TRUE(chi2_passes("my sampler", r));
#include <gtest/gtest.h>

#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "obscura/core/mat3.h"
#include "obscura/core/rng.h"
#include "obscura/core/vec3.h"

namespace obscura::testing {

// Significance level of one chi-square case.
inline constexpr double kChi2Alpha = 1e-3;

// Per-case threshold for k cases in one test (Šidák): 1 − (1 − alpha)^{1/k}.
inline double sidak_threshold(int k, double alpha = kChi2Alpha) {
  return -std::expm1(std::log1p(-alpha) / k);
}

struct Chi2Result {
  double statistic = 0.0;     // Pearson's χ² after pooling (+inf on an outright failure)
  int dof = 0;                // cells after pooling − 1
  double p_value = 0.0;       // P(χ²_dof ≥ statistic); 0 on an outright failure
  std::string table;          // human-readable summary: observed vs expected, worst cells
  double pdf_integral = 0.0;  // ∫ pdf over the binned domain (≈ 1 for a normalised pdf)
};

// ---------------------------------------------------------------------------
// Quadrature, shared with tests that check normalisations.

// ∫_a^b f by adaptive 15-point Gauss–Kronrod, relative tolerance 1e-9 (an
// expected count n p needs only ≪ 1/√(n p) relative accuracy; a tighter
// tolerance chases the rounding noise of pdfs evaluated through a dot product
// near a sharp peak, and the nested sphere quadrature pays for it squared). The
// nodes are interior, so a discontinuity on an endpoint is harmless. The
// interval is mapped onto [−1, 1] here because Boost 1.74 compares its error
// estimate, taken before scaling by the half-width, with a scaled tolerance: on
// a narrow interval (a cos θ band of the sun cone, 1e-6 wide) it never
// converges.
inline double integrate_1d(const std::function<double(double)>& f, double a, double b) {
  if (!(b > a)) return 0.0;
  const double mid = 0.5 * (a + b), half = 0.5 * (b - a);
  return half * boost::math::quadrature::gauss_kronrod<double, 15>::integrate(
                    [&](double t) { return f(mid + half * t); }, -1.0, 1.0, 15, 1e-9);
}

// ∫ f dΩ over the patch c0 ≤ cos θ ≤ c1, φ0 ≤ φ ≤ φ1 of the sphere, θ and φ
// measured in `frame` (dΩ = dcos θ dφ). Nested: φ inside, cos θ outside.
inline double integrate_sphere_patch(const std::function<double(const Vec3&)>& f,
                                     const Frame& frame, double c0, double c1, double phi0,
                                     double phi1) {
  return integrate_1d(
      [&](double c) {
        const double s = std::sqrt(std::max(0.0, (1.0 - c) * (1.0 + c)));
        return integrate_1d(
            [&](double phi) {
              return f(frame.to_world({s * std::cos(phi), s * std::sin(phi), c}));
            },
            phi0, phi1);
      },
      c0, c1);
}

// ∫ f dΩ over the whole sphere, split into cos θ bands at `cos_theta_edges`
// (about `axis`): put edges on f's discontinuities and peaks.
inline double integrate_sphere(const std::function<double(const Vec3&)>& f,
                               const std::vector<double>& cos_theta_edges = {-1.0, 0.0, 1.0},
                               const Vec3& axis = {0, 0, 1}) {
  const Frame frame = Frame::from_normal(normalize(axis));
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < cos_theta_edges.size(); ++i)
    sum += integrate_sphere_patch(f, frame, cos_theta_edges[i], cos_theta_edges[i + 1], 0.0,
                                  2.0 * std::numbers::pi);
  return sum;
}

// ---------------------------------------------------------------------------
// Bin edges in cos θ, each list from −1 to 1, strictly increasing.

// `bins` equal widths: equal solid angles.
inline std::vector<double> uniform_cos_theta_edges(int bins) {
  std::vector<double> e(bins + 1);
  for (int i = 0; i <= bins; ++i) e[i] = -1.0 + 2.0 * i / bins;
  e.back() = 1.0;
  return e;
}

// Edges geometric in the distance to each pole: on [0, 1], 1 − cos θ takes the
// values 1, r, r², …, finest, 0 (r = finest^{1/(n−1)}, n = bins_per_hemisphere),
// mirrored on [−1, 0]. Resolves pdfs peaked at either pole (HG with |g| → 1).
inline std::vector<double> pole_refined_cos_theta_edges(int bins_per_hemisphere, double finest) {
  const int n = bins_per_hemisphere;
  std::vector<double> gaps(n);  // 1, r, …, finest
  for (int k = 0; k < n; ++k) gaps[k] = n == 1 ? 1.0 : std::pow(finest, double(k) / (n - 1));
  std::vector<double> e;
  e.push_back(-1.0);
  for (int k = n - 1; k >= 1; --k) e.push_back(-1.0 + gaps[k]);
  e.push_back(0.0);
  for (int k = 1; k < n; ++k) e.push_back(1.0 - gaps[k]);
  e.push_back(1.0);
  return e;
}

// [−1, cos θmax] as one band (empty if cos θmax = −1), then `bins_inside` bands
// of equal solid angle inside the cone, written as 1 − (1 − cos θmax)(1 − k/n)
// to keep tiny cones exact.
inline std::vector<double> cone_cos_theta_edges(double cos_theta_max, int bins_inside) {
  std::vector<double> e{-1.0};
  if (cos_theta_max > -1.0) e.push_back(cos_theta_max);
  const double h = 1.0 - cos_theta_max;
  for (int k = 1; k < bins_inside; ++k) e.push_back(1.0 - h * (1.0 - double(k) / bins_inside));
  e.push_back(1.0);
  return e;
}

// ---------------------------------------------------------------------------
namespace chi2_detail {

struct Pearson {
  double statistic = 0.0;
  int dof = 0;
  double p_value = 0.0;
  int pooled_cells = 0;
  std::string failure;  // non-empty: an outright failure
};

// Pearson's χ² of observed against expected counts, with chi2.py's pooling.
inline Pearson pearson(const std::vector<double>& observed, const std::vector<double>& expected,
                       const std::function<std::string(int)>& label) {
  Pearson out;
  const int n = static_cast<int>(observed.size());
  for (int k = 0; k < n; ++k)
    if (!(std::isfinite(expected[k]) && expected[k] >= 0.0)) {
      out.failure = "expected count " + std::to_string(expected[k]) +
                    " (pdf not finite or < 0) in " + label(k);
      return out;
    }
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return expected[a] < expected[b]; });
  double pool_o = 0.0, pool_e = 0.0;
  int cells = 0;
  for (int k : order) {
    if (expected[k] == 0.0) {
      if (observed[k] > 0.0) {
        out.failure = std::to_string(static_cast<long long>(observed[k])) +
                      " samples where the pdf integrates to 0: " + label(k);
        return out;
      }
      continue;  // no information either way
    }
    if (expected[k] < 5.0 || (out.pooled_cells > 0 && pool_e < 5.0)) {
      pool_o += observed[k];
      pool_e += expected[k];
      ++out.pooled_cells;
    } else {
      out.statistic += (observed[k] - expected[k]) * (observed[k] - expected[k]) / expected[k];
      ++cells;
    }
  }
  if (out.pooled_cells > 0) {
    out.statistic += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
    ++cells;
  }
  out.dof = cells - 1;
  if (out.dof < 1) {
    out.failure = "fewer than two cells with expected counts: binning too coarse";
    return out;
  }
  const boost::math::chi_squared dist(out.dof);
  out.p_value = boost::math::cdf(boost::math::complement(dist, out.statistic));
  return out;
}

inline std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}

// Summary line, then the rows given, then the cells contributing most to χ².
inline Chi2Result finish(const Pearson& p, const std::vector<double>& observed,
                         const std::vector<double>& expected, double pdf_integral,
                         const std::function<std::string(int)>& label, const std::string& rows) {
  Chi2Result r;
  r.pdf_integral = pdf_integral;
  if (!p.failure.empty()) {
    r.statistic = std::numeric_limits<double>::infinity();
    r.dof = p.dof;
    r.p_value = 0.0;
    r.table = "chi-square FAILED outright: " + p.failure + "\n";
  } else {
    r.statistic = p.statistic;
    r.dof = p.dof;
    r.p_value = p.p_value;
    r.table = format("chi2 = %.4g, dof = %.0f, p = %.4g; ", p.statistic, p.dof, p.p_value) +
              format("%.0f cells pooled; pdf integral %.10f\n", p.pooled_cells, pdf_integral);
  }
  r.table += rows;
  std::vector<int> order(observed.size());
  std::iota(order.begin(), order.end(), 0);
  auto contribution = [&](int k) {
    const double e = expected[k], o = observed[k];
    return e > 0.0 ? (o - e) * (o - e) / e
                   : (o > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  };
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return contribution(a) > contribution(b); });
  r.table += "largest contributions:\n";
  for (std::size_t i = 0; i < std::min<std::size_t>(8, order.size()); ++i) {
    const int k = order[i];
    r.table += "  " + label(k) +
               format(": observed %.0f, expected %.2f, (O-E)^2/E %.3g\n", observed[k], expected[k],
                      contribution(k));
  }
  return r;
}

inline std::string invalid_failure(long long invalid, const char* what) {
  return "chi-square FAILED outright: " + std::to_string(invalid) + " samples " + what + "\n";
}

// Pearson's test on the cells, then an outright failure if any sample was
// invalid (`what` says how).
inline Chi2Result conclude(const std::vector<double>& observed, const std::vector<double>& expected,
                           double pdf_integral, const std::function<std::string(int)>& label,
                           const std::string& rows, long long invalid, const char* what) {
  Chi2Result r =
      finish(pearson(observed, expected, label), observed, expected, pdf_integral, label, rows);
  if (invalid > 0) {
    r.statistic = std::numeric_limits<double>::infinity();
    r.p_value = 0.0;
    r.table = invalid_failure(invalid, what) + r.table;
  }
  return r;
}

}  // namespace chi2_detail

// ---------------------------------------------------------------------------
// Directions: `sampler` draws a unit vector from the Rng it is given (one
// stream, Rng(seed, 0)); `pdf` is its density per steradian. Cells: the cos θ
// bands of `cos_theta_edges` (−1 … 1, strictly increasing) × `phi_bins` equal
// azimuth sectors about `axis`.
inline Chi2Result chi2_sphere(const std::function<Vec3(Rng&)>& sampler,
                              const std::function<double(const Vec3&)>& pdf, int n_samples,
                              const std::vector<double>& cos_theta_edges, int phi_bins,
                              std::uint64_t seed, const Vec3& axis = {0, 0, 1}) {
  const std::vector<double>& edges = cos_theta_edges;
  const int bands = static_cast<int>(edges.size()) - 1;
  if (bands < 1 || edges.front() != -1.0 || edges.back() != 1.0 ||
      !std::is_sorted(edges.begin(), edges.end(), std::less_equal<double>()) || phi_bins < 1 ||
      n_samples < 1)
    throw std::invalid_argument(
        "chi2_sphere: cos θ edges must run from −1 to 1, strictly increasing; phi_bins, n ≥ 1");
  const Frame frame = Frame::from_normal(normalize(axis));
  const double two_pi = 2.0 * std::numbers::pi;
  const int cells = bands * phi_bins;

  std::vector<double> observed(cells, 0.0);
  long long invalid = 0;
  Rng rng(seed, 0);
  for (int s = 0; s < n_samples; ++s) {
    const Vec3 d = sampler(rng);
    if (!is_finite(d) || std::abs(length(d) - 1.0) > 1e-6) {
      ++invalid;
      continue;
    }
    const Vec3 local = frame.to_local(d);
    const double c = std::clamp(local.z, -1.0, 1.0);
    const int band = static_cast<int>(std::upper_bound(edges.begin() + 1, edges.end() - 1, c) -
                                      (edges.begin() + 1));
    double phi = std::atan2(local.y, local.x);
    if (phi < 0.0) phi += two_pi;
    const int sector = std::min(static_cast<int>(phi / two_pi * phi_bins), phi_bins - 1);
    observed[band * phi_bins + sector] += 1.0;
  }

  std::vector<double> expected(cells, 0.0);
  double integral = 0.0;
  for (int i = 0; i < bands; ++i)
    for (int j = 0; j < phi_bins; ++j) {
      const double p = integrate_sphere_patch(pdf, frame, edges[i], edges[i + 1],
                                              two_pi * j / phi_bins, two_pi * (j + 1) / phi_bins);
      integral += p;
      expected[i * phi_bins + j] = p * n_samples;
    }

  auto label = [&](int k) {
    const int i = k / phi_bins, j = k % phi_bins;
    return chi2_detail::format("cos θ [%.9g, %.9g] φ [%.1f°, %.1f°]", edges[i], edges[i + 1],
                               360.0 * j / phi_bins, 360.0 * (j + 1) / phi_bins);
  };
  std::string rows = "per cos θ band (summed over φ):\n";
  for (int i = 0; i < bands; ++i) {
    double o = 0.0, e = 0.0;
    for (int j = 0; j < phi_bins; ++j) {
      o += observed[i * phi_bins + j];
      e += expected[i * phi_bins + j];
    }
    rows += chi2_detail::format("  cos θ [%.9g, %.9g]: ", edges[i], edges[i + 1]) +
            chi2_detail::format("observed %.0f, expected %.2f, (O-E)/sqrt(E) %.3g\n", o, e,
                                e > 0.0 ? (o - e) / std::sqrt(e) : 0.0);
  }
  return chi2_detail::conclude(observed, expected, integral, label, rows, invalid,
                               "not finite or not unit length");
}

// Equal-solid-angle bins: `theta_bins` equal cos θ bands × `phi_bins` sectors.
inline Chi2Result chi2_sphere(const std::function<Vec3(Rng&)>& sampler,
                              const std::function<double(const Vec3&)>& pdf, int n_samples,
                              int theta_bins, int phi_bins, std::uint64_t seed,
                              const Vec3& axis = {0, 0, 1}) {
  return chi2_sphere(sampler, pdf, n_samples, uniform_cos_theta_edges(theta_bins), phi_bins, seed,
                     axis);
}

// ---------------------------------------------------------------------------
// 1-D variables: `sampler` draws x from the Rng (stream Rng(seed, 0)), `pdf` is
// its density. Cells: [edges[k], edges[k+1]) for increasing `edges`, plus one
// cell for everything outside [edges.front(), edges.back()] (±inf included),
// expecting n (1 − ∫ pdf over the edges). So a density on [0, ∞), e.g. a
// free-flight distance, can be tested on a finite range. NaN samples fail.
inline Chi2Result chi2_1d(const std::function<double(Rng&)>& sampler,
                          const std::function<double(double)>& pdf,
                          const std::vector<double>& edges, int n_samples, std::uint64_t seed) {
  const int bins = static_cast<int>(edges.size()) - 1;
  if (bins < 1 || !std::is_sorted(edges.begin(), edges.end(), std::less_equal<double>()) ||
      n_samples < 1)
    throw std::invalid_argument("chi2_1d: edges must be strictly increasing; n ≥ 1");
  const double lo = edges.front(), hi = edges.back();

  std::vector<double> observed(bins + 1, 0.0);  // the last cell: outside [lo, hi]
  long long nan_count = 0;
  Rng rng(seed, 0);
  for (int s = 0; s < n_samples; ++s) {
    const double x = sampler(rng);
    if (std::isnan(x)) {
      ++nan_count;
    } else if (x < lo || x > hi) {
      observed[bins] += 1.0;
    } else {
      const int k = static_cast<int>(std::upper_bound(edges.begin() + 1, edges.end() - 1, x) -
                                     (edges.begin() + 1));
      observed[k] += 1.0;
    }
  }

  std::vector<double> expected(bins + 1, 0.0);
  double integral = 0.0;
  for (int k = 0; k < bins; ++k) {
    const double p = integrate_1d(pdf, edges[k], edges[k + 1]);
    integral += p;
    expected[k] = p * n_samples;
  }
  // The mass outside; below 1e-9 it is quadrature noise, and any sample there fails.
  const double outside = 1.0 - integral;
  expected[bins] = outside > 1e-9 ? outside * n_samples : 0.0;

  auto label = [&](int k) {
    return k < bins ? chi2_detail::format("x [%.9g, %.9g)", edges[k], edges[k + 1])
                    : chi2_detail::format("x outside [%.9g, %.9g]", lo, hi);
  };
  std::string rows;
  if (bins + 1 <= 64) {
    rows = "cells:\n";
    for (int k = 0; k <= bins; ++k)
      rows += "  " + label(k) +
              chi2_detail::format(
                  ": observed %.0f, expected %.2f, (O-E)/sqrt(E) %.3g\n", observed[k], expected[k],
                  expected[k] > 0.0 ? (observed[k] - expected[k]) / std::sqrt(expected[k]) : 0.0);
  }
  return chi2_detail::conclude(observed, expected, integral, label, rows, nan_count, "NaN");
}

// `bins` equal widths on [lo, hi], plus the outside cell.
inline Chi2Result chi2_1d(const std::function<double(Rng&)>& sampler,
                          const std::function<double(double)>& pdf, double lo, double hi, int bins,
                          int n_samples, std::uint64_t seed) {
  std::vector<double> edges(bins + 1);
  for (int k = 0; k <= bins; ++k) edges[k] = lo + (hi - lo) * k / bins;
  edges.back() = hi;
  return chi2_1d(sampler, pdf, edges, n_samples, seed);
}

// ---------------------------------------------------------------------------
// GoogleTest glue: prints one line per case (name, χ², dof, p) and passes when
// p > threshold; on failure the message carries the table.
//   EXPECT_TRUE(chi2_passes("HG g=0.5", result, sidak_threshold(6)));
inline ::testing::AssertionResult chi2_passes(const std::string& name, const Chi2Result& r,
                                              double threshold = kChi2Alpha) {
  std::printf("[ chi2     ] %-40s chi2 = %10.4g  dof = %4d  p = %.4g  (threshold %.3g)\n",
              name.c_str(), r.statistic, r.dof, r.p_value, threshold);
  std::fflush(stdout);
  if (r.p_value > threshold) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << name << ": p = " << r.p_value << " <= " << threshold << "\n"
         << r.table;
}

}  // namespace obscura::testing
