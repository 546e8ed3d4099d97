#include "obscura/render/emission_absorption/emission_absorption_integrator.h"

#include <array>

#include "obscura/render/background.h"
#include "obscura/render/emission_absorption/emission_absorption.h"

namespace obscura {

namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

}  // namespace

std::unique_ptr<RayWorkspace> EmissionAbsorptionIntegrator::make_workspace() const {
  return std::make_unique<Workspace>();
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
  integrate_emission(scene_.medium.get(), camera.ray, camera.t_end(), nodes,
                     scene_.settings.emission_quadrature, scene_.settings.relative_tolerance,
                     radiance, transmittance, &stats);
  workspace.segments += stats.segments;
  workspace.integrand_evals += stats.integrand_evals;
  std::array<double, kMaxSpectralNodes> behind;
  background_radiance(scene_, camera, nodes, static_cast<Workspace&>(workspace).background,
                      behind.data());
  for (int i = 0; i < n; ++i) radiance[i] += transmittance[i] * behind[i];
}

}  // namespace obscura
