#pragma once
// Real spherical harmonics up to degree 6 (3 in CUDA device code), orthonormal on the sphere
// (∫ Y_lm Y_l'm' dω = δ_ll' δ_mm'), in the usual order
// (l, m) = (0,0), (1,−1), (1,0), (1,1), (2,−2), …, index l² + l + m. The
// radiance cache stores the incident radiance at a point as
// c_lm = ∫ Y_lm(ω) L_in(ω) dω (ω the direction of propagation), and the
// Henyey–Greenstein phase function, whose Legendre coefficients are g^l
// (p(μ) = Σ_l (2l + 1)/(4π) g^l P_l(μ)), convolves it exactly band by band:
// by the addition theorem P_l(ω·ω') = 4π/(2l + 1) Σ_m Y_lm(ω) Y_lm(ω'),
//   ∫ p(ω'·ω) L_in(ω') dω' = Σ_l g^l Σ_m Y_lm(ω) c_lm
// (docs/physics.md, "The radiance cache"). Both run on a CUDA device too
// (core/host_device.h).
#include <array>
#include <cmath>
#include <cstring>
#include <numbers>
#include <type_traits>
#include <utility>

#include "obscura/core/host_device.h"
#include "obscura/core/vec3.h"

namespace obscura {

// The CPU's radiance cache goes to degree 6, which a phase function as
// peaked as g = 0.85 needs where a ray has no forward peak (delta-M's
// truncation, docs/validation.md); a CUDA device's kernels stop at degree 3
// (their records and harmonics stay in registers; docs/gpu.md).
inline constexpr int kMaxDeviceShDegree = 3;
#if OBSCURA_DEVICE_CODE
inline constexpr int kMaxShDegree = kMaxDeviceShDegree;
#else
inline constexpr int kMaxShDegree = 6;
#endif
inline constexpr int kMaxShCoefficients = (kMaxShDegree + 1) * (kMaxShDegree + 1);

constexpr int sh_coefficient_count(int degree) { return (degree + 1) * (degree + 1); }

#if !OBSCURA_DEVICE_CODE
// f(std::integral_constant<int, sh_coefficient_count(degree)>{}) for a degree
// in [0, kMaxShDegree] (checked by the caller): the CPU's one place that turns
// a degree into the harmonics' count as a template argument, so that the
// loops over them unroll.
template <int Degree = 0, class F>
decltype(auto) with_sh_count(int degree, F&& f) {
  if constexpr (Degree < kMaxShDegree)
    if (degree != Degree) return with_sh_count<Degree + 1>(degree, std::forward<F>(f));
  return f(std::integral_constant<int, sh_coefficient_count(Degree)>{});
}
#endif

#if !OBSCURA_DEVICE_CODE
// The constants of spherical_harmonics_above_degree_3 (below) that depend
// on (l, m) alone: Q_mm and K_lm (√2 K_lm for m > 0), computed once, not
// per direction.
struct ShAboveDegree3Constants {
  double q_mm[kMaxShDegree + 1];
  double k[kMaxShDegree + 1][kMaxShDegree + 1];  // [l][m]
};
inline const ShAboveDegree3Constants& sh_above_degree_3_constants() {
  static const ShAboveDegree3Constants constants = [] {
    ShAboveDegree3Constants c{};
    for (int m = 0; m <= kMaxShDegree; ++m) {
      c.q_mm[m] = 1.0;  // (2m − 1)!!
      for (int k = 1; k <= m; ++k) c.q_mm[m] *= 2 * k - 1;
      double ratio = 1.0;  // (l − m)!/(l + m)!
      for (int k = 1; k <= 2 * m; ++k) ratio /= k;
      for (int l = m; l <= kMaxShDegree; ++l) {
        if (l > m) ratio *= static_cast<double>(l - m) / (l + m);
        const double k_lm = std::sqrt((2 * l + 1) * ratio * (0.25 * std::numbers::inv_pi));
        c.k[l][m] = m == 0 ? k_lm : std::numbers::sqrt2 * k_lm;
      }
    }
    return c;
  }();
  return constants;
}

// Y_lm(d) for 4 ≤ l ≤ degree into y[l² + l + m], in the form the explicit
// degrees below take: Y_l0 = K_l0 Q_l0(z), Y_l±m = √2 K_lm Q_lm(z) times the
// real (+m) or imaginary (−m) part of (x + i y)^m, m > 0, where Q_lm is the
// m-th derivative of the Legendre polynomial P_l (so Q_lm (1 − z²)^{m/2} is
// the associated Legendre function without the Condon–Shortley phase) and
// K_lm = √((2l + 1)/(4π) (l − m)!/(l + m)!). Q_lm by the recurrence
// (l − m) Q_lm = (2l − 1) z Q_{l−1,m} − (l + m − 1) Q_{l−2,m} from
// Q_mm = (2m − 1)!! (Press et al., Numerical Recipes, §6.7).
inline void spherical_harmonics_above_degree_3(double x, double yy, double z, int degree,
                                               std::array<double, kMaxShCoefficients>& y) {
  const ShAboveDegree3Constants& c = sh_above_degree_3_constants();
  double re[kMaxShDegree + 1], im[kMaxShDegree + 1];  // (x + i y)^m
  re[0] = 1.0;
  im[0] = 0.0;
  for (int m = 1; m <= degree; ++m) {
    re[m] = re[m - 1] * x - im[m - 1] * yy;
    im[m] = im[m - 1] * x + re[m - 1] * yy;
  }
  for (int m = 0; m <= degree; ++m) {
    double q_prev = 0.0, q = c.q_mm[m];  // Q_{l−1,m}, Q_lm
    for (int l = m; l <= degree; ++l) {
      if (l > m) {
        const double next = ((2 * l - 1) * z * q - (l + m - 1) * q_prev) / (l - m);
        q_prev = q;
        q = next;
      }
      if (l < 4) continue;
      if (m == 0) {
        y[l * l + l] = c.k[l][0] * q;
      } else {
        y[l * l + l + m] = c.k[l][m] * q * re[m];
        y[l * l + l - m] = c.k[l][m] * q * im[m];
      }
    }
  }
}
#endif

// Y_lm(d) for l ≤ max(degree, 3), d a unit vector (x, y, z), into
// y[l² + l + m]; degree ≤ kMaxShDegree.
OBSCURA_HOST_DEVICE inline void spherical_harmonics(const Vec3& d,
                                                    std::array<double, kMaxShCoefficients>& y,
                                                    int degree) {
  const double x = d.x, yy = d.y, z = d.z;
  // Normalisation constants of the real harmonics (Sloan 2008, "Stupid
  // Spherical Harmonics Tricks", appendix).
  constexpr double k00 = 0.28209479177387814;  // 1/(2√π)
  constexpr double k1 = 0.48860251190291992;   // √(3/(4π))
  constexpr double k2a = 1.0925484305920792;   // √(15/(4π))
  constexpr double k2b = 0.31539156525252005;  // √(5/(16π))
  constexpr double k2c = 0.54627421529603959;  // √(15/(16π))
  constexpr double k3a = 0.59004358992664352;  // √(35/(32π))
  constexpr double k3b = 2.8906114426405538;   // √(105/(4π))
  constexpr double k3c = 0.45704579946446572;  // √(21/(32π))
  constexpr double k3d = 0.37317633259011546;  // √(7/(16π))
  constexpr double k3e = 1.4453057213202769;   // √(105/(16π))
  y[0] = k00;
  y[1] = k1 * yy;
  y[2] = k1 * z;
  y[3] = k1 * x;
  y[4] = k2a * x * yy;
  y[5] = k2a * yy * z;
  y[6] = k2b * (3 * z * z - 1);
  y[7] = k2a * x * z;
  y[8] = k2c * (x * x - yy * yy);
  y[9] = k3a * yy * (3 * x * x - yy * yy);
  y[10] = k3b * x * yy * z;
  y[11] = k3c * yy * (5 * z * z - 1);
  y[12] = k3d * z * (5 * z * z - 3);
  y[13] = k3c * x * (5 * z * z - 1);
  y[14] = k3e * z * (x * x - yy * yy);
  y[15] = k3a * x * (x * x - 3 * yy * yy);
#if !OBSCURA_DEVICE_CODE
  if (degree > 3) spherical_harmonics_above_degree_3(x, yy, z, degree, y);
#else
  (void)degree;
#endif
}

// ∫ p_HG(ω'·ω) L(ω') dω' from L's coefficients `c` (degree ≤ `degree`) and
// the harmonics `y` of ω: Σ_l (g^l − f) Σ_m y_lm c_lm, f = 0 for the phase
// function itself; f = g^{degree+1} gives delta-M's (Wiscombe 1977) for the
// part of the phase function the harmonics hold, its forward peak f δ
// taken by the march (cache_source.h).
OBSCURA_HOST_DEVICE inline double hg_convolved(const float* c,
                                               const std::array<double, kMaxShCoefficients>& y,
                                               double g, int degree, double f = 0.0) {
  double result = 0.0, g_l = 1.0;
  for (int l = 0; l <= degree; ++l) {
    double band = 0.0;
    for (int i = l * l; i < (l + 1) * (l + 1); ++i) band += y[i] * c[i];
    result += (g_l - f) * band;
    g_l *= g;
  }
  return result;
}

#if !OBSCURA_DEVICE_CODE
// hg_convolved for the many points of one camera ray, whose direction (the
// harmonics y) is fixed: Σ_i g^{l(i)} y_i c_i, four coefficients at a time in
// float, each group of four times its lanes' powers of g (coefficient i has
// degree l(i) = ⌊√i⌋: lanes 0–3 hold degrees 0, 1, 1, 1; 4–7 degree 2; 8–11
// degrees 2, 3, 3, 3; 12–15 degree 3; above degree 3 the lanes' powers are
// gathered from a table of the degrees). What the CPU's camera march spends on
// the cache's multiple scattering (docs/performance.md); a CUDA device keeps
// hg_convolved. Agrees with it to float rounding (relative 1e-6 of the terms'
// magnitudes; tests/render/radiance_cache/spherical_harmonics_test.cpp).
class HgConvolution {
 public:
  HgConvolution() = default;
  HgConvolution(const std::array<double, kMaxShCoefficients>& y, int degree)
      : groups_(readable(degree) / 4) {
    for (int i = 0; i < sh_coefficient_count(degree); ++i) y_[i] = static_cast<float>(y[i]);
  }

