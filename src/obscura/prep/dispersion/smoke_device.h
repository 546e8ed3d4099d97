#pragma once
// One smoke source of the built-in dispersion model (docs/dispersion.md): a
// grenade, pot or generator that releases agent from a point over a burn time.
// A burn time of 0 is a bursting device (one instantaneous puff); a burning
// device becomes a train of puffs (puff_train.h).
#include <string>

namespace obscura {

struct SmokeDevice {
  std::string name;             // for messages; the config names unnamed ones "device N"
  double x_m = 0;               // release point, east (world x), m
  double y_m = 0;               // release point, north (world y), m
  double release_height_m = 0;  // effective release height H above the ground (>= 0), m
  double start_s = 0;           // when the release begins, s
  double burn_time_s = 0;       // release duration (>= 0; 0: instantaneous burst), s
  double agent_mass_g = 0;      // fill of obscurant agent (> 0), g
  // Aerosol mass per agent mass (> 0): WP and RP take up water and give about
  // 3–8 (docs/domain.md §2.6); 1 for agents released as they are (TA, fog oil).
  double yield_factor = 1.0;
  // σ0 of the cloud at release (> 0), added in quadrature to the travel σ in
  // all three axes (virtual source, docs/domain.md §3.1): a burst radius, or the
  // size of the plume where it leaves a burning canister.
  double initial_sigma_m = 1.0;
  // Temperature of fresh smoke above ambient (may be 0 or negative), K, and the
  // e-folding time of that excess as the puff mixes with ambient air (> 0), s.
  double source_temperature_excess_k = 0.0;
  double temperature_decay_time_s = 10.0;
  // Puffs per second of burn time for a burning device (> 0). Consecutive
  // puffs are u/rate apart along the wind; keep that below σ0 for a smooth
  // plume (docs/dispersion.md, "Puff train").
  double puffs_per_second = 10.0;

  // Aerosol mass the device releases in total, g.
  double released_mass_g() const { return agent_mass_g * yield_factor; }
};

}  // namespace obscura
