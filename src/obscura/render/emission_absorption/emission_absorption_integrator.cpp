#include "obscura/render/emission_absorption/emission_absorption_integrator.h"

#include <array>
#include <chrono>

#include "obscura/render/background.h"
#include "obscura/render/emission_absorption/emission_absorption.h"
#include "obscura/render/emission_absorption/emission_source.h"
#include "obscura/render/lattice/lattice_march.h"

namespace obscura {

namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

}  // namespace

EmissionAbsorptionIntegrator::EmissionAbsorptionIntegrator(const Scene& scene,
                                                           const FrameSpectra& spectra)
    : scene_(scene), spectra_(spectra), distinct_(distinct_nodes(spectra)) {
  if (!scene.medium || distinct_.nodes.empty() ||
      scene.settings.emission_quadrature != EmissionQuadrature::kCell)
    return;
  const auto start = std::chrono::steady_clock::now();
  std::vector<SpectralLerp> lerps;
  for (const SpectralNode& nd : distinct_.nodes) lerps.push_back(nd.lerp());
  GridRecords records =
      grid_records(*scene.medium, lerps, record::kMediumStride, scene.settings.threads);
  if (!records.volume) return;  // not one grid: the medium's march
  lattice_ = std::move(records.lattice);
  volume_ = std::move(records.volume);
  preparation_.seconds = preparation_.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

EmissionAbsorptionIntegrator::~EmissionAbsorptionIntegrator() = default;

PreparationStats EmissionAbsorptionIntegrator::preparation(int sensor) const {
  return sensor == 0 ? preparation_ : PreparationStats{};
}

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
  if (volume_) {
    std::array<PlanckTableView, kMaxSpectralNodes> planck;
    for (int i = 0; i < n; ++i) planck[i] = nodes.nodes()[i].planck_table->view();
    const EmissionSource source{planck.data()};
    workspace.segments += march_lattice<record::kMediumStride>(
        *volume_, distinct_.index[sensor][band].data(), n, camera.ray, camera.t_end(), source,
        radiance, transmittance);
  } else {
    EmissionAbsorptionStats stats;
    integrate_emission(scene_.medium.get(), camera.ray, camera.t_end(), nodes,
                       scene_.settings.emission_quadrature, scene_.settings.relative_tolerance,
                       radiance, transmittance, &stats);
    workspace.segments += stats.segments;
    workspace.integrand_evals += stats.integrand_evals;
  }
  std::array<double, kMaxSpectralNodes> behind;
  background_radiance(scene_, camera, nodes, static_cast<Workspace&>(workspace).background,
                      behind.data());
  for (int i = 0; i < n; ++i) radiance[i] += transmittance[i] * behind[i];
}

}  // namespace obscura
