#include "obscura/prep/dispersion/puff_train.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace obscura {

long long puff_count(const SmokeDevice& device) {
  if (!(device.burn_time_s > 0)) return 1;
  // The small tolerance keeps an exact product (2 s × 10 /s) from rounding up
  // to one puff more through floating-point noise.
  const double n = std::ceil(device.burn_time_s * device.puffs_per_second - 1e-9);
  return std::max(1LL, static_cast<long long>(n));
}

std::vector<Puff> puff_train(const SmokeDevice& device, const Wind& wind) {
  const long long n = puff_count(device);
  const double interval_s = device.burn_time_s / static_cast<double>(n);
  Puff p;
  p.release_point_m = {device.x_m, device.y_m, device.release_height_m};
  p.mass_g = device.released_mass_g() / static_cast<double>(n);
  p.velocity_m_s = wind.velocity_at_m_s(device.release_height_m);
  p.initial_sigma_m = device.initial_sigma_m;
  p.temperature_excess_k = device.source_temperature_excess_k;
  p.temperature_decay_time_s = device.temperature_decay_time_s;
  std::vector<Puff> puffs(static_cast<std::size_t>(n), p);
  for (long long i = 0; i < n; ++i)
    puffs[static_cast<std::size_t>(i)].release_time_s =
        device.start_s + (static_cast<double>(i) + 0.5) * interval_s;
  return puffs;
}

PuffState puff_state(const Puff& puff, double time_s, SigmaSet set, StabilityClass stability) {
  const double age_s = std::max(time_s - puff.release_time_s, 0.0);
  const double travel_m = length(puff.velocity_m_s) * age_s;
  const DispersionSigmas s = dispersion_sigmas(set, stability, travel_m);
  const double s0 = puff.initial_sigma_m;
  PuffState state;
  state.centre_m = puff.release_point_m + puff.velocity_m_s * age_s;
  state.sigma_horizontal_m = std::sqrt(s0 * s0 + s.y_m * s.y_m);
  state.sigma_vertical_m = std::sqrt(s0 * s0 + s.z_m * s.z_m);
  state.mass_g = puff.mass_g;
  state.temperature_excess_k =
      puff.temperature_excess_k * std::exp(-age_s / puff.temperature_decay_time_s);
  return state;
}

double puff_concentration_g_m3(const PuffState& puff, const Vec3& point_m) {
  if (point_m.z < 0) return 0.0;
  const double sh = puff.sigma_horizontal_m, sz = puff.sigma_vertical_m;
  const double dx = point_m.x - puff.centre_m.x, dy = point_m.y - puff.centre_m.y;
  const double dz = point_m.z - puff.centre_m.z;        // from the real source
  const double dz_image = point_m.z + puff.centre_m.z;  // from its image below ground
  const double norm = puff.mass_g / (std::pow(2.0 * std::numbers::pi, 1.5) * sh * sh * sz);
  return norm * std::exp(-(dx * dx + dy * dy) / (2.0 * sh * sh)) *
         (std::exp(-dz * dz / (2.0 * sz * sz)) + std::exp(-dz_image * dz_image / (2.0 * sz * sz)));
}

}  // namespace obscura
