#include "obscura/medium/spectral_lerp.h"

#include "obscura/core/tabulated_spectrum.h"

namespace obscura {

SpectralLerp SpectralLerp::at(const std::vector<double>& w, double wavelength_um) {
  const WavelengthBracket b = bracket_wavelength(w, wavelength_um);
  return {static_cast<int>(b.lower), static_cast<int>(b.upper), b.frac};
}

}  // namespace obscura
