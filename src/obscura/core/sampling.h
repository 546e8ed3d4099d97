#pragma once
// Warps from the unit square [0,1)² to unit directions, each with its density
// (per steradian) and its inverse (direction → the two uniforms), so a test can
// check every warp by round trip (docs/conventions.md §7, after pbrt-v4 util/sampling.h).
//
// Conventions: the warps work in a local frame whose pole is +z; θ is the polar
// angle from +z and φ = 2π u2 the azimuth from +x towards +y. To sample around
// another axis, warp locally and rotate with local_to_world(axis, v) (the frame
// of Frame::from_normal, core/mat3.h); world_to_local undoes it.
//
// Every inverse returns u2 in [0, 1). At a pole (sin θ = 0) the azimuth, and so
// u2, is undefined and comes back as 0.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "obscura/core/mat3.h"
#include "obscura/core/vec3.h"

namespace obscura {

// A point of the unit square: the two uniforms a warp consumes.
struct SquareSample {
  double u1 = 0.0;
  double u2 = 0.0;
};

namespace sampling_detail {

// u2 = φ / (2π) for the azimuth of (x, y), in [0, 1).
inline double azimuth_fraction(double x, double y) {
  double u = std::atan2(y, x) * (0.5 * std::numbers::inv_pi);  // (−1/2, 1/2]
  if (u < 0.0) u += 1.0;
  return u < 1.0 ? u : 0.0;  // −tiny + 1 rounds to 1: that is φ = 0
}

}  // namespace sampling_detail

// 1 − cos θ of a unit vector about +z, i.e. 1 − v.z, without the cancellation
// of the direct subtraction near the pole: 1 − z = (x² + y²) / (1 + z).
// For the sun (θ ≈ 0.005 rad) this keeps ~16 digits where 1 − z keeps ~11.
inline double one_minus_cos_theta(const Vec3& v) {
  return v.z > 0.0 ? (v.x * v.x + v.y * v.y) / (1.0 + v.z) : 1.0 - v.z;
}

// ---------------------------------------------------------------------------
// Frames around an axis.

// Rotates a direction given in the local frame whose +z is `axis` (unit) into
// world coordinates (frame of Duff et al. 2017, Frame::from_normal).
inline Vec3 local_to_world(const Vec3& axis, const Vec3& local) {
  return Frame::from_normal(axis).to_world(local);
}

// Inverse of local_to_world: world direction → the frame whose +z is `axis`.
inline Vec3 world_to_local(const Vec3& axis, const Vec3& world) {
  return Frame::from_normal(axis).to_local(world);
}

// ---------------------------------------------------------------------------
// Uniform sphere: z = 1 − 2 u1, φ = 2π u2 (Archimedes: z is uniform on the
// sphere). sin θ = √(1 − z²) = 2 √(u1 (1 − u1)) avoids 1 − z² near the poles.

inline Vec3 sample_uniform_sphere(double u1, double u2) {
  const double z = 1.0 - 2.0 * u1;
  const double r = 2.0 * std::sqrt(std::max(0.0, u1 * (1.0 - u1)));
  const double phi = 2.0 * std::numbers::pi * u2;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Density of sample_uniform_sphere: 1/(4π) sr⁻¹.
inline constexpr double uniform_sphere_pdf() { return 0.25 * std::numbers::inv_pi; }

// Inverse of sample_uniform_sphere for a unit vector: u1 = (1 − z)/2.
inline SquareSample invert_uniform_sphere(const Vec3& d) {
  return {0.5 * one_minus_cos_theta(d), sampling_detail::azimuth_fraction(d.x, d.y)};
}

// ---------------------------------------------------------------------------
// Cosine-weighted hemisphere about +z by Malley's method: a uniform point of
// the unit disk lifted onto the hemisphere has density cos θ / π (pbrt-v4
// §A.5.3). The disk point comes from Shirley and Chiu's (1997) concentric map,
// which keeps the square's strata compact (no polar squeeze at the centre).

// Concentric map [0,1)² → unit disk (Shirley & Chiu 1997, eq. 4): the square's
// concentric squares go to concentric circles.
inline void sample_disk_concentric(double u1, double u2, double* x, double* y) {
  const double a = 2.0 * u1 - 1.0, b = 2.0 * u2 - 1.0;
  if (a == 0.0 && b == 0.0) {
    *x = *y = 0.0;
    return;
  }
  constexpr double kPiOver4 = 0.25 * std::numbers::pi;
  double r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = kPiOver4 * (b / a);
  } else {
    r = b;
    phi = 2.0 * kPiOver4 - kPiOver4 * (a / b);
  }
  *x = r * std::cos(phi);
  *y = r * std::sin(phi);
}

// Inverse of sample_disk_concentric: the angle ψ of the disk point, taken in
// [−π/4, 7π/4), says which of the square's four triangles the point came from.
inline SquareSample invert_disk_concentric(double x, double y) {
  constexpr double kPi = std::numbers::pi;
  constexpr double kPiOver4 = 0.25 * kPi;
  const double r = std::hypot(x, y);
  double psi = std::atan2(y, x);
  if (psi < -kPiOver4) psi += 2.0 * kPi;
  double a, b;
  if (psi < kPiOver4) {  // right triangle: r = a > 0, ψ = (π/4) b/a
    a = r;
    b = a * psi / kPiOver4;
  } else if (psi <= 3.0 * kPiOver4) {  // top: r = b > 0, ψ = π/2 − (π/4) a/b
    b = r;
    a = b * (2.0 * kPiOver4 - psi) / kPiOver4;
  } else if (psi < 5.0 * kPiOver4) {  // left: r = a < 0, the point sits at angle φ + π
    a = -r;
    b = a * (psi - kPi) / kPiOver4;
  } else {  // bottom: r = b < 0
    b = -r;
    a = b * (2.0 * kPiOver4 - (psi - kPi)) / kPiOver4;
  }
  return {std::clamp(0.5 * (a + 1.0), 0.0, 1.0), std::clamp(0.5 * (b + 1.0), 0.0, 1.0)};
}

inline Vec3 sample_cosine_hemisphere(double u1, double u2) {
  double x, y;
  sample_disk_concentric(u1, u2, &x, &y);
  // 1 − x² − y² = 1 − r² with r the concentric radius max(|a|, |b|); computed as
  // (1 − r)(1 + r) so z keeps its relative precision near the horizon.
  const double r = std::max(std::abs(2.0 * u1 - 1.0), std::abs(2.0 * u2 - 1.0));
  const double z = std::sqrt(std::max(0.0, (1.0 - r) * (1.0 + r)));
  return {x, y, z};
}

// Density of sample_cosine_hemisphere: cos θ / π sr⁻¹ for cos θ > 0, else 0.
inline double cosine_hemisphere_pdf(double cos_theta) {
  return cos_theta > 0.0 ? cos_theta * std::numbers::inv_pi : 0.0;
}

// Inverse of sample_cosine_hemisphere: project onto the disk, invert the
// concentric map. Directions below the horizon are not in the warp's image.
inline SquareSample invert_cosine_hemisphere(const Vec3& d) {
  return invert_disk_concentric(d.x, d.y);
}

// ---------------------------------------------------------------------------
// Uniform cone about +z of half-angle θmax: cos θ uniform on [cos θmax, 1]
// (pbrt-v4 SampleUniformCone). Written in h = 1 − cos θ so tiny cones keep
// their precision: 1 − cos θ = u1 (1 − cos θmax), sin θ = √(h (2 − h)); the
// subtraction 1 − cos θmax itself is exact for cos θmax ≥ 1/2 (Sterbenz).
// Precondition: −1 ≤ cos_theta_max < 1.

inline Vec3 sample_uniform_cone(double u1, double u2, double cos_theta_max) {
  const double h = u1 * (1.0 - cos_theta_max);
  const double sin_theta = std::sqrt(std::max(0.0, h * (2.0 - h)));
  const double phi = 2.0 * std::numbers::pi * u2;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), 1.0 - h};
}

// Density of sample_uniform_cone inside the cone: 1 / (2π (1 − cos θmax)) sr⁻¹.
inline double uniform_cone_pdf(double cos_theta_max) {
  return 0.5 * std::numbers::inv_pi / (1.0 - cos_theta_max);
}

// Density of sample_uniform_cone at a local unit direction: the constant above
// inside the cone (1 − cos θ ≤ 1 − cos θmax), 0 outside.
inline double uniform_cone_pdf(const Vec3& local, double cos_theta_max) {
  return one_minus_cos_theta(local) <= 1.0 - cos_theta_max ? uniform_cone_pdf(cos_theta_max) : 0.0;
}

// Inverse of sample_uniform_cone: u1 = (1 − cos θ) / (1 − cos θmax).
inline SquareSample invert_uniform_cone(const Vec3& d, double cos_theta_max) {
  return {one_minus_cos_theta(d) / (1.0 - cos_theta_max),
          sampling_detail::azimuth_fraction(d.x, d.y)};
}

}  // namespace obscura
