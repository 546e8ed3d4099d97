#pragma once
// The emission of one cell along a ray, ∫₀ʰ e^{−τ(s)} ε(s) ds with
// τ(s) = ∫₀ˢ σt, from σt and the emissivity ε (σa B(T), plus σs J for the
// radiance cache: W m⁻³ sr⁻¹ µm⁻¹) at the cell's entry, middle and exit
// (docs/physics.md, "The cell quadrature").
//
//  * The cell's optical depth D = h/6 (σt,0 + 4 σt,½ + σt,1) is exact:
//    trilinear σt restricted to a line is a cubic, which Simpson's rule
//    integrates exactly. τ(h/2) ≈ h/24 (5 σt,0 + 8 σt,½ − σt,1), the integral
//    of the quadratic through the three values, places the middle point.
//  * Optically thin cells (D < kThinCell): Simpson's rule in s on
//    e^{−τ} ε, error ≤ h⁵ max|f⁗|/2880.
//  * Otherwise in optical depth t (the short-characteristics form of Olson &
//    Kunasz 1987): ∫₀ᴰ e^{−t} S(t) dt with the source function S = ε/σt, a
//    weighted mean of B(T) and J and therefore bounded, replaced by the
//    parabola P through its three values. With I₀ = 1 − e^{−D},
//    I₁ = 1 − e^{−D}(1 + D), I₂ = 2 − e^{−D}(D² + 2D + 2) and the divided
//    differences of S, ∫ e^{−t} P = S₀ I₀ + S[0,½] I₁ + S[0,½,1] (I₂ − t½ I₁),
//    stable for any D (a thick cell tends to its entry value). The error is
//    third order in D: |error| ≤ 0.008 D³ max|d³S/dt³| (1 − e^{−D}). The
//    middle point is used only when it lies in [0.2 D, 0.8 D] (else a line
//    through the ends): the parabola's weights then stay bounded. (The
//    bounds keep away from t½ = D/4, where a cell whose σt rises linearly
//    from zero puts it, so that rounding does not choose the rule there.) The result is linear in
//    the three S values, so noise in them (the radiance cache's photon estimates) averages out
//    without bias.
// The same code runs on a CUDA device (core/host_device.h, docs/gpu.md).
#include <algorithm>
#include <cmath>

#include "obscura/core/fast_exp.h"
#include "obscura/core/host_device.h"

