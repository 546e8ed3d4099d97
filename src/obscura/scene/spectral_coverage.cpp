#include "obscura/scene/spectral_coverage.h"

#include <fmt/format.h>

namespace obscura {

std::vector<std::string> bands_beyond_cloud_samples(const Scene& scene) {
  std::vector<std::string> notes;
  if (!scene.medium) return notes;
  const std::vector<double>& w = scene.medium->wavelengths_um();
  if (w.size() < 2) return notes;  // grey: one value at every wavelength, by design
  const double first = w.front(), last = w.back();
  for (const Sensor& s : scene.sensors)
    for (const Band& b : s.bands) {
      if (b.hi_um() >= first && b.lo_um() <= last) continue;  // some of it is sampled
      const double held = b.hi_um() < first ? first : last;
      notes.push_back(
          fmt::format("sensor {}, band {} ({:g}-{:g} µm) lies outside the clouds' spectral "
                      "samples ({:g}-{:g} µm): their coefficients are held at the {:g} µm values "
                      "across it; prepare the clouds at wavelengths in the band",
                      s.name, b.name(), b.lo_um(), b.hi_um(), first, last, held));
    }
  return notes;
}

}  // namespace obscura
