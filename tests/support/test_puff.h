#pragma once
// The small Gaussian puff the CLI tests write as a keyframe: 16³ voxels, two
// spectral samples (4 and 10 µm), absorbing, scattering and 10 K warm.
#include "obscura/medium/gaussian_puff.h"

namespace obscura::testing {

inline GaussianPuffSpec small_puff_spec() {
  GaussianPuffSpec spec;
  spec.center_m = {0, 0, 3};
  spec.radius_m = 2;
  spec.resolution = 16;
  spec.wavelengths_um = {4, 10};
  spec.peak_sigma_a = {0.5, 0.6};
  spec.peak_sigma_s = {0.2, 0.1};
  spec.g = {0.5, 0.3};
  spec.temperature_excess_k = 10;
  return spec;
}

}  // namespace obscura::testing
