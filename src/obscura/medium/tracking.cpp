#include "obscura/medium/tracking.h"

#include <algorithm>
#include <cmath>

#include "obscura/core/tabulated_spectrum.h"

namespace obscura {

SpectralLerp SpectralLerp::at(const std::vector<double>& w, double wavelength_um) {
  const WavelengthBracket b = bracket_wavelength(w, wavelength_um);
  return {static_cast<int>(b.lower), static_cast<int>(b.upper), b.frac};
}

namespace {

// Exponential step with rate `sigma` (1/m); 1 − u lies in (0, 1], so the log is finite.
inline double exponential_step(Rng& rng, double sigma) {
  return -std::log(1.0 - rng.uniform()) / sigma;
}

// The walk both estimators share: tentative collisions at rate σ̄ through each
// majorant piece (restarted at piece boundaries), with the true σt evaluated
// at each. `visit(t, sigma_t, majorant)` returns false to stop the walk.
template <typename Visit>
void walk_tentative_collisions(const Medium& medium, const Ray& ray, double t_max,
                               const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch,
                               Visit&& visit) {
  medium.trace_majorants(ray, 0.0, t_max, [&](const MajorantSegment& piece) {
    const double majorant = lambda(piece.sigma_majorant);
    if (!(majorant > 0.0)) return true;
    double t = piece.t_begin;
    while (true) {
      t += exponential_step(rng, majorant);
      if (t >= piece.t_end) return true;  // no collision in this piece: on to the next
      medium.coefficients_at(ray.at(t), scratch);
      const double sigma_t = lambda(scratch.sigma_a.data()) + lambda(scratch.sigma_s.data());
      if (!visit(t, sigma_t, majorant)) return false;
    }
  });
}

}  // namespace

std::optional<double> sample_free_flight(const Medium& medium, const Ray& ray, double t_max,
                                         const SpectralLerp& lambda, Rng& rng,
                                         MediumPoint& scratch) {
  std::optional<double> hit;
  walk_tentative_collisions(medium, ray, t_max, lambda, rng, scratch,
                            [&](double t, double sigma_t, double majorant) {
                              if (rng.uniform() * majorant >= sigma_t)
                                return true;  // null collision
                              hit = t;
                              return false;
                            });
  return hit;
}

double estimate_transmittance(const Medium& medium, const Ray& ray, double t_max,
                              const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  // Ratio tracking (Novák et al. 2014) with Russian roulette: below
  // kRouletteBelow the estimate survives each further collision with
  // probability ½ at twice the weight, which keeps it unbiased and stops
  // shadow rays through opaque clouds after a few collisions instead of
  // hundreds.
  constexpr double kRouletteBelow = 0.05;
  double transmittance = 1.0;
  walk_tentative_collisions(medium, ray, t_max, lambda, rng, scratch,
                            [&](double, double sigma_t, double majorant) {
                              transmittance *= std::max(0.0, 1.0 - sigma_t / majorant);
                              if (transmittance > 0.0 && transmittance < kRouletteBelow) {
                                if (rng.uniform() >= 0.5)
                                  transmittance = 0.0;
                                else
                                  transmittance *= 2.0;
                              }
                              return transmittance != 0.0;
                            });
  return transmittance;
}

}  // namespace obscura
