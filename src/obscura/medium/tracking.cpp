#include "obscura/medium/tracking.h"

#include <algorithm>
#include <cmath>
#include <functional>

namespace obscura {

namespace {

// Exponential step with rate `sigma` (1/m); 1 − u lies in (0, 1], so the log is finite.
inline double exponential_step(Rng& rng, double sigma) {
  return -std::log(1.0 - rng.uniform()) / sigma;
}

// The walk both estimators share: tentative collisions at `rate` (per m)
// over [t_begin, t_end) of the ray, with the true σt evaluated at each.
// `visit(t, sigma_t)` returns false to stop the walk; returns whether it ran
// to t_end.
template <typename Visit>
bool walk_tentative_collisions(const Medium& medium, const Ray& ray, double t_begin, double t_end,
                               double rate, const SpectralLerp& lambda, Rng& rng,
                               MediumPoint& scratch, Visit&& visit) {
  double t = t_begin;
  while (true) {
    t += exponential_step(rng, rate);
    if (t >= t_end) return true;
    const double sigma_t = medium.extinction_at(ray.at(t), lambda, scratch);
    if (!visit(t, sigma_t)) return false;
  }
}

}  // namespace

std::optional<double> sample_free_flight(const Medium& medium, const Ray& ray, double t_max,
                                         const SpectralLerp& lambda, Rng& rng,
                                         MediumPoint& scratch) {
  // Delta tracking through each majorant piece, restarted at its boundary.
  std::optional<double> hit;
  const auto each_piece = [&](const MajorantSegment& piece) {
    const double majorant = lambda(piece.sigma_majorant);
    if (!(majorant > 0.0)) return true;
    return walk_tentative_collisions(medium, ray, piece.t_begin, piece.t_end, majorant, lambda, rng,
                                     scratch, [&](double t, double sigma_t) {
                                       if (rng.uniform() * majorant >= sigma_t)
                                         return true;  // null collision
                                       hit = t;
                                       return false;
                                     });
  };
  // By reference: the lambda's captures outgrow std::function's inline
  // buffer, and a copy would be a heap allocation per flight (4 % of photon
  // tracing, docs/performance.md).
  medium.trace_majorants(ray, 0.0, t_max, std::ref(each_piece));
  // The walk evaluated only the lerp's σa and σs; the caller's collision
  // (its albedo, phase function and emission) reads the lerp's two samples'
  // σa, σs, g and the temperature, the same values coefficients_at gives
  // them, without the grid's other samples (half the work on the demo's
  // four, docs/performance.md).
  if (hit) medium.coefficients_of_samples(ray.at(*hit), lambda.sample0, lambda.sample1, scratch);
  return hit;
}

double estimate_transmittance(const Medium& medium, const Ray& ray, double t_max,
                              const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  // Residual ratio tracking (Novák, Selle & Jarosz 2014, "Residual ratio
  // tracking for estimating attenuation in participating media", §4): with a
  // piece's minorant σc as the control, T = e^{−σc Δt} E[Π (1 − (σt(x_i) −
  // σc)/σ̄r)] over tentative collisions x_i at the residual rate σ̄r = σ̄ − σc.
  // Where the medium is constant over a piece (σc = σ̄) the estimate is
  // exact; without a minorant it is plain ratio tracking. Russian roulette:
  // below kRouletteBelow the estimate survives each further collision with
  // probability ½ at twice the weight, which keeps it unbiased and stops
  // shadow rays through opaque clouds after a few collisions instead of
  // hundreds.
  constexpr double kRouletteBelow = 0.05;
  double transmittance = 1.0;
  const auto each_piece = [&](const MajorantSegment& piece) {
    const double majorant = lambda(piece.sigma_majorant);
    if (!(majorant > 0.0)) return true;
    const double control =
        piece.sigma_minorant ? std::clamp(lambda(piece.sigma_minorant), 0.0, majorant) : 0.0;
    transmittance *= std::exp(-control * (piece.t_end - piece.t_begin));
    const double residual = majorant - control;
    // Within rounding of a constant piece: the control is the whole of σt.
    if (!(residual > 1e-9 * majorant)) return transmittance != 0.0;
    return walk_tentative_collisions(medium, ray, piece.t_begin, piece.t_end, residual, lambda, rng,
                                     scratch, [&](double, double sigma_t) {
                                       transmittance *=
                                           std::max(0.0, 1.0 - (sigma_t - control) / residual);
                                       if (transmittance > 0.0 && transmittance < kRouletteBelow) {
                                         if (rng.uniform() >= 0.5)
                                           transmittance = 0.0;
                                         else
                                           transmittance *= 2.0;
                                       }
                                       return transmittance != 0.0;
                                     });
  };
  medium.trace_majorants(ray, 0.0, t_max, std::ref(each_piece));  // by reference, as above
  return transmittance;
}

}  // namespace obscura