  // Floats of `c` read: the coefficients rounded up to a whole group of four
  // (the reader's buffer must hold them; y is zero beyond the coefficients,
  // so finite values there add nothing).
  static constexpr int readable(int degree) { return (sh_coefficient_count(degree) + 3) / 4 * 4; }

  // With f: Σ_i (g^{l(i)} − f) y_i c_i (hg_convolved's f).
  double operator()(const float* c, double g, double f = 0.0) const {
    using Float4 = float __attribute__((vector_size(16)));
    const float g1 = static_cast<float>(g), f1 = static_cast<float>(f);
    if (groups_ > 4) [[unlikely]]
      return above_degree_3(c, g1, f1);
    const float g2 = g1 * g1, g3 = g2 * g1;
    const Float4 power[4] = {Float4{1.0f, g1, g1, g1} - f1, Float4{g2, g2, g2, g2} - f1,
                             Float4{g2, g3, g3, g3} - f1, Float4{g3, g3, g3, g3} - f1};
    Float4 sum = {};
    for (int q = 0; q < groups_; ++q) {
      Float4 y_q, c_q;
      std::memcpy(&y_q, y_ + 4 * q, sizeof y_q);
      std::memcpy(&c_q, c + 4 * q, sizeof c_q);
      sum += power[q] * y_q * c_q;
    }
    return static_cast<double>((sum[0] + sum[1]) + (sum[2] + sum[3]));
  }

