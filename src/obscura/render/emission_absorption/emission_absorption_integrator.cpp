#include "obscura/render/emission_absorption/emission_absorption_integrator.h"

#include "obscura/render/emission_absorption/emission_absorption.h"

namespace obscura {

std::unique_ptr<RayWorkspace> EmissionAbsorptionIntegrator::make_workspace() const {
  return std::make_unique<RayWorkspace>();
}

void EmissionAbsorptionIntegrator::band_radiance(const CameraRay& camera, int sensor, int band,
                                                 Rng& /*rng*/, RayWorkspace& workspace,
                                                 double* radiance, double* transmittance) const {
  const SpectralNodes& nodes = spectra_[sensor][band];
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    radiance[i] = 0.0;
    transmittance[i] = 1.0;
  }
  EmissionAbsorptionStats stats;
  integrate_emission_absorption(scene_.medium.get(), camera.ray, camera.t_end(), nodes,
                                scene_.settings.relative_tolerance, radiance, transmittance,
                                &stats);
  workspace.segments += stats.segments;
  workspace.integrand_evals += stats.integrand_evals;
  for (int i = 0; i < n; ++i) {
    const SpectralNode& nd = nodes.nodes()[i];
    double background;
    if (camera.on_surface) {
      const SurfaceMaterial& m = scene_.surfaces[camera.hit.surface]->material();
      const double emissivity = m.emissivity_at(nd.wavelength_um);
      background =
          emissivity * nd.planck(m.temperature_k) +
          (1.0 - emissivity) * scene_.sky.cosine_weighted_mean(camera.hit.normal, nd.wavelength_um);
    } else {
      background = scene_.sky.radiance(camera.ray.direction, nd.wavelength_um);
    }
    radiance[i] += transmittance[i] * background;
  }
}

}  // namespace obscura
