#include "obscura/optics/material_species_optics.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace obscura {

SpeciesOptics material_species_optics(const Material& material,
                                      const std::vector<double>& wavelengths_um,
                                      double relative_humidity, int threads,
                                      std::vector<std::string>& warnings) {
  SpeciesOptics s;
  s.name = material.name;
  s.wavelengths_um = wavelengths_um;
  const std::vector<MaterialOptics> o =
      optics_at(material, wavelengths_um, relative_humidity, threads);
  for (const MaterialOptics& m : o) {
    if (std::isnan(m.mass_scattering_m2_g) || std::isnan(m.asymmetry)) {
      warnings.push_back(
          fmt::format("{} at {} um: the sources give extinction only ({} m2/g); it is "
                      "taken as absorption (albedo 0, g 0)",
                      material.name, m.wavelength_um, m.mass_extinction_m2_g));
      s.mass_absorption_m2_g.push_back(m.mass_extinction_m2_g);
      s.mass_scattering_m2_g.push_back(0.0);
      s.asymmetry.push_back(0.0);
    } else {
      s.mass_absorption_m2_g.push_back(m.mass_absorption_m2_g);
      s.mass_scattering_m2_g.push_back(m.mass_scattering_m2_g);
      s.asymmetry.push_back(std::clamp(m.asymmetry, -0.999, 0.999));
    }
  }
  return s;
}

}  // namespace obscura
