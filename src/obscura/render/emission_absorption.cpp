#include "obscura/render/emission_absorption.h"

#include <array>
#include <cmath>

#include "obscura/core/error.h"

namespace obscura {
namespace {

// Deepest bisection of one segment; 2^-16 of a voxel is far below any feature
// the trilinear field can hold, so reaching it means the tolerance is met to
// rounding.
constexpr int kMaxDepth = 16;

using NodeArray = std::array<double, kMaxSpectralNodes>;

// The emission integrand e^{−τ(s)} σa(s) B(T(s)) for the nodes still being integrated.
struct SegmentIntegrand {
  int count = 0;
  std::array<Cubic, kMaxSpectralNodes> sigma_a;
  std::array<Cubic, kMaxSpectralNodes> sigma_t;
  std::array<const PlanckAtWavelength*, kMaxSpectralNodes> planck;
  Cubic temperature;
  std::uint64_t evals = 0;

  void operator()(double s, double* out) {
    ++evals;
    const double t = temperature(s);
    for (int j = 0; j < count; ++j)
      out[j] = std::exp(-sigma_t[j].integral(s)) * sigma_a[j](s) * (*planck[j])(t);
  }
};

// Adaptive Simpson on [a, b] for all nodes at once; bisects until every node's
// two-level estimates agree within 15 ε |I| (the Richardson factor of Simpson's
// rule), then adds the Richardson correction.
void adaptive_simpson(SegmentIntegrand& f, double a, double b, const double* fa, const double* fm,
                      const double* fb, const double* whole, double eps, int depth, double* result) {
  const int n = f.count;
  const double m = 0.5 * (a + b);
  NodeArray flm, frm, left, right;
  f(0.5 * (a + m), flm.data());
  f(0.5 * (m + b), frm.data());
  const double hl = (m - a) / 6.0, hr = (b - m) / 6.0;
  bool converged = true;
  for (int j = 0; j < n; ++j) {
    left[j] = hl * (fa[j] + 4.0 * flm[j] + fm[j]);
    right[j] = hr * (fm[j] + 4.0 * frm[j] + fb[j]);
    const double diff = left[j] + right[j] - whole[j];
    if (std::abs(diff) > 15.0 * eps * std::abs(left[j] + right[j])) converged = false;
  }
  if (converged || depth >= kMaxDepth) {
    for (int j = 0; j < n; ++j) {
      const double two = left[j] + right[j];
      result[j] += two + (two - whole[j]) / 15.0;
    }
    return;
  }
  adaptive_simpson(f, a, m, fa, flm.data(), fm, left.data(), eps, depth + 1, result);
  adaptive_simpson(f, m, b, fm, frm.data(), fb, right.data(), eps, depth + 1, result);
}

}  // namespace

void integrate_emission_absorption(const Medium* medium, const Ray& ray, double t_max,
                                   const SpectralNodes& nodes, double relative_tolerance,
                                   double* radiance, double* transmittance,
                                   EmissionAbsorptionStats* stats) {
  if (!medium) return;
  const int count = static_cast<int>(nodes.size());
  if (count > kMaxSpectralNodes) throw Error("emission-absorption: too many spectral nodes");
  const auto& node = nodes.nodes();
  SegmentIntegrand integrand;
  std::array<int, kMaxSpectralNodes> active;  // node index of each integrand slot
  NodeArray emitted, delta_tau;
  std::uint64_t segments = 0;

  medium->trace_segments(ray, 0.0, t_max, [&](const MediumSegment& seg) {
    ++segments;
    const double h = seg.t_end - seg.t_begin;
    const bool isothermal = seg.temperature.is_constant();
    integrand.count = 0;
    for (int i = 0; i < count; ++i) {
      const SpectralNode& nd = node[i];
      const Cubic sa = seg.sigma_a[nd.sample0] * (1.0 - nd.frac) + seg.sigma_a[nd.sample1] * nd.frac;
      const Cubic ss = seg.sigma_s[nd.sample0] * (1.0 - nd.frac) + seg.sigma_s[nd.sample1] * nd.frac;
      const Cubic st = sa + ss;
      delta_tau[i] = st.integral(h);
      emitted[i] = 0.0;
      if (sa.is_zero()) continue;
      if (isothermal && ss.is_zero()) {
        // σa = σt and B constant: ∫ e^{−τ} σt B ds = B (1 − e^{−Δτ}) exactly.
        emitted[i] = nd.planck(seg.temperature.c[0]) * -std::expm1(-delta_tau[i]);
        continue;
      }
      const int j = integrand.count++;
      integrand.sigma_a[j] = sa;
      integrand.sigma_t[j] = st;
      integrand.planck[j] = &nd.planck;
      active[j] = i;
    }
    if (integrand.count > 0) {
      integrand.temperature = seg.temperature;
      NodeArray fa, fm, fb, whole, result{};
      integrand(0.0, fa.data());
      integrand(0.5 * h, fm.data());
      integrand(h, fb.data());
      for (int j = 0; j < integrand.count; ++j) whole[j] = h / 6.0 * (fa[j] + 4.0 * fm[j] + fb[j]);
      adaptive_simpson(integrand, 0.0, h, fa.data(), fm.data(), fb.data(), whole.data(),
                       relative_tolerance, 0, result.data());
      for (int j = 0; j < integrand.count; ++j) emitted[active[j]] = result[j];
    }
    for (int i = 0; i < count; ++i) {
      radiance[i] += transmittance[i] * emitted[i];
      transmittance[i] *= std::exp(-delta_tau[i]);
    }
    return true;
  });
  if (stats) {
    stats->segments += segments;
    stats->integrand_evals += integrand.evals;
  }
}

}  // namespace obscura
