#include "obscura/scene/environment_loader.h"

#include <fmt/format.h>

#include <cmath>

namespace obscura {

// "sky": {"temperature": K, "below_horizon": true} or a zenith table
// {"zenith_deg": [...], "wavelengths_um": [...], "radiance": [[...], ...]}.
Sky parse_sky(JsonObject& sky) {
  if (sky.has("temperature")) {
    if (sky.has("zenith_deg") || sky.has("radiance"))
      throw sky.error("temperature", "give either a temperature or a zenith table, not both");
    const double t = sky.number("temperature");
    if (!(t >= 0)) throw sky.error("temperature", "must be >= 0 K");
    const bool below = sky.boolean_or("below_horizon", true);
    sky.finish();
    return Sky::blackbody(t, below);
  }
  if (!sky.has("zenith_deg"))
    throw sky.error("temperature",
                    "give a brightness temperature (K) or a table: zenith_deg, "
                    "wavelengths_um and radiance (W m-2 sr-1 um-1)");
  std::vector<double> zenith = sky.numbers("zenith_deg");
  std::vector<double> wavelengths = sky.numbers("wavelengths_um");
  const auto& rows = sky.array("radiance");
  std::vector<std::vector<double>> radiance;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (!rows[i].is_array())
      throw InputError(sky.file(), fmt::format("{}/{}", sky.path_of("radiance"), i),
                       "must be an array of radiances, one per wavelength");
    std::vector<double> row;
    for (std::size_t j = 0; j < rows[i].size(); ++j) {
      if (!rows[i][j].is_number())
        throw InputError(sky.file(), fmt::format("{}/{}/{}", sky.path_of("radiance"), i, j),
                         "must be a number (W m-2 sr-1 um-1)");
      row.push_back(rows[i][j].get<double>());
    }
    radiance.push_back(std::move(row));
  }
  sky.finish();
  try {
    return Sky::zenith_table(std::move(zenith), std::move(wavelengths), std::move(radiance), "");
  } catch (const InputError& e) {
    throw InputError(sky.file(), sky.path() + "/" + e.field(), e.detail());
  }
}

// "sun": {"azimuth_deg", "elevation_deg", "angular_diameter_deg",
// "temperature", "total_irradiance"} or an "irradiance_table".
Sun parse_sun(JsonObject& sun) {
  Sun s;
  s.enabled = true;
  s.azimuth_deg = sun.number("azimuth_deg");
  s.elevation_deg = sun.number("elevation_deg");
  if (!(s.elevation_deg > 0 && s.elevation_deg <= 90))
    throw sun.error("elevation_deg",
                    "must lie in (0, 90] degrees: a sun below the horizon lights nothing");
  s.angular_diameter_deg = sun.number_or("angular_diameter_deg", s.angular_diameter_deg);
  if (!(s.angular_diameter_deg > 0 && s.angular_diameter_deg < 10))
    throw sun.error("angular_diameter_deg", "must lie in (0, 10) degrees");
  s.temperature_k = sun.number_or("temperature", s.temperature_k);
  if (!(s.temperature_k > 0)) throw sun.error("temperature", "must be > 0 K");
  s.total_irradiance_w_m2 = sun.number_or("total_irradiance", s.total_irradiance_w_m2);
  if (!(s.total_irradiance_w_m2 >= 0))
    throw sun.error("total_irradiance", "must be >= 0 W m-2 (a negative irradiance is not light)");
  if (auto table = sun.optional_object("irradiance_table")) {
    if (sun.has("temperature") || sun.has("total_irradiance"))
      throw sun.error("irradiance_table",
                      "give either irradiance_table or temperature/total_irradiance, not both");
    std::vector<double> wavelengths = table->numbers("wavelengths_um");
    std::vector<double> irradiance = table->numbers("irradiance_w_m2_um");
    if (wavelengths.size() < 2)
      throw table->error("wavelengths_um", "needs at least two wavelengths");
    if (irradiance.size() != wavelengths.size())
      throw table->error("irradiance_w_m2_um",
                         fmt::format("needs one value per wavelength ({}, got {})",
                                     wavelengths.size(), irradiance.size()));
    for (std::size_t i = 0; i < wavelengths.size(); ++i) {
      if (!(wavelengths[i] > (i ? wavelengths[i - 1] : 0.0)))
        throw table->error(fmt::format("wavelengths_um/{}", i),
                           "must be > 0 µm and strictly increasing");
      if (!(irradiance[i] >= 0))
        throw table->error(fmt::format("irradiance_w_m2_um/{}", i),
                           "must be >= 0 W m-2 um-1 (a negative irradiance is not light)");
    }
    s.irradiance_table = TabulatedSpectrum(std::move(wavelengths), std::move(irradiance),
                                           TabulatedSpectrum::Outside::kZero);
    table->finish();
  }
  sun.finish();
  return s;
}

// "atmosphere": {"temperature": K, "extinction_per_km": number or {band: 1/km}};
// every band of every sensor needs a coefficient.
Atmosphere parse_atmosphere(JsonObject& atm, const std::vector<Sensor>& sensors) {
  Atmosphere a;
  a.enabled = true;
  a.temperature_k = atm.number("temperature");
  if (!(a.temperature_k > 0 && a.temperature_k < 1000))
    throw atm.error("temperature", "must be an air temperature in K (0, 1000)");
  const auto& ext = atm.raw("extinction_per_km");
  const std::string ext_path = atm.path_of("extinction_per_km");
  auto coefficient = [&](const nlohmann::json& v, const std::string& path) {
    if (!v.is_number() || !(v.get<double>() >= 0) || !std::isfinite(v.get<double>()))
      throw InputError(atm.file(), path, "expected an extinction coefficient >= 0 in 1/km");
    return v.get<double>() / 1000.0;
  };
  if (ext.is_number()) {
    a.extinction_per_m["*"] = coefficient(ext, ext_path);
  } else if (ext.is_object()) {
    for (const auto& [band, v] : ext.items())
      a.extinction_per_m[band] = coefficient(v, ext_path + "/" + band);
  } else {
    throw atm.error("extinction_per_km",
                    "expected a number (1/km, every band) or an object of band name → 1/km");
  }
  for (std::size_t i = 0; i < sensors.size(); ++i)
    for (const Band& b : sensors[i].bands)
      if (!a.extinction_per_m.count(b.name()) && !a.extinction_per_m.count("*"))
        throw InputError(
            atm.file(), ext_path,
            fmt::format("no coefficient for band '{}' of sensor '{}' (give one per band, "
                        "or a number for all)",
                        b.name(), sensors[i].name));
  atm.finish();
  return a;
}

}  // namespace obscura
