#include "obscura/render/radiance_cache/radiance_cache_integrator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>

#include "obscura/render/background.h"
#include "obscura/render/emission_absorption/emission_marcher.h"

namespace obscura {
namespace {

struct Workspace final : RayWorkspace {
  BackgroundScratch background;
};

// p_HG(μ) per steradian (medium/phase_function.h has the careful form; here g
// is clamped to |g| ≤ 0.999999, where this one is exact to rounding).
inline double hg(double g, double mu) {
  const double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) * (0.25 * std::numbers::inv_pi) / (d * std::sqrt(d));
}

// σs J from the cache at a point of the camera march, for every node of a band.
class CacheInScattering {
 public:
  static constexpr bool kWantsG = true;

  CacheInScattering(const Scene& scene, const RadianceCache& cache, const Ray& ray,
                    const SpectralNodes& nodes, const int* node_index)
      : cache_(cache), ray_(ray), nodes_(nodes), node_index_(node_index) {
    spherical_harmonics(-ray.direction, y_);  // ω: the light travels towards the camera
    mu_sun_ = scene.sun.enabled ? dot(scene.sun.direction(), ray.direction) : 0.0;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      sun_irradiance_[j] =
          scene.sun.enabled ? scene.sun.irradiance(nodes.nodes()[j].wavelength_um) : 0.0;
  }

  void add(const MarchCell&, int, double t, const double* sigma_s, const double* g,
           double* emissivity) {
    const int n = static_cast<int>(nodes_.size());
    bool scatters = false;
    for (int j = 0; j < n; ++j) scatters = scatters || sigma_s[j] > 0.0;
    if (!scatters) return;
    std::array<std::size_t, 8> slot;
    std::array<double, 8> w;
    if (!cache_.lattice().corners(ray_.at(t), slot, w)) return;
    const int ns = cache_.spectral_count();
    std::array<double, 64> tau{};  // per medium sample (at most 64 read here)
    double visibility = 0.0;
    if (cache_.has_sun()) {
      for (int c = 0; c < 8; ++c) {
        if (slot[c] == CacheLattice::kNoSlot || w[c] == 0.0) continue;
        const float* s = cache_.sun(slot[c]);
        for (int k = 0; k < std::min(ns, 64); ++k) tau[k] += w[c] * s[k];
        visibility += w[c] * s[ns];
      }
    }
    const int count = cache_.sh_count();
    for (int j = 0; j < n; ++j) {
      if (!(sigma_s[j] > 0.0)) continue;
      const double gj = std::clamp(g[j], -0.999999, 0.999999);
      double j_in = 0.0;
      if (visibility > 0.0) {
        const SpectralLerp lerp = nodes_.nodes()[j].lerp();
        j_in += sun_irradiance_[j] * hg(gj, mu_sun_) * visibility * std::exp(-lerp(tau.data()));
      }
      std::array<float, kMaxShCoefficients> coeff{};
      for (int c = 0; c < 8; ++c) {
        if (slot[c] == CacheLattice::kNoSlot || w[c] == 0.0) continue;
        const float* r = cache_.radiance(node_index_[j], slot[c]);
        for (int i = 0; i < count; ++i) coeff[i] += static_cast<float>(w[c] * r[i]);
      }
      j_in += hg_convolved(coeff.data(), y_, gj, cache_.sh_degree());
      // Not clamped at zero: the photon estimate is linear in the photons, so
      // its noise (which can make a truncated expansion dip below zero)
      // averages out along the ray without bias.
      emissivity[j] += sigma_s[j] * j_in;
    }
  }

 private:
  const RadianceCache& cache_;
  const Ray& ray_;
  const SpectralNodes& nodes_;
  const int* node_index_;
  std::array<double, kMaxShCoefficients> y_;
  std::array<double, kMaxSpectralNodes> sun_irradiance_{};
  double mu_sun_ = 0.0;
};

}  // namespace

RadianceCacheIntegrator::RadianceCacheIntegrator(const Scene& scene, const FrameSpectra& spectra,
                                                 const ProcessGroup& processes)
    : scene_(scene), spectra_(spectra) {
  // The distinct wavelengths of every sensor's bands: sensors that share a
  // band share its cache.
  for (const auto& sensor_bands : spectra) {
    auto& sensor_index = node_index_.emplace_back();
    for (const SpectralNodes& band : sensor_bands) {
      auto& band_index = sensor_index.emplace_back();
      for (const SpectralNode& nd : band.nodes()) {
        int u = 0;
        while (u < static_cast<int>(distinct_.size()) &&
               distinct_[u].wavelength_um != nd.wavelength_um)
          ++u;
        if (u == static_cast<int>(distinct_.size())) distinct_.push_back(nd);
        band_index.push_back(u);
      }
    }
  }
  if (scene.medium && !distinct_.empty()) {
    cache_ = std::make_unique<RadianceCache>(scene, distinct_, processes);
    preparation_.photons = cache_->photons_stored();
    preparation_.photon_bytes = cache_->memory_bytes();
    preparation_.seconds = cache_->seconds;
    preparation_.trace_seconds = cache_->photon_seconds;
    preparation_.build_seconds = cache_->seconds - cache_->photon_seconds;
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
  for (int j = 0; j < n; ++j) {
    radiance[j] = 0.0;
    transmittance[j] = 1.0;
  }
  if (cache_) {
    CacheInScattering in(scene_, *cache_, camera.ray, nodes, node_index_[sensor][band].data());
    EmissionMarcher<CacheInScattering> marcher(nodes, in, radiance, transmittance);
    MarchOptions march;
    march.with_g = true;
    march.max_cell_m = cache_->lattice().spacing_m();
    scene_.medium->march_cells(camera.ray, 0.0, camera.t_end(), march, marcher);
    workspace.segments += marcher.cells();
  }
  std::array<double, kMaxSpectralNodes> behind;
  auto& ws = static_cast<Workspace&>(workspace);
  background_radiance(scene_, camera, nodes, ws.background, behind.data());
  for (int j = 0; j < n; ++j) radiance[j] += transmittance[j] * behind[j];
}

}  // namespace obscura
