#pragma once
// Mean values of a rendered band over a rectangle of pixels (a region of
// interest): what the time-series CSV of a frame sequence reports.
#include <string>
#include <vector>

#include "obscura/film/sensor_image.h"
#include "obscura/scene/scene.h"

namespace obscura {

struct RegionStats {
  std::string region;
  std::string band;
  double mean_radiance = 0;              // W m⁻² sr⁻¹
  double mean_transmittance = 0;         // 1
  double mean_apparent_temperature = 0;  // K, of the mean radiance
  int pixels = 0;
};

// One row per (region, band) for the regions of `image`'s sensor, preceded by
// the whole image as region "image". Apparent temperature is that of the mean
// band radiance (the average of temperatures would not be a radiometric mean),
// by the band's quadrature as `render` renders it (RenderSettings::spectral_nodes).
std::vector<RegionStats> region_stats(const SensorImage& image,
                                      const std::vector<PixelRegion>& regions,
                                      const RenderSettings& render);

}  // namespace obscura
