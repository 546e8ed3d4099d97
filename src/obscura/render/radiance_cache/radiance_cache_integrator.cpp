#include "obscura/render/radiance_cache/radiance_cache_integrator.h"

#include <array>

#include "obscura/render/background.h"
#include "obscura/render/radiance_cache/cache_march.h"

namespace obscura {
namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

}  // namespace

RadianceCacheIntegrator::RadianceCacheIntegrator(const Scene& scene, const FrameSpectra& spectra,
                                                 const ProcessGroup& processes,
                                                 const PreparationProgress& progress)
    : scene_(scene), spectra_(spectra), distinct_(distinct_nodes(spectra)) {
  if (scene.medium && !distinct_.nodes.empty()) {
    // Only this integrator's camera rays read the cache: its light is made
    // where the sensors of each node look.
    cache_ = std::make_unique<RadianceCache>(
        scene, distinct_.nodes, processes, RadianceCache::SunDepths::kHere,
        sensors_of_nodes(distinct_), photons_of_nodes(scene, distinct_), progress);
    preparation_.photons = cache_->photons_stored();
    preparation_.photon_bytes = cache_->memory_bytes();
    preparation_.seconds = cache_->seconds;
    preparation_.trace_seconds = cache_->photon_seconds;
    preparation_.build_seconds = cache_->seconds - cache_->photon_seconds;
    preparation_.walks = cache_->photon_walks();
  }
}

PreparationStats RadianceCacheIntegrator::preparation(int sensor) const {
  return sensor == 0 ? preparation_ : PreparationStats{};
}

std::unique_ptr<RayWorkspace> RadianceCacheIntegrator::make_workspace() const {
  return std::make_unique<Workspace>();
}

void RadianceCacheIntegrator::band_radiance(const CameraRay& camera, int sensor, int band,
                                            Rng& /*rng*/, RayWorkspace& workspace, double* radiance,
                                            double* transmittance) const {
  const SpectralNodes& nodes = spectra_[sensor][band];
  const int n = static_cast<int>(nodes.size());
  // What the background is seen through: the transmittance, or more with
  // delta-M (cache_march.h).
  std::array<double, kMaxSpectralNodes> attenuation;
  for (int j = 0; j < n; ++j) {
    radiance[j] = 0.0;
    transmittance[j] = 1.0;
    attenuation[j] = 1.0;
  }
  if (cache_) {
    const int* record = distinct_.index[sensor][band].data();
    workspace.segments += cache_->volume().has_medium()
                              ? march_cache_lattice(scene_, *cache_, camera, nodes, record,
                                                    cache_->peak_channel(sensor), radiance,
                                                    transmittance, attenuation.data())
                              : march_cache_medium(scene_, *cache_, camera, nodes, record, radiance,
                                                   transmittance, attenuation.data());
  }
  std::array<double, kMaxSpectralNodes> behind;
  auto& ws = static_cast<Workspace&>(workspace);
  background_radiance(scene_, camera, nodes, ws.background, behind.data());
  // The cloud's light on the ground, which the surface's own radiance leaves
  // out (ground_light.h).
  if (cache_)
    add_ground_light(scene_, *cache_, camera, nodes, distinct_.index[sensor][band].data(),
                     behind.data());
  for (int j = 0; j < n; ++j) radiance[j] += attenuation[j] * behind[j];
}

}  // namespace obscura
