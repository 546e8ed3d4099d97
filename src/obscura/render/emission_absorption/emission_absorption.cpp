#include "obscura/render/emission_absorption/emission_absorption.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/render/emission_absorption/emission_marcher.h"

namespace obscura {
namespace {

// Deepest bisection of one segment; 2^-16 of a voxel is far below any feature
// the trilinear field can hold, so reaching it means the tolerance is met to
// rounding.
constexpr int kMaxDepth = 16;

using NodeArray = std::array<double, kMaxSpectralNodes>;

// The emission integrand e^{−τ(s)} Σ_c σa,c(s) B(T_c(s)) for the spectral nodes
// still being integrated ("slots"), summed over the segment's components.
struct SegmentIntegrand {
  int count = 0;       // slots
  int components = 0;  // overlapping media
  std::array<Cubic, kMaxSpectralNodes> sigma_t;
  std::array<const PlanckAtWavelength*, kMaxSpectralNodes> planck;
  std::vector<Cubic> sigma_a;      // [component * kMaxSpectralNodes + slot]
  std::vector<Cubic> temperature;  // per component
  std::uint64_t evals = 0;

  void prepare(int component_count) {
    components = component_count;
    if (static_cast<int>(temperature.size()) < component_count) {
      temperature.resize(component_count);
      sigma_a.resize(static_cast<std::size_t>(component_count) * kMaxSpectralNodes);
    }
  }
  Cubic& sa(int c, int j) { return sigma_a[static_cast<std::size_t>(c) * kMaxSpectralNodes + j]; }
  const Cubic& sa(int c, int j) const {
    return sigma_a[static_cast<std::size_t>(c) * kMaxSpectralNodes + j];
  }

