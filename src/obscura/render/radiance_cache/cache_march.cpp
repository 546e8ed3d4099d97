#include "obscura/render/radiance_cache/cache_march.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "obscura/core/check.h"
#include "obscura/render/emission_absorption/emission_marcher.h"
#include "obscura/render/lattice/lattice_march.h"

namespace obscura {
namespace {

// p_HG(μ) per steradian (medium/phase_function.h has the careful form; here g
// is clamped to |g| ≤ 0.999999, where this one is exact to rounding).
inline double hg(double g, double mu) {
  const double d = 1.0 + g * g - 2.0 * g * mu;
  return (1.0 - g * g) * (0.25 * std::numbers::inv_pi) / (d * std::sqrt(d));
}

inline double clamped_g(double g) { return std::clamp(g, -0.999999, 0.999999); }

// What every point of one camera ray shares: the harmonics of the direction
// the light travels (towards the camera), the sun's cosine with it, and the
// sun's irradiance at each node of the band.
class RayLight {
 public:
  RayLight(const Scene& scene, const RadianceCache& cache, const Ray& ray,
           const SpectralNodes& nodes)
      : sh_degree_(cache.sh_degree()) {
    spherical_harmonics(-ray.direction, y_);
    mu_sun_ = scene.sun.enabled ? dot(scene.sun.direction(), ray.direction) : 0.0;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      sun_irradiance_[j] =
          scene.sun.enabled ? scene.sun.irradiance(nodes.nodes()[j].wavelength_um) : 0.0;
  }

  // J at node j from the point's g and light channels (`light` from
  // record::kTauSun on, interpolated). Not clamped at zero: the photon
  // estimate is linear in the photons, so its noise (which can make a
  // truncated expansion dip below zero) averages out along the ray.
  double in_scattered(int j, double g, const float* light) const {
    static_assert(record::kSunVisibility == record::kTauSun + 1 &&
                  record::kSh == record::kTauSun + 2);
    const double tau = light[0], visibility = light[1];
    double j_in = 0.0;
    if (visibility > 0.0) j_in += sun_irradiance_[j] * hg(g, mu_sun_) * visibility * std::exp(-tau);
    return j_in + hg_convolved(light + 2, y_, g, sh_degree_);
  }

 private:
  int sh_degree_;
  std::array<double, kMaxShCoefficients> y_;
  std::array<double, kMaxSpectralNodes> sun_irradiance_{};
  double mu_sun_ = 0.0;
};

// The lattice march's Source (render/lattice/lattice_march.h).
struct CacheSource {
  const RayLight& light;
  const SpectralNode* nodes;
  void point(int j, const float* v, double& sigma_t, double& emissivity) const {
    const double sigma_a = v[record::kSigmaA], sigma_s = v[record::kSigmaS];
    sigma_t = sigma_a + sigma_s;
    emissivity = sigma_a != 0.0 ? sigma_a * (*nodes[j].planck_table)(v[record::kTemperature]) : 0.0;
    if (sigma_s > 0.0)
      emissivity += sigma_s * light.in_scattered(j, clamped_g(v[record::kSigmaSG] / sigma_s),
                                                 v + record::kTauSun);
  }
};

template <int Stride>
std::uint64_t march_records(const LatticeVolume& volume, const int* record, int nodes,
                            const CameraRay& camera, const CacheSource& source, double* radiance,
                            double* transmittance) {
  return march_lattice<Stride>(volume, record, nodes, camera.ray, camera.t_end(), source, radiance,
                               transmittance);
}

// σs J from the cache at a point of the medium's march (emission_marcher.h's
// InScattering), the light channels interpolated from the records.
class CacheInScattering {
 public:
  static constexpr bool kWantsG = true;

  CacheInScattering(const RadianceCache& cache, const RayLight& light, const Ray& ray,
                    const int* record, int nodes)
      : cache_(cache), light_(light), ray_(ray), record_(record), nodes_(nodes) {}

  void add(const MarchCell&, int, double t, const double* sigma_s, const double* g,
           double* emissivity) {
    bool scatters = false;
    for (int j = 0; j < nodes_; ++j) scatters = scatters || sigma_s[j] > 0.0;
    if (!scatters) return;
    std::array<std::size_t, 8> slot;
    std::array<double, 8> w;
    if (!cache_.lattice().corners(ray_.at(t), slot, w)) return;
    const LatticeVolume& volume = cache_.volume();
    const int stride = volume.stride(), count = record::kSh + cache_.sh_count();
    for (int j = 0; j < nodes_; ++j) {
      if (!(sigma_s[j] > 0.0)) continue;
      std::array<float, record::kSh + kMaxShCoefficients> v{};
      const float* records = volume.records(record_[j]);
      for (int c = 0; c < 8; ++c) {
        if (slot[c] == NodeLattice::kNoSlot || w[c] == 0.0) continue;
        const float* r = records + slot[c] * static_cast<std::size_t>(stride);
        for (int i = record::kTauSun; i < count; ++i) v[i] += static_cast<float>(w[c] * r[i]);
      }
      emissivity[j] +=
          sigma_s[j] * light_.in_scattered(j, clamped_g(g[j]), v.data() + record::kTauSun);
    }
  }

 private:
  const RadianceCache& cache_;
  const RayLight& light_;
  const Ray& ray_;
  const int* record_;
  int nodes_;
};

}  // namespace

std::uint64_t march_cache_lattice(const Scene& scene, const RadianceCache& cache,
                                  const CameraRay& camera, const SpectralNodes& nodes,
                                  const int* record, double* radiance, double* transmittance) {
  const RayLight light(scene, cache, camera.ray, nodes);
  const CacheSource source{light, nodes.nodes().data()};
  const int n = static_cast<int>(nodes.size());
  const LatticeVolume& volume = cache.volume();
  switch (volume.stride()) {
    case record::light_stride(1):
      return march_records<record::light_stride(1)>(volume, record, n, camera, source, radiance,
                                                    transmittance);
    case record::light_stride(4):
      return march_records<record::light_stride(4)>(volume, record, n, camera, source, radiance,
                                                    transmittance);
    case record::light_stride(9):
      return march_records<record::light_stride(9)>(volume, record, n, camera, source, radiance,
                                                    transmittance);
    default:
      OBSCURA_CHECK(volume.stride() == record::light_stride(kMaxShCoefficients));
      return march_records<record::light_stride(kMaxShCoefficients)>(
          volume, record, n, camera, source, radiance, transmittance);
  }
}

std::uint64_t march_cache_medium(const Scene& scene, const RadianceCache& cache,
                                 const CameraRay& camera, const SpectralNodes& nodes,
                                 const int* record, double* radiance, double* transmittance) {
  const RayLight light(scene, cache, camera.ray, nodes);
  CacheInScattering in(cache, light, camera.ray, record, static_cast<int>(nodes.size()));
  EmissionMarcher<CacheInScattering> marcher(nodes, in, radiance, transmittance);
  MarchOptions march;
  march.with_g = true;
  // Medium cells longer than a lattice spacing (a box's) are cut, so the
  // light is read at least once per lattice cell; a grid the lattice is laid
  // on has the lattice's cells already.
  if (!cache.volume().has_medium()) march.max_cell_m = cache.lattice().spacing_m();
  scene.medium->march_cells(camera.ray, 0.0, camera.t_end(), march, marcher);
  return marcher.cells();
}

}  // namespace obscura
