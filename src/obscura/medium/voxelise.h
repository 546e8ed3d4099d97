#pragma once
// The preparation phase's last step (docs/preparation.md, the source paper's
// "preparation phase"), also taken by a scene's vdb-density clouds as they
// are read (scene/vdb_density_cloud.h): particle mass concentration c (g/m³)
// and the mass optical coefficients of the particles (m²/g) give the
// radiative properties of every voxel,
//   σa(λ) = c · k_abs(λ),  σs(λ) = c · k_sca(λ)  (1/m),  g(λ) = g_particles(λ),
// and the temperature is the frame's, or the ambient air's where the source
// has none. The formula is expand_species's (medium/species_optics.h) for one
// species, so a frame written in the compact species form expands on reading
// to exactly the grid voxelise gives.
#include <string>

#include "obscura/medium/concentration_series.h"
#include "obscura/medium/species_optics.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// The one-species compact cloud of one frame: its concentration, its
// temperature (or `ambient_temperature_k` everywhere where the frame has
// none), and `optics`, whose wavelengths become the cloud's. Checks the
// optics, the ambient temperature and the array sizes; throws InputError
// naming `source` otherwise.
SpeciesCloud species_cloud(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                           double ambient_temperature_k, const std::string& source);

// The voxel grid of one frame: expand_species(species_cloud(...)). Checks the
// optics (sizes, finite, k ≥ 0, |g| < 1) and the grid's memory before
// allocating; throws InputError naming `source` otherwise.
VoxelGrid voxelise(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                   double ambient_temperature_k, const std::string& source);

}  // namespace obscura
