#include "obscura/prep/voxelise.h"

#include <cmath>

#include <fmt/format.h>

#include "obscura/core/error.h"

namespace obscura {

VoxelGrid voxelise(const ConcentrationFrame& frame, const SpeciesOptics& optics,
                   double ambient_temperature_k, const std::string& source) {
  const std::size_t n = optics.wavelengths_um.size();
  if (n == 0) throw InputError(source, "optics", "needs at least one wavelength");
  if (optics.mass_absorption_m2_g.size() != n || optics.mass_scattering_m2_g.size() != n ||
      optics.asymmetry.size() != n)
    throw InputError(source, "optics", "needs one absorption, scattering and g value per wavelength");
  for (std::size_t k = 0; k < n; ++k) {
    if (!(optics.mass_absorption_m2_g[k] >= 0 && std::isfinite(optics.mass_absorption_m2_g[k])) ||
        !(optics.mass_scattering_m2_g[k] >= 0 && std::isfinite(optics.mass_scattering_m2_g[k])))
      throw InputError(source, fmt::format("optics at {} um", optics.wavelengths_um[k]),
                       "mass coefficients must be finite and >= 0 m2/g");
    if (!(std::abs(optics.asymmetry[k]) < 1))
      throw InputError(source, fmt::format("optics at {} um", optics.wavelengths_um[k]), "g must lie in (-1, 1)");
  }
  if (!(ambient_temperature_k > 0 && std::isfinite(ambient_temperature_k)))
    throw InputError(source, "ambient_temperature_k", "must be a finite temperature > 0 K");
  const ScalarGrid& c = frame.concentration_g_m3;
  if (c.values.size() != c.dims.count())
    throw InputError(source, fmt::format("frame at {} s", frame.time_s), "concentration grid has the wrong size");
  if (frame.temperature_k && frame.temperature_k->values.size() != c.values.size())
    throw InputError(source, fmt::format("frame at {} s", frame.time_s),
                     "temperature and concentration grids differ in size");
  VoxelGrid grid(c.dims, c.placement, optics.wavelengths_um, source);  // checks the memory first
  const std::size_t voxels = c.dims.count();
  for (std::size_t k = 0; k < n; ++k) {
    float* sa = grid.sigma_a(static_cast<int>(k));
    float* ss = grid.sigma_s(static_cast<int>(k));
    float* g = grid.g(static_cast<int>(k));
    const double ka = optics.mass_absorption_m2_g[k], ks = optics.mass_scattering_m2_g[k];
    const float gk = static_cast<float>(optics.asymmetry[k]);
    for (std::size_t v = 0; v < voxels; ++v) {
      sa[v] = static_cast<float>(c.values[v] * ka);
      ss[v] = static_cast<float>(c.values[v] * ks);
      g[v] = gk;
    }
  }
  float* t = grid.temperature();
  for (std::size_t v = 0; v < voxels; ++v)
    t[v] = frame.temperature_k ? frame.temperature_k->values[v] : static_cast<float>(ambient_temperature_k);
  grid.validate(source);
  return grid;
}

}  // namespace obscura
