#include "obscura/analysis/region_stats.h"

namespace obscura {

std::vector<RegionStats> region_stats(const SensorImage& image,
                                      const std::vector<PixelRegion>& regions,
                                      const RenderSettings& render) {
  std::vector<PixelRegion> all = {{"image", image.sensor, 0, 0, image.width, image.height}};
  for (const auto& r : regions)
    if (r.sensor == image.sensor) all.push_back(r);
  std::vector<RegionStats> out;
  for (const auto& r : all) {
    for (const auto& b : image.bands) {
      RegionStats s;
      s.region = r.name;
      s.band = b.band.name();
      double l = 0, t = 0;
      for (int y = r.y0; y < r.y1; ++y)
        for (int x = r.x0; x < r.x1; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * image.width + x;
          l += b.radiance[i];
          t += b.transmittance[i];
        }
      s.pixels = (r.x1 - r.x0) * (r.y1 - r.y0);
      s.mean_radiance = l / s.pixels;
      s.mean_transmittance = t / s.pixels;
      // The same quadrature as the renderer's, so a uniform blackbody region gives its temperature.
      s.mean_apparent_temperature = BandQuadrature(b.band, render.spectral_nodes(b.band), 0.0)
                                        .apparent_temperature(s.mean_radiance);
      out.push_back(s);
    }
  }
  return out;
}

}  // namespace obscura
