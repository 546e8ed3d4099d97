#pragma once
// The preparation phase's last step (DESIGN.md §4, the source paper's
// "preparation phase"): particle mass concentration c (g/m³) and the mass
// optical coefficients of the particles (m²/g) give the radiative properties
// of every voxel,
//   σa(λ) = c · k_abs(λ),  σs(λ) = c · k_sca(λ)  (1/m),  g(λ) = g_particles(λ),
// and the temperature is the frame's, or the ambient air's where the source
// has none.
#include <string>
#include <vector>

#include "obscura/medium/voxel_grid.h"
#include "obscura/prep/concentration_series.h"

namespace obscura {

// Mass optical coefficients of one particle species at the cloud's spectral
// samples.
struct SpeciesOptics {
  std::string name;
  std::vector<double> wavelengths_um;        // strictly increasing
  std::vector<double> mass_absorption_m2_g;  // k_abs
  std::vector<double> mass_scattering_m2_g;  // k_sca
  std::vector<double> asymmetry;             // HG g, in (−1, 1)
};

// The voxel grid of one frame. Checks the optics (sizes, finite, k ≥ 0,
// |g| < 1) and the grid's memory before allocating; throws InputError naming
// `source` otherwise.
VoxelGrid voxelise(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                   double ambient_temperature_k, const std::string& source);

}  // namespace obscura
