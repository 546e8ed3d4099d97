#pragma once
// The radiance arriving from directions that hit neither surface nor cloud:
// a uniform blackbody sky of a given brightness temperature, or none (0).
#include "obscura/core/planck.h"

namespace obscura {

struct UniformSky {
  double temperature_k = 0.0;  // 0: no sky radiance (cold space)
  // Spectral radiance, W m⁻² sr⁻¹ µm⁻¹.
  double radiance(double wavelength_um) const { return planck_radiance(wavelength_um, temperature_k); }
};

}  // namespace obscura
