#include "obscura/prep/dispersion/dispersion_model.h"

#include <utility>

namespace obscura {

DispersionModel::DispersionModel(DispersionConfig config) : config_(std::move(config)) {
  validate_dispersion_config(config_);
  for (const SmokeDevice& device : config_.devices) {
    const std::vector<Puff> train = puff_train(device, config_.wind);
    puffs_.insert(puffs_.end(), train.begin(), train.end());
  }
}

std::vector<PuffState> DispersionModel::puffs_at(double time_s) const {
  std::vector<PuffState> states;
  for (const Puff& p : puffs_)
    if (p.release_time_s <= time_s)
      states.push_back(puff_state(p, time_s, config_.sigma_set, config_.stability));
  return states;
}

double DispersionModel::released_mass_g(double time_s) const {
  double mass = 0;
  for (const Puff& p : puffs_)
    if (p.release_time_s <= time_s) mass += p.mass_g;
  return mass;
}

double DispersionModel::concentration_g_m3(const Vec3& point_m, double time_s) const {
  double c = 0;
  for (const PuffState& s : puffs_at(time_s)) c += puff_concentration_g_m3(s, point_m);
  return c;
}

double DispersionModel::temperature_k(const Vec3& point_m, double time_s) const {
  double c = 0, weighted_excess = 0;
  for (const PuffState& s : puffs_at(time_s)) {
    const double ci = puff_concentration_g_m3(s, point_m);
    c += ci;
    weighted_excess += ci * s.temperature_excess_k;
  }
  return c > 0 ? config_.ambient_temperature_k + weighted_excess / c
               : config_.ambient_temperature_k;
}

}  // namespace obscura
