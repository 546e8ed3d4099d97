#pragma once
// Real spherical harmonics up to degree 3, orthonormal on the sphere
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
#include <cstring>

#include "obscura/core/host_device.h"
#include "obscura/core/vec3.h"

namespace obscura {

inline constexpr int kMaxShDegree = 3;
inline constexpr int kMaxShCoefficients = (kMaxShDegree + 1) * (kMaxShDegree + 1);

constexpr int sh_coefficient_count(int degree) { return (degree + 1) * (degree + 1); }

// Y_lm(d) for l ≤ kMaxShDegree, d a unit vector (x, y, z), into y[l² + l + m].
OBSCURA_HOST_DEVICE inline void spherical_harmonics(const Vec3& d,
                                                    std::array<double, kMaxShCoefficients>& y) {
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
// degrees 2, 3, 3, 3; 12–15 degree 3). What the CPU's camera march spends on
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
    const float g1 = static_cast<float>(g), g2 = g1 * g1, g3 = g2 * g1;
    const float f1 = static_cast<float>(f);
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
  float y_[kMaxShCoefficients] = {};  // y_i, 0 beyond the degree's coefficients
  int groups_ = 0;
};
#endif

}  // namespace obscura
