#pragma once
// The radiance cache's source for the lattice march
// (render/lattice/lattice_view_march.h; docs/physics.md, "The radiance
// cache"): σt and ε = σa B(T) + σs J, with the in-scattered radiance
//   J(x, ω) = E_sun p_HG(ω_sun·ω) V_sun e^{−τ_sun(x)} + Σ_l g^l Σ_m Y_lm(ω) c_lm(x)
//             [+ J_peak(x): the phase function beyond the harmonics, towards
//               the ray's sensor, where the cache holds it]
// from the record's light channels, g = (σs g)/σs. A ray with no such peak
// takes delta-M instead (Wiscombe 1977; docs/physics.md): the phase
// function's moments beyond degree L as those of a forward peak f δ, f =
// g^{L+1}, which keeps f σs L(x, ω) in the ray's own direction. The
// harmonics are then weighted g^l − f, and the radiance's extinction along
// the ray is σt − f σs (the march's `forward`, lattice_view_march.h), while
// the transmittance stays exact. Plain data, so that a
// CUDA device runs it too (docs/gpu.md); the CPU's march over the medium's
// cells (cache_march.cpp) reads the same CacheLight.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "obscura/core/fast_exp.h"
#include "obscura/core/host_device.h"
#include "obscura/core/planck_table.h"
#include "obscura/core/vec3.h"
#include "obscura/render/lattice/lattice_view.h"
#include "obscura/render/radiance_cache/spherical_harmonics.h"

namespace obscura {

// p_HG(μ) per steradian (medium/phase_function.h has the careful form; here g
// is clamped to |g| ≤ 0.999999, where this one is exact to rounding).
OBSCURA_HOST_DEVICE inline double cache_hg(double g, double mu) {
  const double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) * (0.25 * std::numbers::inv_pi) / (d * std::sqrt(d));
}

OBSCURA_HOST_DEVICE inline double cache_clamped_g(double g) {
  return std::clamp(g, -0.999999, 0.999999);
}

// What the spherical harmonics to `degree` leave out of the HG phase
// function at cosine μ (per steradian):
//   q(μ; g) = p_HG(μ) − Σ_{l ≤ degree} (2l + 1)/(4π) g^l P_l(μ),
// whose integral against any P_l, l ≤ degree, over the sphere is zero. The
// radiance cache splats it towards a narrow sensor's viewing direction (the
// forward peak the truncated expansion misses; flight_splat.h), for one μ
// per flight and many g along it: the P_l(μ) are kept.
class HgBeyondDegree {
 public:
  HgBeyondDegree() = default;
  OBSCURA_HOST_DEVICE HgBeyondDegree(double mu, int degree)
      : mu_(mu),
        p_{1.0, mu, 0.5 * (3.0 * mu * mu - 1.0), 0.5 * mu * (5.0 * mu * mu - 3.0)},
        degree_(degree < kMaxShDegree ? degree : kMaxShDegree) {
    // Bonnet's recurrence l P_l = (2l − 1) μ P_{l−1} − (l − 1) P_{l−2}.
    for (int l = 4; l <= degree_; ++l)
      p_[l] = ((2 * l - 1) * mu * p_[l - 1] - (l - 1) * p_[l - 2]) / l;
  }

  OBSCURA_HOST_DEVICE double operator()(double g) const {
    double kept = 0.0, g_l = 1.0;
    for (int l = 0; l <= degree_; ++l) {
      kept += (2 * l + 1) * g_l * p_[l];
      g_l *= g;
    }
    return cache_hg(g, mu_) - kept * (0.25 * std::numbers::inv_pi);
  }

 private:
  double mu_ = 0.0;
  double p_[kMaxShDegree + 1] = {};  // P_0 … P_degree at μ
  int degree_ = 0;
};

OBSCURA_HOST_DEVICE inline double hg_beyond_degree(double g, double mu, int degree) {
  return HgBeyondDegree(mu, degree)(g);
}

// What every point of one camera ray shares: the harmonics of the direction
// the light travels (towards the camera), the sun's cosine with it, the
// sun's irradiance at each node of the march, and which light channel holds
// the forward peak beyond the harmonics towards this ray's sensor (none:
// delta-M).
struct CacheLight {
  std::array<double, kMaxShCoefficients> y{};
  double mu_sun = 0.0;
  const double* sun_irradiance = nullptr;  // per node j, W m⁻² µm⁻¹ (0 without a sun)
  int sh_degree = 0;
  int peak = -1;  // index from record::kTauSun (RadianceCache::peak_channel); −1: none
#if !OBSCURA_DEVICE_CODE
  HgConvolution convolution;  // the CPU's form of hg_convolved with y
#endif

  // For a camera ray along unit `direction`; `to_sun` is the unit direction
  // towards the sun when `sun`.
  OBSCURA_HOST_DEVICE CacheLight(const Vec3& direction, bool sun, const Vec3& to_sun,
                                 const double* irradiance, int degree, int peak_channel = -1)
      : mu_sun(sun ? dot(to_sun, direction) : 0.0),
        sun_irradiance(irradiance),
        sh_degree(degree),
        peak(peak_channel) {
    spherical_harmonics(-direction, y, degree);
#if !OBSCURA_DEVICE_CODE
    convolution = HgConvolution(y, degree);
#endif
  }

