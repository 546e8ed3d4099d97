#pragma once
// A procedural smoke puff: a spherical Gaussian concentration profile
//   ρ(x) = exp(−|x − c|² / (2 s²))
// scaling peak coefficients per spectral sample, with temperature
// T = T_ambient + ΔT ρ. Used for the example scene and, because its line
// integrals have a closed form, as a Beer–Lambert test of the grid code.
#include <vector>

#include "obscura/core/ray.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

struct GaussianPuffSpec {
  Vec3 center_m{0, 0, 0};
  double radius_m = 1.0;      // the Gaussian's standard deviation s
  double extent_radii = 4.0;  // the grid spans ±extent_radii·s around the centre
  int resolution = 64;        // voxels along each axis
  std::vector<double> wavelengths_um{10.0};
  std::vector<double> peak_sigma_a{1.0};  // 1/m at the centre, per sample
  std::vector<double> peak_sigma_s{0.0};  // 1/m at the centre, per sample
  std::vector<double> g{0.0};             // per sample
  double ambient_temperature_k = 290.0;
  double temperature_excess_k = 0.0;  // ΔT at the centre

  void validate() const;  // throws InputError on inconsistent or invalid values
};

// Samples the puff at voxel centres.
VoxelGrid make_gaussian_puff(const GaussianPuffSpec& spec);

// Closed-form ∫ ρ(o + t d) dt over [t0, t1] for unit d:
//   s √(π/2) e^{−(|p|² − b²)/(2s²)} [erf((t1 + b)/(s√2)) − erf((t0 + b)/(s√2))],
// with p = o − c and b = p·d. Multiply by a peak coefficient for optical depth.
double gaussian_puff_line_integral(const GaussianPuffSpec& spec, const Ray& ray, double t0,
                                   double t1);

}  // namespace obscura
