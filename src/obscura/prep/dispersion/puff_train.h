#pragma once
// Gaussian puffs: what a smoke device releases, where each puff is at a later
// time and how large it has grown, and its concentration field with ground
// reflection (docs/domain.md §3.1; docs/dispersion.md).
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/prep/dispersion/smoke_device.h"
#include "obscura/prep/dispersion/stability.h"
#include "obscura/prep/dispersion/wind.h"

namespace obscura {

// One puff as released.
struct Puff {
  Vec3 release_point_m;  // (x, y, H), world metres
  double release_time_s = 0;
  double mass_g = 0;                    // aerosol mass (agent × yield) carried
  Vec3 velocity_m_s;                    // advection velocity, constant over the puff's life
  double initial_sigma_m = 0;           // σ0, added in quadrature
  double temperature_excess_k = 0;      // at release
  double temperature_decay_time_s = 1;  // τ of the excess
};

// A puff at a time after its release. Horizontal σ is one number because both
// σ sets have σx = σy (stability.h): the puff is round in plan, so it is also
// separable along the world's x and y axes whatever the wind direction.
struct PuffState {
  Vec3 centre_m;                  // the real source; its image is at (x, y, −z)
  double sigma_horizontal_m = 0;  // σx = σy
  double sigma_vertical_m = 0;    // σz
  double mass_g = 0;
  double temperature_excess_k = 0;  // ΔT0 · exp(−age/τ)
};

// Number of puffs a device releases: 1 for a burst (burn_time_s = 0), else
// ceil(burn_time_s · puffs_per_second) (at least 1).
long long puff_count(const SmokeDevice& device);

// The device's puffs in order of release. The burn is cut into puff_count
// equal intervals, each released as one puff at the interval's midpoint (the
// midpoint rule for the continuous release; a burst releases at start_s), each
// carrying released_mass_g() / puff_count. Every puff moves with the wind at
// the device's release height (Wind::velocity_at_m_s, floored at the wind's
// minimum height): the puff model keeps its centre at H (no plume rise), so
// the wind there is the one that carries it (CCPS 1999; GasDispersion.jl).
std::vector<Puff> puff_train(const SmokeDevice& device, const Wind& wind);

// The puff at `time_s` (>= release_time_s): centre advected by velocity · age,
// σ from the set at travel distance x = |velocity| · age, with σ0 in
// quadrature: σ² = σ0² + σ_set(x)² (docs/domain.md §3.1, virtual source).
PuffState puff_state(const Puff& puff, double time_s, SigmaSet set, StabilityClass stability);

// C(p) of one puff with ground reflection at z = 0 (docs/domain.md §3.1):
//   Q / ((2π)^{3/2} σx σy σz) · exp(−Δx²/2σx²) exp(−Δy²/2σy²)
//     · {exp(−(z−H)²/2σz²) + exp(−(z+H)²/2σz²)},   g/m³; 0 below the ground.
double puff_concentration_g_m3(const PuffState& puff, const Vec3& point_m);

}  // namespace obscura
