#pragma once
// A material of the database (optics/material.h) as one particle species of a
// cloud (medium/species_optics.h): its mass coefficients at the cloud's
// wavelengths, what both `obscura prepare` and a scene's vdb-density clouds
// multiply concentrations by.
#include <string>
#include <vector>

#include "obscura/medium/species_optics.h"
#include "obscura/optics/material.h"

namespace obscura {

// k_abs, k_sca (m²/g) and g of `material` at each of `wavelengths_um`, at a
// relative humidity in [0, 1), computed in parallel on `threads` (0: all
// cores). Where the sources give extinction only (tabulated infrared bands)
// the extinction is taken as absorption with g = 0 and a line saying so is
// appended to `warnings`; g is held inside ±0.999, as the media need |g| < 1.
// Throws InputError (optics_at's) where the material has no data.
SpeciesOptics material_species_optics(const Material& material,
                                      const std::vector<double>& wavelengths_um,
                                      double relative_humidity, int threads,
                                      std::vector<std::string>& warnings);

}  // namespace obscura
