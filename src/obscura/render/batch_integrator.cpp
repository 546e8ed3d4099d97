#include "obscura/render/batch_integrator.h"

#include <array>

#include "obscura/render/background.h"

namespace obscura {
namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

}  // namespace

std::vector<int> band_output_offsets(const std::vector<SpectralNodes>& bands) {
  std::vector<int> offsets{0};
  for (const SpectralNodes& nodes : bands)
    offsets.push_back(offsets.back() + static_cast<int>(nodes.size()));
  return offsets;
}

std::unique_ptr<RayWorkspace> BatchIntegrator::make_workspace() const {
  return std::make_unique<Workspace>();
}

void BatchIntegrator::behind_radiance(const CameraRay& ray, int sensor, int band,
                                      const SpectralNodes& nodes, BackgroundScratch& scratch,
                                      double* behind) const {
  background_radiance(scene_, ray, nodes, scratch, behind);
  add_surface_light(ray, sensor, band, behind);
}

void BatchIntegrator::band_radiance(const CameraRay& ray, int sensor, int band, Rng& /*rng*/,
                                    RayWorkspace& workspace, double* radiance,
                                    double* transmittance) const {
  MediumBatch batch;
  march_batch(sensor, std::span<const CameraRay>(&ray, 1), batch);
  workspace.segments += batch.band_cells[static_cast<std::size_t>(band)];
  const std::vector<SpectralNodes>& bands = spectra_[static_cast<std::size_t>(sensor)];
  const SpectralNodes& nodes = bands[static_cast<std::size_t>(band)];
  const int first = band_output_offsets(bands)[static_cast<std::size_t>(band)];
  std::array<double, kMaxSpectralNodes> behind;
  behind_radiance(ray, sensor, band, nodes, static_cast<Workspace&>(workspace).background,
                  behind.data());
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    transmittance[j] = batch.transmittance[first + j];
    radiance[j] = batch.radiance[first + j] + batch.attenuation[first + j] * behind[j];
  }
}

}  // namespace obscura