  // The source Σ_c σa,c B(T_c) at s, per slot.
  void source(double s, double* out) const {
    if (components == 1) {  // the common case: one cloud here
      const double t = temperature[0](s);
      for (int j = 0; j < count; ++j) out[j] = sa(0, j)(s) * (*planck[j])(t);
      return;
    }
    for (int j = 0; j < count; ++j) out[j] = 0.0;
    for (int c = 0; c < components; ++c) {
      const double t = temperature[c](s);
      for (int j = 0; j < count; ++j) {
        const double a = sa(c, j)(s);
        if (a != 0.0) out[j] += a * (*planck[j])(t);
      }
    }
  }
  void operator()(double s, double* out) {
    ++evals;
    source(s, out);
    for (int j = 0; j < count; ++j) out[j] *= std::exp(-sigma_t[j].integral(s));
  }
  // The same, also returning the source and the attenuation e^{−τ} apart.
  void split(double s, double* out, double* src, double* attenuation) {
    ++evals;
    source(s, src);
    for (int j = 0; j < count; ++j) {
      attenuation[j] = std::exp(-sigma_t[j].integral(s));
      out[j] = attenuation[j] * src[j];
    }
  }
};

// Adaptive Simpson on [a, b] for all slots at once (Lyness 1969); bisects
// until every slot's two-level estimates agree within 15 tol (the Richardson
// factor of Simpson's rule), each half then allowed half the tolerance, and
// adds the Richardson correction. `tol` is absolute per slot: a relative test
// on each piece alone would chase pieces whose contribution is negligible
// (a nearly empty corner of a cell) to the deepest level.
void adaptive_simpson(SegmentIntegrand& f, double a, double b, const double* fa, const double* fm,
                      const double* fb, const double* whole, const double* tol, int depth,
                      double* result) {
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
    if (std::abs(diff) > 15.0 * tol[j]) converged = false;
  }
  if (converged || depth >= kMaxDepth) {
    for (int j = 0; j < n; ++j) {
      const double two = left[j] + right[j];
      result[j] += two + (two - whole[j]) / 15.0;
    }
    return;
  }
  NodeArray half;
  for (int j = 0; j < n; ++j) half[j] = 0.5 * tol[j];
  adaptive_simpson(f, a, m, fa, flm.data(), fm, left.data(), half.data(), depth + 1, result);
  adaptive_simpson(f, m, b, fm, frm.data(), fb, right.data(), half.data(), depth + 1, result);
}

// A component's cubic at a spectral node: linear in wavelength between the
// medium's samples.
inline Cubic at_node(const Cubic* per_sample, const SpectralNode& nd) {
  return per_sample[nd.sample0] * (1.0 - nd.frac) + per_sample[nd.sample1] * nd.frac;
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
  NodeArray emitted, delta_tau, segment_transmittance;
  NodeArray start_source;  // per slot: source at s = 0, or −1 if unknown
  // The source at the end of the previous segment, per node: where the fields
  // are continuous across the face it is the next segment's starting value.
  NodeArray source_end;
  std::array<bool, kMaxSpectralNodes> source_end_valid{};
  std::uint64_t segments = 0;

  medium->trace_segments(ray, 0.0, t_max, [&](const MediumSegment& seg) {
    ++segments;
    const double h = seg.t_end - seg.t_begin;
    const int nc = seg.component_count;
    integrand.prepare(nc);
    integrand.count = 0;
    for (int i = 0; i < count; ++i) {
      const SpectralNode& nd = node[i];
      Cubic st;
      bool emits = false, scatters = false;
      const int j_next = integrand.count;  // the slot this node takes if it needs quadrature
      for (int c = 0; c < nc; ++c) {
        Cubic& sa = integrand.sa(c, j_next);
        sa = at_node(seg.components[c].sigma_a, nd);
        const Cubic ss = at_node(seg.components[c].sigma_s, nd);
        st += sa + ss;
        emits = emits || !sa.is_zero();
        scatters = scatters || !ss.is_zero();
      }
      delta_tau[i] = st.integral(h);
      emitted[i] = 0.0;
      segment_transmittance[i] = -1.0;  // computed below
      const bool reuse = seg.continuous_with_previous && source_end_valid[i];
      source_end_valid[i] = false;
      if (!emits) continue;
      if (nc == 1 && !scatters && seg.components[0].temperature.is_constant()) {
        // σa = σt and B constant: ∫ e^{−τ} σt B ds = B (1 − e^{−Δτ}) exactly.
        emitted[i] = nd.planck(seg.components[0].temperature.c[0]) * -std::expm1(-delta_tau[i]);
        continue;
      }
      const int j = integrand.count++;  // == j_next: its σa cubics are already in place
      integrand.sigma_t[j] = st;
      integrand.planck[j] = &nd.planck;
      active[j] = i;
      start_source[j] = reuse ? source_end[i] : -1.0;
    }
    if (integrand.count > 0) {
      for (int c = 0; c < nc; ++c) integrand.temperature[c] = seg.components[c].temperature;
      const int n = integrand.count;
      // First level of adaptive Simpson on [0, h] with its two halves: five
      // points, of which s = 0 needs no exponential (τ = 0) and its source is
      // usually the previous segment's end value.
      NodeArray f0, fq1, fm, fq3, fh, src, att, whole, left, right, result;
      std::fill_n(result.begin(), n, 0.0);
      bool need_start = false;
      for (int j = 0; j < n; ++j) need_start = need_start || start_source[j] < 0.0;
      if (need_start) integrand.source(0.0, f0.data());
      for (int j = 0; j < n; ++j)
        if (start_source[j] >= 0.0) f0[j] = start_source[j];
      integrand(0.25 * h, fq1.data());
      integrand(0.5 * h, fm.data());
      integrand(0.75 * h, fq3.data());
      integrand.split(h, fh.data(), src.data(), att.data());
      // The tolerance of the segment, absolute: the relative tolerance of the
      // larger of its emission and the radiance gathered so far (which the
      // segment's emission adds to, seen through the transmittance so far).
      NodeArray tol;
      bool converged = true;
      for (int j = 0; j < n; ++j) {
        whole[j] = h / 6.0 * (f0[j] + 4.0 * fm[j] + fh[j]);
        left[j] = h / 12.0 * (f0[j] + 4.0 * fq1[j] + fm[j]);
        right[j] = h / 12.0 * (fm[j] + 4.0 * fq3[j] + fh[j]);
        const int i = active[j];
        const double so_far =
            transmittance[i] > 0.0 ? std::abs(radiance[i]) / transmittance[i] : 0.0;
        tol[j] = relative_tolerance * std::max(std::abs(left[j] + right[j]), so_far);
        const double diff = left[j] + right[j] - whole[j];
        if (std::abs(diff) > 15.0 * tol[j]) converged = false;
      }
      if (converged) {
        for (int j = 0; j < n; ++j) {
          const double two = left[j] + right[j];
          result[j] = two + (two - whole[j]) / 15.0;
        }
      } else {
        NodeArray half;
        for (int j = 0; j < n; ++j) half[j] = 0.5 * tol[j];
        adaptive_simpson(integrand, 0.0, 0.5 * h, f0.data(), fq1.data(), fm.data(), left.data(),
                         half.data(), 1, result.data());
        adaptive_simpson(integrand, 0.5 * h, h, fm.data(), fq3.data(), fh.data(), right.data(),
                         half.data(), 1, result.data());
      }
      for (int j = 0; j < n; ++j) {
        const int i = active[j];
        emitted[i] = result[j];
        source_end[i] = src[j];
        source_end_valid[i] = true;
        segment_transmittance[i] = att[j];  // e^{−τ(h)}, already computed
      }
    }
    for (int i = 0; i < count; ++i) {
      radiance[i] += transmittance[i] * emitted[i];
      transmittance[i] *=
          segment_transmittance[i] >= 0.0 ? segment_transmittance[i] : std::exp(-delta_tau[i]);
    }
    return true;
  });
  if (stats) {
    stats->segments += segments;
    stats->integrand_evals += integrand.evals;
  }
}

void integrate_emission_cells(const Medium* medium, const Ray& ray, double t_max,
                              const SpectralNodes& nodes, double* radiance, double* transmittance,
                              EmissionAbsorptionStats* stats) {
  if (!medium) return;
  OBSCURA_CHECK(nodes.size() <= static_cast<std::size_t>(kMaxSpectralNodes));
  NoInScattering none;
  EmissionMarcher<NoInScattering> marcher(nodes, none, radiance, transmittance);
  medium->march_cells(ray, 0.0, t_max, {}, marcher);
  if (stats) {
    stats->segments += marcher.cells();
    stats->integrand_evals += 2 * marcher.cells();
  }
}

void integrate_emission(const Medium* medium, const Ray& ray, double t_max,
                        const SpectralNodes& nodes, EmissionQuadrature quadrature,
                        double relative_tolerance, double* radiance, double* transmittance,
                        EmissionAbsorptionStats* stats) {
  if (quadrature == EmissionQuadrature::kCell)
    integrate_emission_cells(medium, ray, t_max, nodes, radiance, transmittance, stats);
  else
    integrate_emission_absorption(medium, ray, t_max, nodes, relative_tolerance, radiance,
                                  transmittance, stats);
}

}  // namespace obscura