 private:
  // The same sum for degrees above 3 (more than four groups); kept out of
  // line, so that the march at the usual degrees inlines only the above.
  [[gnu::noinline, gnu::cold]] double above_degree_3(const float* c, float g1, float f1) const {
    using Float4 = float __attribute__((vector_size(16)));
    float power[kMaxShDegree + 1];
    power[0] = 1.0f;
    for (int l = 1; l <= kMaxShDegree; ++l) power[l] = power[l - 1] * g1;
    Float4 sum = {};
    for (int q = 0; q < groups_; ++q) {
      const unsigned char* l = kDegreeOf.data() + 4 * q;
      const Float4 p = Float4{power[l[0]], power[l[1]], power[l[2]], power[l[3]]} - f1;
      Float4 y_q, c_q;
      std::memcpy(&y_q, y_ + 4 * q, sizeof y_q);
      std::memcpy(&c_q, c + 4 * q, sizeof c_q);
      sum += p * y_q * c_q;
    }
    return static_cast<double>((sum[0] + sum[1]) + (sum[2] + sum[3]));
  }

  static constexpr int kReadableMax = (kMaxShCoefficients + 3) / 4 * 4;
  // Coefficient i's degree ⌊√i⌋ (kMaxShDegree in the last group's padding).
  static constexpr std::array<unsigned char, kReadableMax> kDegreeOf = [] {
    std::array<unsigned char, kReadableMax> degree{};
    for (int i = 0; i < kReadableMax; ++i) {
      int l = 0;
      while (l < kMaxShDegree && (l + 1) * (l + 1) <= i) ++l;
      degree[i] = static_cast<unsigned char>(l);
    }
    return degree;
  }();
  float y_[kReadableMax] = {};  // y_i, 0 beyond the degree's coefficients
  int groups_ = 0;
};
#endif

}  // namespace obscura
