#pragma once
// The air between the sensor and the scene (docs/physics.md, "Atmosphere"):
// a homogeneous path of extinction coefficient β_b (1/m, one per sensor band)
// at air temperature T_air. A sensor ray that meets the scene at distance d
// sees
//   L_sensor = τ L_scene + (1 − τ) B_b(T_air),   τ = exp(−β_b d),
// where B_b is the band's blackbody radiance (the air emits what it absorbs,
// Kirchhoff; its scattering of sunlight into the line of sight — path
// radiance in the visible — is not modelled). d is the distance to the first
// surface the ray hits, or, for a ray that hits no surface, to where it leaves
// the clouds' bounds; a ray that meets neither sees the sky as given (the sky
// radiance already includes the whole atmosphere above). The scene is assumed
// compact compared with the range: the clouds' own light is attenuated over
// the same d as the surface behind them (an error of β × the cloud's depth).
#include <map>
#include <string>

#include "obscura/core/band.h"

namespace obscura {

struct Atmosphere {
  bool enabled = false;
  double temperature_k = 288.15;
  // β per band name, 1/m (the scene file gives 1/km).
  std::map<std::string, double> extinction_per_m;

  // β for `band`: its entry, else the entry "*" (all bands). Throws Error if
  // neither exists (the scene loader checks every sensor band up front).
  double extinction_for(const Band& band) const;
  // τ = exp(−β d) over `distance_m`.
  double transmittance(const Band& band, double distance_m) const;
};

}  // namespace obscura
