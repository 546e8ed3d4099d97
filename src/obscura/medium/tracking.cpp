#include "obscura/medium/tracking.h"

#include <algorithm>
#include <cmath>

namespace obscura {

SpectralLerp SpectralLerp::at(const std::vector<double>& w, double wavelength_um) {
  SpectralLerp l;
  if (w.size() <= 1 || wavelength_um <= w.front()) return l;
  if (wavelength_um >= w.back()) {
    l.sample0 = l.sample1 = static_cast<int>(w.size()) - 1;
    return l;
  }
  const auto it = std::upper_bound(w.begin(), w.end(), wavelength_um);
  l.sample1 = static_cast<int>(it - w.begin());
  l.sample0 = l.sample1 - 1;
  l.frac = (wavelength_um - w[l.sample0]) / (w[l.sample1] - w[l.sample0]);
  return l;
}

namespace {

// Exponential step with rate `sigma` (1/m); 1 − u lies in (0, 1], so the log is finite.
inline double exponential_step(Rng& rng, double sigma) { return -std::log(1.0 - rng.uniform()) / sigma; }

}  // namespace

std::optional<double> sample_free_flight(const Medium& medium, const Ray& ray, double t_max,
                                         const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  std::optional<double> hit;
  medium.trace_majorants(ray, 0.0, t_max, [&](const MajorantSegment& piece) {
    const double majorant = lambda(piece.sigma_majorant);
    if (!(majorant > 0.0)) return true;
    double t = piece.t_begin;
    while (true) {
      t += exponential_step(rng, majorant);
      if (t >= piece.t_end) return true;  // no collision in this piece: on to the next
      medium.coefficients_at(ray.at(t), scratch);
      const double sigma_t = lambda(scratch.sigma_a.data()) + lambda(scratch.sigma_s.data());
      if (rng.uniform() * majorant < sigma_t) {
        hit = t;
        return false;
      }
    }
  });
  return hit;
}

double estimate_transmittance(const Medium& medium, const Ray& ray, double t_max,
                              const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  double transmittance = 1.0;
  medium.trace_majorants(ray, 0.0, t_max, [&](const MajorantSegment& piece) {
    const double majorant = lambda(piece.sigma_majorant);
    if (!(majorant > 0.0)) return true;
    double t = piece.t_begin;
    while (true) {
      t += exponential_step(rng, majorant);
      if (t >= piece.t_end) return true;
      medium.coefficients_at(ray.at(t), scratch);
      const double sigma_t = lambda(scratch.sigma_a.data()) + lambda(scratch.sigma_s.data());
      transmittance *= std::max(0.0, 1.0 - sigma_t / majorant);
      if (transmittance == 0.0) return false;
    }
  });
  return transmittance;
}

}  // namespace obscura
