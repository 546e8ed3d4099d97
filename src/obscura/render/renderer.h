#pragma once
// Renders a sensor's images of a scene: for every pixel and band, band
// radiance (W m⁻² sr⁻¹), line-of-sight transmittance of the medium up to the
// first surface (response-weighted over the band, dimensionless) and apparent
// temperature (K, the blackbody temperature with the same band radiance).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "obscura/core/band.h"
#include "obscura/film/sensor_image.h"
#include "obscura/scene/scene.h"

namespace obscura {

struct RenderOptions {
  int threads = 0;         // 0: all cores
  std::uint64_t seed = 1;  // per-pixel streams derive from it
  // Called as rows complete, with (rows done, rows total); may be called from any thread.
  std::function<void(int, int)> progress;
};

SensorImage render_sensor(const Scene& scene, const Sensor& sensor, const RenderOptions& options);

}  // namespace obscura