  // Delta-M's f = g^{L+1} at a point of asymmetry g, where the ray has no
  // forward peak and g > 0 (0 otherwise: a backward or isotropic phase
  // function has no forward peak to keep).
  OBSCURA_HOST_DEVICE double forward_fraction(double g) const {
    if (peak >= 0 || !(g > 0.0)) return 0.0;
    double f = g;
    for (int l = 0; l < sh_degree; ++l) f *= g;
    return f;
  }

  // J at node j from the point's g and light channels (`light` from
  // record::kTauSun on, interpolated; on the CPU readable up to
  // HgConvolution::readable(sh_degree) harmonics), the harmonics weighted
  // g^l − f (f from forward_fraction). Not clamped at zero: the photon
  // estimate is linear in the photons, so its noise (which can make a
  // truncated expansion dip below zero) averages out along the ray.
  OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE double in_scattered(int j, double g, double f,
                                                                const float* light) const {
    double sun;
    return in_scattered(j, g, f, light, sun);
  }
  // The same, and the sun's part of it alone in `sun` (what falls off as
  // e^{−τ_sun}: sun_scattered).
  OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE double in_scattered(int j, double g, double f,
                                                                const float* light,
                                                                double& sun) const {
    double j_in = sun = sun_scattered(j, g, light);
#if OBSCURA_DEVICE_CODE
    j_in += hg_convolved(light + 2, y, g, sh_degree, f);
#else
    j_in += convolution(light + 2, g, f);
#endif
    return peak >= 0 ? j_in + light[peak] : j_in;
  }
  // The sun's light scattered once at the point: E_sun p_HG V_sun e^{−τ_sun}
  // (`light` as in_scattered's; only its first two channels are read).
  OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE double sun_scattered(int j, double g,
                                                                 const float* light) const {
    static_assert(record::kSunVisibility == record::kTauSun + 1 &&
                  record::kSh == record::kTauSun + 2);
    const double tau = light[0], visibility = light[1];
    return visibility > 0.0 ? sun_irradiance[j] * cache_hg(g, mu_sun) * visibility * fast_exp(-tau)
                            : 0.0;
  }
};

// The march's source for a ray with a forward peak (DeltaM false: the
// harmonics and the peak hold the whole phase function, the radiance's
// extinction is σt) or without one (DeltaM true: delta-M, which also gives
// the march the f σs it keeps along the ray). Two types rather than a test
// per point, so that a ray with a peak (the demo's) marches as before
// delta-M, without carrying a forward part that is zero.
template <bool DeltaM>
struct CacheSourceOf {
  const PlanckTableView* planck;  // per node j of the march
  const CacheLight& light;
  // The sun's optical depth: where it changes steeply across a cell, the
  // march integrates the sun's light scattered once (sun_scattered) over
  // pieces of the cell (lattice_view_march.h), reading σa, σs, T, σs g, τ_sun
  // and V_sun there.
  static constexpr int kSteepChannel = record::kTauSun;
  static constexpr int kSteepReads = 8;
  static_assert(record::kSunVisibility < kSteepReads);
  static constexpr bool kKeepsForward = DeltaM;

  // Delta-M: σt, ε and the f σs kept along the ray.
  OBSCURA_HOST_DEVICE void point(int j, const float* v, double& sigma_t, double& emissivity,
                                 double& forward) const requires DeltaM {
    evaluate(j, v, sigma_t, emissivity, forward);
  }
  // With a forward peak: σt and ε.
  OBSCURA_HOST_DEVICE void point(int j, const float* v, double& sigma_t, double& emissivity) const
      requires(!DeltaM) {
    double forward, steep;
    evaluate(j, v, sigma_t, emissivity, forward, steep);
  }
  // σt, ε, φ and ε's part from the sun's light scattered once, σs J_sun.
  OBSCURA_HOST_DEVICE void split_point(int j, const float* v, double& sigma_t, double& emissivity,
                                       double& forward, double& steep) const {
    evaluate(j, v, sigma_t, emissivity, forward, steep);
  }
  // σt, σs J_sun and φ alone, from v's first kSteepReads floats.
  OBSCURA_HOST_DEVICE void steep_point(int j, const float* v, double& sigma_t, double& steep,
                                       double& forward) const {
    const double sigma_a = v[record::kSigmaA], sigma_s = v[record::kSigmaS];
    sigma_t = sigma_a + sigma_s;
    steep = forward = 0.0;
    if (sigma_s > 0.0) {
      const double g = cache_clamped_g(v[record::kSigmaSG] / sigma_s);
      forward = (DeltaM ? light.forward_fraction(g) : 0.0) * sigma_s;
      steep = sigma_s * light.sun_scattered(j, g, v + record::kTauSun);
    }
  }

 private:
  OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE void evaluate(int j, const float* v, double& sigma_t,
                                                          double& emissivity, double& forward,
                                                          double& steep) const {
    const double sigma_a = v[record::kSigmaA], sigma_s = v[record::kSigmaS];
    sigma_t = sigma_a + sigma_s;
    emissivity = sigma_a != 0.0 ? sigma_a * planck[j](v[record::kTemperature]) : 0.0;
    forward = steep = 0.0;
    if (sigma_s > 0.0) {
      const double g = cache_clamped_g(v[record::kSigmaSG] / sigma_s);
      const double f = DeltaM ? light.forward_fraction(g) : 0.0;
      forward = f * sigma_s;
      double sun;
      emissivity += sigma_s * light.in_scattered(j, g, f, v + record::kTauSun, sun);
      steep = sigma_s * sun;
    }
  }
};

using CacheSource = CacheSourceOf<false>;
using DeltaMCacheSource = CacheSourceOf<true>;

}  // namespace obscura
