// `obscura radiance`: band radiance of a blackbody, and its inverse, the
// apparent temperature of a band radiance.
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "obscura/core/band.h"
#include "obscura/core/error.h"

namespace obscura::cli {

Command add_radiance_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "radiance",
      "Blackbody band radiance for a temperature, or the apparent temperature of a band radiance");
  struct Options {
    std::optional<double> temperature;
    std::optional<double> band_radiance;
    std::string band;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  auto* temperature_option =
      cmd->add_option("--temperature", o->temperature, "Blackbody temperature, K");
  auto* radiance_option =
      cmd->add_option("--band-radiance", o->band_radiance, "Band radiance to invert, W m-2 sr-1");
  temperature_option->excludes(radiance_option);
  cmd->add_option("--band", o->band,
                  "Band as LO:HI in micrometres (flat response) or a preset: visible, laser1064, "
                  "mwir, lwir")
      ->required();
  cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
  return {
      cmd, [o]() {
        if (!o->temperature && !o->band_radiance)
          throw InputError("", "radiance", "give --temperature K or --band-radiance L");
        const Band band = Band::parse(o->band, "--band");
        const BandQuadrature q = BandQuadrature::accurate(band);
        nlohmann::json out;
        out["band"] = {{"name", band.name()}, {"min_um", band.lo_um()}, {"max_um", band.hi_um()}};
        if (o->temperature) {
          const double temp = *o->temperature;
          if (!(temp >= 0 && std::isfinite(temp)))
            throw InputError("", "--temperature", "must be a finite temperature >= 0 K");
          const double l = q.blackbody_radiance(temp);
          out["temperature"] = temp;
          out["band_radiance"] = l;
          out["units"] = {{"temperature", "K"}, {"band_radiance", "W m-2 sr-1"}};
          if (o->json) {
            std::cout << out.dump(2) << "\n";
          } else {
            std::cout << fmt::format("band {} ({}–{} µm), blackbody at {} K:\n", band.name(),
                                     band.lo_um(), band.hi_um(), temp)
                      << fmt::format("  band radiance {:.6g} W m⁻² sr⁻¹\n", l);
          }
        } else {
          const double l = *o->band_radiance;
          if (!(l > 0 && std::isfinite(l)))
            throw InputError("", "--band-radiance", "must be a finite radiance > 0 W m-2 sr-1");
          const double temp = q.apparent_temperature(l);
          out["band_radiance"] = l;
          out["temperature"] = temp;
          out["units"] = {{"temperature", "K"}, {"band_radiance", "W m-2 sr-1"}};
          if (o->json) {
            std::cout << out.dump(2) << "\n";
          } else {
            std::cout << fmt::format("band {} ({}–{} µm), band radiance {} W m⁻² sr⁻¹:\n",
                                     band.name(), band.lo_um(), band.hi_um(), l)
                      << fmt::format("  apparent temperature {:.6f} K\n", temp);
          }
        }
        return 0;
      }};
}

}  // namespace obscura::cli
