#pragma once
// The Henyey–Greenstein phase function (Henyey & Greenstein 1941, ApJ 93, 70),
// evaluated and sampled exactly, in forms that stay accurate from g = 0 to
// |g| = 0.999 (the consistency tests in tests/medium/phase_function_test.cpp,
// after pbrt-v4 media_test.cpp; docs/conventions.md §6).
//
// Direction convention: both directions are directions of propagation. The
// incoming direction ω_i is the way the light travels when it reaches the
// scattering point, the outgoing direction ω_o the way it travels afterwards,
// and cos θ = dot(ω_i, ω_o). So g > 0 (forward scattering) keeps light going
// roughly the way it was going. (pbrt points ω_o back towards the viewer and
// evaluates p(−dot); obscura does not.)
#include <algorithm>
#include <cmath>
#include <numbers>

#include "obscura/core/mat3.h"
#include "obscura/core/sampling.h"
#include "obscura/core/vec3.h"

namespace obscura {

class HenyeyGreenstein {
 public:
  // Asymmetry g = mean cosine of the scattering angle; needs |g| < 1 (finite),
  // throws obscura::Error otherwise.
  explicit HenyeyGreenstein(double g);

  double g() const { return g_; }

  // Phase function per steradian, normalised over the sphere:
  //   p(cos θ) = (1 − g²) / (4π (1 + g² − 2 g cos θ)^{3/2}).
  // The denominator is written as a sum of two non-negative terms,
  //   1 + g² − 2g cos θ = (1 − g)² + 2g (1 − cos θ)   for g ≥ 0,
  //                     = (1 + g)² − 2g (1 + cos θ)   for g < 0,
  // so it does not cancel at the peak (cos θ → ±1) even for |g| → 1.
  double eval(double cos_theta) const {
    const double c = std::clamp(cos_theta, -1.0, 1.0);
    const double d = denominator(c);
    return (1.0 - g_) * (1.0 + g_) * (0.25 * std::numbers::inv_pi) / (d * std::sqrt(d));
  }

  // p for propagation directions ω_i, ω_o (unit vectors), per steradian.
  double eval(const Vec3& incoming_direction, const Vec3& outgoing_direction) const {
    return eval(dot(incoming_direction, outgoing_direction));
  }

  // P(cos Θ ≤ c) for the scattering angle Θ: 2π ∫_{−1}^{c} p(x) dx. The
  // textbook antiderivative, (1 − g²)/(2g) [D(c)^{−1/2} − 1/(1 + g)] with
  // D = 1 + g² − 2gc, divides by g and cancels as g → 0; rationalising the
  // bracket gives the form used here, with no 1/g and no cancellation:
  //   P = (1 − g)(1 + c) / (√D (1 + g + √D)).
  double cdf(double cos_theta) const;

  // Exact inversion of cdf: the cos θ with cdf(cos θ) = u, u in [0, 1].
  // The usual closed form, cos θ = (1 + g² − s²)/(2g) with
  // s = (1 − g²)/(1 − g + 2gu), loses digits as 1/g for small g and in
  // 1 − cos θ at the forward peak. Rationalised as in cdf, its distances
  // from the two poles are
  //   1 − cos θ = (1 − g)(1 − u)(1 − g + s) / (1 − g + 2gu),
  //   1 + cos θ = (1 + g) u (1 + g + s) / (1 − g + 2gu),
  // neither of which divides by g or cancels (1 − g + 2gu is evaluated as
  // (1 + g) + 2|g|(1 − u) for g < 0); cos θ is taken from the smaller.
  // At g = 0 this is exactly cos θ = 2u − 1 (isotropic), with no special case.
  double sample_cos_theta(double u) const {
    double one_minus, one_plus;
    sample_poles(u, &one_minus, &one_plus);
    return cos_from_poles(one_minus, one_plus);
  }

  // Samples an outgoing propagation direction about `incoming_direction` (unit):
  // cos θ = sample_cos_theta(u1), azimuth 2π u2 in the frame of
  // Frame::from_normal(incoming_direction). Returns a unit vector; *pdf (if not
  // null) receives its density per steradian, equal to eval(cos θ).
  Vec3 sample(const Vec3& incoming_direction, double u1, double u2, double* pdf) const {
    double one_minus, one_plus;
    sample_poles(u1, &one_minus, &one_plus);
    const double c = cos_from_poles(one_minus, one_plus);
    const double sin_theta = std::sqrt(std::max(0.0, one_minus * one_plus));  // sin²θ = (1−c)(1+c)
    const double phi = 2.0 * std::numbers::pi * u2;
    if (pdf) *pdf = eval(c);
    return Frame::from_normal(incoming_direction)
        .to_world({sin_theta * std::cos(phi), sin_theta * std::sin(phi), c});
  }

  // Inverse of sample: the (u1, u2) that sample() maps to `outgoing_direction`.
  SquareSample invert(const Vec3& incoming_direction, const Vec3& outgoing_direction) const;

 private:
  double denominator(double c) const {
    return g_ >= 0.0 ? (1.0 - g_) * (1.0 - g_) + 2.0 * g_ * (1.0 - c)
                     : (1.0 + g_) * (1.0 + g_) - 2.0 * g_ * (1.0 + c);
  }
  void sample_poles(double u, double* one_minus, double* one_plus) const {
    // 1 − g + 2gu ≥ 1 − |g| > 0, as a sum of two non-negative terms: written
    // directly it cancels for g → −1, u → 1 (1.999 − 1.996 at g = −0.999, u = 0.999).
    const double den = g_ >= 0.0 ? (1.0 - g_) + 2.0 * g_ * u : (1.0 + g_) - 2.0 * g_ * (1.0 - u);
    const double s = (1.0 - g_) * (1.0 + g_) / den;
    *one_minus = (1.0 - g_) * (1.0 - u) * (1.0 - g_ + s) / den;
    *one_plus = (1.0 + g_) * u * (1.0 + g_ + s) / den;
  }
  static double cos_from_poles(double one_minus, double one_plus) {
    const double c = one_minus <= one_plus ? 1.0 - one_minus : one_plus - 1.0;
    return std::clamp(c, -1.0, 1.0);
  }

  double g_;
};

}  // namespace obscura
