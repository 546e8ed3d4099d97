#include "obscura/render/integrator.h"

namespace obscura {

CameraRay find_camera_ray_hit(const Scene& scene, const Ray& ray) {
  CameraRay c;
  c.ray = ray;
  c.on_surface =
      intersect_surfaces(scene.surfaces, ray, 0.0, std::numeric_limits<double>::infinity(), c.hit);
  return c;
}

std::vector<SpectralNodes> sensor_spectra(const Scene& scene, const Sensor& sensor) {
  static const std::vector<double> grey = {1.0};
  const std::vector<double>& medium_wl = scene.medium ? scene.medium->wavelengths_um() : grey;
  std::vector<SpectralNodes> bands;
  for (const Band& band : sensor.bands) {
    bands.emplace_back(BandQuadrature(band, scene.settings.spectral_nodes(band), 0.0), medium_wl);
    if (bands.back().size() > static_cast<std::size_t>(kMaxSpectralNodes))
      throw InputError("", "band " + band.name(), "too many spectral nodes for one band");
  }
  return bands;
}

FrameSpectra frame_spectra(const Scene& scene) {
  FrameSpectra spectra;
  for (const Sensor& sensor : scene.sensors) spectra.push_back(sensor_spectra(scene, sensor));
  return spectra;
}

DistinctNodes distinct_nodes(const FrameSpectra& spectra) {
  DistinctNodes out;
  for (const auto& sensor_bands : spectra) {
    auto& sensor_index = out.index.emplace_back();
    for (const SpectralNodes& band : sensor_bands) {
      auto& band_index = sensor_index.emplace_back();
      for (const SpectralNode& nd : band.nodes()) {
        int u = 0;
        while (u < static_cast<int>(out.nodes.size()) &&
               out.nodes[u].wavelength_um != nd.wavelength_um)
          ++u;
        if (u == static_cast<int>(out.nodes.size())) out.nodes.push_back(nd);
        band_index.push_back(u);
      }
    }
  }
  return out;
}

std::vector<std::vector<int>> sensors_of_nodes(const DistinctNodes& distinct) {
  std::vector<std::vector<int>> sensors(distinct.nodes.size());
  for (std::size_t s = 0; s < distinct.index.size(); ++s)
    for (const std::vector<int>& band : distinct.index[s])
      for (const int u : band) {
        std::vector<int>& of_node = sensors[static_cast<std::size_t>(u)];
        if (of_node.empty() || of_node.back() != static_cast<int>(s))
          of_node.push_back(static_cast<int>(s));
      }
  return sensors;
}

}  // namespace obscura
