#include "obscura/render/emission_absorption/emission_absorption_integrator.h"

#include <array>
#include <chrono>

#include "obscura/render/background.h"
#include "obscura/render/emission_absorption/emission_absorption.h"
#include "obscura/render/lattice/lattice_march.h"

namespace obscura {

namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

// σt and σa B(T) from a record (lattice_march.h's Source).
struct EmissionSource {
  const SpectralNode* nodes;
  void point(int j, const float* v, double& sigma_t, double& emissivity) const {
    const double sigma_a = v[record::kSigmaA];
    sigma_t = sigma_a + v[record::kSigmaS];
    emissivity = sigma_a != 0.0 ? sigma_a * (*nodes[j].planck_table)(v[record::kTemperature]) : 0.0;
  }
};

// Lattices up to this many nodes are laid out (only occupied blocks are stored).
constexpr double kMaxLatticeNodes = 4e9;

}  // namespace

EmissionAbsorptionIntegrator::EmissionAbsorptionIntegrator(const Scene& scene,
                                                           const FrameSpectra& spectra)
    : scene_(scene), spectra_(spectra), distinct_(distinct_nodes(spectra)) {
  if (!scene.medium || distinct_.nodes.empty() ||
      scene.settings.emission_quadrature != EmissionQuadrature::kCell)
    return;
  const std::optional<GridFrame> frame = scene.medium->grid_frame();
  if (!frame || !frame->voxels) return;  // not one grid
  const auto start = std::chrono::steady_clock::now();
  lattice_ = std::make_unique<NodeLattice>(*scene.medium, 0.0, 0.0,
                                           static_cast<std::size_t>(kMaxLatticeNodes));
  const VoxelGrid* grid = LatticeVolume::aligned_grid(*scene.medium, *lattice_);
  if (!grid) {
    lattice_.reset();
    return;
  }
  std::vector<SpectralLerp> lerps;
  for (const SpectralNode& nd : distinct_.nodes) lerps.push_back(nd.lerp());
  volume_ = std::make_unique<LatticeVolume>(*lattice_, lerps, record::kMediumStride, grid,
                                            scene.settings.threads, "clouds");
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
    const EmissionSource source{nodes.nodes().data()};
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
