#pragma once
// Everything the built-in dispersion model needs: devices, wind, stability,
// σ set and ambient temperature, read from a JSON "dispersion" object
// (format, defaults and an example in docs/dispersion.md).
#include <string>
#include <vector>

#include "obscura/io/json_reader.h"
#include "obscura/prep/dispersion/smoke_device.h"
#include "obscura/prep/dispersion/stability.h"
#include "obscura/prep/dispersion/wind.h"

namespace obscura {

struct DispersionConfig {
  std::vector<SmokeDevice> devices;  // at least one
  Wind wind;
  StabilityClass stability = StabilityClass::kD;  // neutral: overcast, dawn and dusk
  SigmaSet sigma_set = SigmaSet::kCcpsPuff;       // docs/domain.md §3.7
  double ambient_temperature_k = 288.15;          // ISA sea level, 15 °C
  // Where the configuration came from and the JSON path of its object: every
  // validation error names source and json_path + "/devices/2/agent_mass_g".
  std::string source = "dispersion model";
  std::string json_path = "/dispersion";
};

// Checks every value (ranges in docs/dispersion.md); throws InputError naming
// config.source and the field's JSON path.
void validate_dispersion_config(const DispersionConfig& config);

// Reads a "dispersion" object; `dispersion.path()` (for instance "/dispersion")
// prefixes every error path. Unknown keys are errors. The wind's
// power_law_exponent defaults to the stability class's rural value
// (default_wind_profile_exponent). The result is validated.
DispersionConfig parse_dispersion_config(JsonObject dispersion);

}  // namespace obscura
