#pragma once
// The scene file's environment objects (docs/formats.md): the sky, the sun and
// the atmosphere between sensors and scene. Errors name the file and the
// JSON path; unknown keys are errors.
#include <vector>

#include "obscura/io/json_reader.h"
#include "obscura/scene/atmosphere.h"
#include "obscura/scene/sensor.h"
#include "obscura/scene/sky.h"
#include "obscura/scene/sun.h"

namespace obscura {

Sky parse_sky(JsonObject& sky);
Sun parse_sun(JsonObject& sun);
Atmosphere parse_atmosphere(JsonObject& atmosphere, const std::vector<Sensor>& sensors);

}  // namespace obscura
