#include "obscura/io/vdb_keyframe_layout.h"

#include <fmt/format.h>

#include <mutex>
#include <tuple>

namespace obscura::vdb_format {

const std::set<std::string>& reserved_keys() {
  static const std::set<std::string> keys = {"obscura_format",
                                             "obscura_format_version",
                                             "obscura_form",
                                             "time_s",
                                             "wavelengths_um",
                                             "spectral_count",
                                             "dims",
                                             "coefficient_units",
                                             "temperature_units",
                                             "placement",
                                             "species_count",
                                             "species_optics",
                                             "concentration_units"};
  return keys;
}

void ensure_openvdb_initialized() {
  static std::once_flag once;
  std::call_once(once, [] { openvdb::initialize(); });
}

std::vector<GridSpec> spectral_layout(const std::vector<double>& wavelengths_um) {
  const int n = static_cast<int>(wavelengths_um.size());
  std::vector<GridSpec> layout;
  for (const auto& [prefix, units, fog] :
       {std::tuple{"sigma_a_", kCoefficientUnits, true},
        std::tuple{"sigma_s_", kCoefficientUnits, true}, std::tuple{"g_", "1", false}})
    for (int k = 0; k < n; ++k)
      layout.push_back({fmt::format("{}{:03d}", prefix, k), units, fog, k, wavelengths_um[k], ""});
  layout.push_back({kTransformGrid, kTemperatureUnits, false, -1, 0.0, ""});
  return layout;
}

std::vector<GridSpec> species_layout(const std::vector<SpeciesOptics>& species) {
  std::vector<GridSpec> layout;
  for (std::size_t s = 0; s < species.size(); ++s)
    layout.push_back({species_concentration_name(static_cast<int>(s)), kConcentrationUnits, true,
                      -1, 0.0, species[s].name});
  layout.push_back({kTransformGrid, kTemperatureUnits, false, -1, 0.0, ""});
  return layout;
}

openvdb::CoordBBox dense_bbox(const GridDims& d) {
  return openvdb::CoordBBox(openvdb::Coord(0, 0, 0), openvdb::Coord(d.nx - 1, d.ny - 1, d.nz - 1));
}

}  // namespace obscura::vdb_format
