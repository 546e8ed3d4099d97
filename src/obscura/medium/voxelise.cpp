#include "obscura/medium/voxelise.h"

#include <fmt/format.h>

#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

SpeciesCloud species_cloud(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                           double ambient_temperature_k, const std::string& source) {
  if (optics.wavelengths_um.empty())
    throw InputError(source, "optics", "needs at least one wavelength");
  check_species_optics(optics, optics.wavelengths_um, source, "optics");
  if (!(ambient_temperature_k > 0 && std::isfinite(ambient_temperature_k)))
    throw InputError(source, "ambient_temperature_k", "must be a finite temperature > 0 K");
  const ScalarGrid& c = frame.concentration_g_m3;
  if (c.values.size() != c.dims.count())
    throw InputError(source, fmt::format("frame at {} s", frame.time_s),
                     "concentration grid has the wrong size");
  if (frame.temperature_k && frame.temperature_k->values.size() != c.values.size())
    throw InputError(source, fmt::format("frame at {} s", frame.time_s),
                     "temperature and concentration grids differ in size");
  SpeciesCloud cloud;
  cloud.dims = c.dims;
  cloud.placement = c.placement;
  cloud.wavelengths_um = optics.wavelengths_um;
  cloud.species = {optics};
  cloud.concentration_g_m3 = {c.values};
  cloud.temperature_k =
      frame.temperature_k
          ? frame.temperature_k->values
          : std::vector<float>(c.values.size(), static_cast<float>(ambient_temperature_k));
  return cloud;
}

VoxelGrid voxelise(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                   double ambient_temperature_k, const std::string& source) {
  return expand_species(species_cloud(frame, optics, ambient_temperature_k, source), source);
}

}  // namespace obscura