namespace obscura {

inline constexpr double kThinCell = 0.1;

// How many equal pieces a cell is cut into when the sun's optical depth
// changes by `sun_depth_change` between its entry and exit: the parabola
// above cannot follow e^{−τ_sun} over several units of τ_sun (a grazing sun
// on an optically thick cell), so each piece spans at most 1, up to 16
// pieces (docs/physics.md, "A sun whose depth climbs steeply across a cell").
OBSCURA_HOST_DEVICE inline int cell_pieces(double sun_depth_change) {
  const double change = std::abs(sun_depth_change);
  return change > 1.0 ? static_cast<int>(std::min(16.0, std::ceil(change))) : 1;
}

struct CellEmission {
  double emitted = 0.0;        // ∫ e^{−τ} ε ds over the cell, W m⁻² sr⁻¹ µm⁻¹
  double transmittance = 1.0;  // e^{−D}
};

// `sigma_t` (1/m) and `emissivity` at s = 0, h/2, h; `h` in m. Forced
// inline: left as a call from add_cell's loop over a band's nodes, its
// arguments went through memory (3 % of a march with 8 nodes, callgrind).
OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE inline CellEmission integrate_cell(
    double h, const double sigma_t[3], const double emissivity[3]) {
  CellEmission out;
  const double h6 = h * (1.0 / 6.0);
  const double d = h6 * (sigma_t[0] + 4.0 * sigma_t[1] + sigma_t[2]);
  if (!(d > 0.0)) return out;
  const bool thin = d < kThinCell;
  const double e = thin ? exp_neg_small(d) : fast_exp(-d);
  out.transmittance = e;
  const double t_half =
      std::clamp(h * (1.0 / 24.0) * (5.0 * sigma_t[0] + 8.0 * sigma_t[1] - sigma_t[2]), 0.0, d);
  if (emissivity[0] == 0.0 && emissivity[1] == 0.0 && emissivity[2] == 0.0) return out;
  if (thin) {
    out.emitted =
        h6 * (emissivity[0] + 4.0 * emissivity[1] * exp_neg_small(t_half) + emissivity[2] * e);
    return out;
  }
  // Source function per point; where σt = 0 the emissivity is 0 too and the
  // neighbouring value stands in. So where σt is below 1e-6 of the cell's
  // largest: a trilinear σt vanishes only on a face, edge or corner of empty
  // voxels and grows linearly away from it, so such a point lies within 1e-6
  // of a cell width of that zero, where ε/σt is the ratio of the rounding
  // errors of the point's position (float or double) rather than a value of
  // the field.
  const double zero_sigma_t = 1e-6 * std::max({sigma_t[0], sigma_t[1], sigma_t[2]});
  double s[3];
  for (int i = 0; i < 3; ++i) s[i] = sigma_t[i] > zero_sigma_t ? emissivity[i] / sigma_t[i] : -1.0;
  if (s[1] < 0.0) s[1] = std::max(s[0], s[2]);
  if (s[0] < 0.0) s[0] = s[1];
  if (s[2] < 0.0) s[2] = s[1];
  const double i0 = 1.0 - e;
  const double i1 = 1.0 - e * (1.0 + d);
  double integral;
  if (t_half < 0.2 * d || t_half > 0.8 * d) {
    integral = s[0] * i0 + (s[2] - s[0]) / d * i1;  // the middle adds nothing new: a line
  } else {
    const double i2 = 2.0 - e * (d * d + 2.0 * d + 2.0);
    const double f01 = (s[1] - s[0]) / t_half;
    const double f12 = (s[2] - s[1]) / (d - t_half);
    const double f012 = (f12 - f01) / d;
    integral = s[0] * i0 + f01 * i1 + f012 * (i2 - t_half * i1);
  }
  out.emitted = integral;
  return out;
}

// The cell's e^{−D} alone, with integrate_cell's arithmetic (the same bits).
OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE inline double cell_transmittance(
    double h, const double sigma_t[3]) {
  const double d = h * (1.0 / 6.0) * (sigma_t[0] + 4.0 * sigma_t[1] + sigma_t[2]);
  if (!(d > 0.0)) return 1.0;
  return d < kThinCell ? exp_neg_small(d) : fast_exp(-d);
}

// One cell of a march for `count` spectral nodes, node j's σt and ε at the
// cell's entry, middle and exit in sigma_t[p][j] and emissivity[p][j]: adds
// to radiance[j] the cell's emission seen through transmittance[j] (the line
// so far), then attenuates transmittance[j] by the cell.
OBSCURA_HOST_DEVICE inline void add_cell(double h, int count, const double* const sigma_t[3],
                                         const double* const emissivity[3], double* radiance,
                                         double* transmittance) {
  for (int j = 0; j < count; ++j) {
    const double st[3] = {sigma_t[0][j], sigma_t[1][j], sigma_t[2][j]};
    const double em[3] = {emissivity[0][j], emissivity[1][j], emissivity[2][j]};
    const CellEmission c = integrate_cell(h, st, em);
    radiance[j] += transmittance[j] * c.emitted;
    transmittance[j] *= c.transmittance;
  }
}

// The same where the radiance's extinction along the ray is σt − φ, φ the
// scattering the source keeps in the ray's own direction (delta-M:
// φ = f σs, docs/physics.md, "Delta-M where a ray has no forward peak"),
// given at the same points in forward[p][j]: the cell's emission is
// integrated with σt − φ and seen through attenuation[j] (the line's
// e^{−∫(σt − φ)} so far), which the cell then attenuates, while
// transmittance[j] takes the line's exact e^{−∫σt}. Where φ is zero at the
// three points both equal add_cell's, bit for bit.
//
// integrate_seen is one node's cell of it: the emission integrated with
// σt − φ where φ is not zero at the three points, else with σt.
OBSCURA_ALWAYS_INLINE OBSCURA_HOST_DEVICE inline CellEmission integrate_seen(
    double h, const double sigma_t[3], const double forward[3], const double emissivity[3]) {
  const bool kept = forward[0] != 0.0 || forward[1] != 0.0 || forward[2] != 0.0;
  const double scaled[3] = {sigma_t[0] - forward[0], sigma_t[1] - forward[1],
                            sigma_t[2] - forward[2]};
  return integrate_cell(h, kept ? scaled : sigma_t, emissivity);
}

OBSCURA_HOST_DEVICE inline void add_cell_forward(double h, int count,
                                                 const double* const sigma_t[3],
                                                 const double* const forward[3],
                                                 const double* const emissivity[3],
                                                 double* radiance, double* transmittance,
                                                 double* attenuation) {
  for (int j = 0; j < count; ++j) {
    const double st[3] = {sigma_t[0][j], sigma_t[1][j], sigma_t[2][j]};
    const double fw[3] = {forward[0][j], forward[1][j], forward[2][j]};
    const double em[3] = {emissivity[0][j], emissivity[1][j], emissivity[2][j]};
    const bool kept = fw[0] != 0.0 || fw[1] != 0.0 || fw[2] != 0.0;
    const CellEmission c = integrate_seen(h, st, fw, em);
    radiance[j] += attenuation[j] * c.emitted;
    attenuation[j] *= c.transmittance;
    transmittance[j] *= kept ? cell_transmittance(h, st) : c.transmittance;
  }
}

}  // namespace obscura
