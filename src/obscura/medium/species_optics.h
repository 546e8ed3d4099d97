#pragma once
// The compact species form of a cloud (docs/formats.md, "Species form"; the
// DIRSIG PlumeVDB / EOSAEL habit, docs/domain.md §1): the mass concentration
// (g/m³) of one or a few particle species plus temperature per voxel, and each
// species' mass optical coefficients at the cloud's wavelengths.
// expand_species turns it into the dense spectral VoxelGrid every medium
// samples; the preparation phase (medium/voxelise) and the species keyframe
// reader (io/vdb_keyframe) both go through it, so the two keyframe forms give
// bit-identical grids.
#include <cstddef>
#include <string>
#include <vector>

#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

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

// Checks `optics` for a cloud sampled at `wavelengths_um`: a non-empty name,
// exactly those wavelengths, one k_abs, k_sca and g per wavelength, k finite
// and >= 0 m²/g, |g| < 1. Throws InputError naming `source` and the member
// (field + "/asymmetry/2", a JSON path when `field` is one) whose message
// names the species.
void check_species_optics(const SpeciesOptics& optics, const std::vector<double>& wavelengths_um,
                          const std::string& source, const std::string& field);

struct SpeciesCloud {
  GridDims dims;
  GridPlacement placement;
  std::vector<double> wavelengths_um;  // µm, strictly increasing
  std::vector<SpeciesOptics> species;  // each at exactly wavelengths_um
  // One array of dims.count() values per species (g/m³, x fastest).
  std::vector<std::vector<float>> concentration_g_m3;
  std::vector<float> temperature_k;  // K, dims.count() values

  // Bytes of the per-voxel data (concentrations and temperature).
  std::size_t memory_bytes() const;
};

// Name of species s's concentration grid in keyframe files and errors:
// "concentration_000", ... (docs/formats.md).
std::string species_concentration_name(int s);

// Checks everything expand_species relies on: dims > 0, a finite placement,
// wavelengths, 1…999 species with valid optics (check_species_optics, field
// "species/s"), array sizes, concentrations finite and >= 0 (field
// "concentration_NNN voxel (i,j,k)") and temperatures finite and >= 0 K
// ("temperature voxel (i,j,k)"). Throws InputError naming `source`.
void validate_species_cloud(const SpeciesCloud& cloud, const std::string& source);

// The dense spectral grid of `cloud` (docs/formats.md), at each wavelength k:
//   σa_k = Σ_s c_s k_abs,s(λ_k),   σs_k = Σ_s c_s k_sca,s(λ_k)   (1/m),
//   g_k  = Σ_s (c_s k_sca,s(λ_k) / σs_k) g_s(λ_k)   (scattering-weighted),
// T = the cloud's temperature. Sums are in double, rounded to float once.
// Where no particle scatters (σs_k = 0) g_k is the species' g weighted by
// k_sca alone (0 if no species scatters at λ_k): a clear voxel then carries
// the g a trace of the mixture would have, so a one-species cloud has exactly
// its material's g everywhere (renders never see it: media weight g by σs).
// Validates the cloud first and checks the grid's memory before allocating;
// throws InputError naming `source`.
VoxelGrid expand_species(const SpeciesCloud& cloud, const std::string& source);

}  // namespace obscura
