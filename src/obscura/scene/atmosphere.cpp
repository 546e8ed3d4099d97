#include "obscura/scene/atmosphere.h"

#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

double Atmosphere::extinction_for(const Band& band) const {
  auto it = extinction_per_m.find(band.name());
  if (it == extinction_per_m.end()) it = extinction_per_m.find("*");
  if (it == extinction_per_m.end())
    throw Error("atmosphere: no extinction coefficient for band '" + band.name() + "'");
  return it->second;
}

double Atmosphere::transmittance(const Band& band, double distance_m) const {
  if (!enabled || !(distance_m > 0.0)) return 1.0;
  return std::exp(-extinction_for(band) * distance_m);
}

}  // namespace obscura
