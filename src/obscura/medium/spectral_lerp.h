#pragma once
// One wavelength between a medium's spectral samples: what every estimator
// at a single wavelength (tracking, the photons, the lattices) reads the
// medium's per-sample values through.
#include <vector>

namespace obscura {

// Where a wavelength falls between the medium's spectral samples: values are
// (1 − frac)·v[sample0] + frac·v[sample1] (linear in wavelength, clamped).
struct SpectralLerp {
  int sample0 = 0, sample1 = 0;
  double frac = 0.0;
  double operator()(const double* per_sample) const {
    return (1.0 - frac) * per_sample[sample0] + frac * per_sample[sample1];
  }
  static SpectralLerp at(const std::vector<double>& sample_wavelengths_um, double wavelength_um);
};

}  // namespace obscura
