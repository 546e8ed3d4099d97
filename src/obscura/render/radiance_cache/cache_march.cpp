#include "obscura/render/radiance_cache/cache_march.h"

#include <algorithm>
#include <array>

#include "obscura/core/check.h"
#include "obscura/render/emission_absorption/emission_marcher.h"
#include "obscura/render/lattice/lattice_march.h"
#include "obscura/render/radiance_cache/cache_source.h"

namespace obscura {
namespace {

// The per-ray light (cache_source.h) and the sun's irradiance at each node
// of the band, which it points to.
class RayLight {
 public:
  RayLight(const Scene& scene, const RadianceCache& cache, const Ray& ray,
           const SpectralNodes& nodes, int peak_channel = -1)
      : light_(ray.direction, scene.sun.enabled, scene.sun.enabled ? scene.sun.direction() : Vec3(),
               sun_irradiance_.data(), cache.sh_degree(), peak_channel) {
    for (std::size_t j = 0; j < nodes.size(); ++j)
      sun_irradiance_[j] =
          scene.sun.enabled ? scene.sun.irradiance(nodes.nodes()[j].wavelength_um) : 0.0;
    for (std::size_t j = 0; j < nodes.size(); ++j)
      planck_[j] = nodes.nodes()[j].planck_table->view();
  }
  RayLight(const RayLight&) = delete;
  RayLight& operator=(const RayLight&) = delete;

  const CacheLight& light() const { return light_; }
  const PlanckTableView* planck() const { return planck_.data(); }

 private:
  std::array<double, kMaxSpectralNodes> sun_irradiance_{};
  std::array<PlanckTableView, kMaxSpectralNodes> planck_;
  CacheLight light_;
};

// The lattice march over the cache's records, whose stride its degree gives.
template <class Source>
std::uint64_t march_records(const RadianceCache& cache, const int* record, int nodes,
                            const CameraRay& camera, const Source& source, double* radiance,
                            double* transmittance, double* attenuation) {
  return with_sh_count(cache.sh_degree(), [&](auto count) {
    constexpr int kStride = record::light_stride(decltype(count)::value);
    OBSCURA_CHECK(cache.volume().stride() == kStride);
    return march_lattice<kStride>(cache.volume(), record, nodes, camera.ray, camera.t_end(), source,
                                  radiance, transmittance, attenuation);
  });
}

// σs J from the cache at a point of the medium's march (emission_marcher.h's
// InScattering), the light channels interpolated from the records.
class CacheInScattering {
 public:
  static constexpr bool kWantsG = true;

  CacheInScattering(const Medium& medium, const RadianceCache& cache, const CacheLight& light,
                    const Ray& ray, const int* record, int nodes)
      : medium_(medium), cache_(cache), light_(light), ray_(ray), record_(record), nodes_(nodes) {}

  void medium_at(double t, MediumPoint& point) const { medium_.coefficients_at(ray_.at(t), point); }

  // The sun's optical depth per node at distance t along the ray (0 where
  // the lattice holds nothing): the marcher cuts cells where it climbs
  // steeply (emission_marcher.h).
  void sun_depths(double t, double* tau) {
    const LatticeCorners& at = corners_at(t);
    const bool inside = at.inside;
    const auto& slot = at.slot;
    const auto& w = at.w;
    const LatticeVolume& volume = cache_.volume();
    const auto stride = static_cast<std::size_t>(volume.stride());
    for (int j = 0; j < nodes_; ++j) {
      tau[j] = 0.0;
      if (!inside) continue;
      const float* records = volume.records(record_[j]);
      for (int c = 0; c < 8; ++c)
        if (slot[c] != NodeLattice::kNoSlot && w[c] != 0.0)
          tau[j] += w[c] * records[slot[c] * stride + record::kTauSun];
    }
  }

  // Delta-M's f at a point of asymmetry g (CacheLight::forward_fraction).
  double forward_fraction(double g) const { return light_.forward_fraction(cache_clamped_g(g)); }

  void add(const MarchCell&, int, double t, const double* sigma_s, const double* g,
           double* emissivity) {
    add_light(t, sigma_s, g, emissivity, nullptr, false);
  }
  // The same, and σs J_sun alone (the sun's light scattered once) into
  // sun[j].
  void add(const MarchCell&, int, double t, const double* sigma_s, const double* g,
           double* emissivity, double* sun) {
    add_light(t, sigma_s, g, emissivity, sun, false);
  }
  // σs J_sun alone added to emissivity[j] (a cut cell's pieces,
  // emission_marcher.h).
  void add_sun(const MarchCell&, int, double t, const double* sigma_s, const double* g,
               double* emissivity) {
    add_light(t, sigma_s, g, emissivity, nullptr, true);
  }

 private:
  // The light channels interpolated at distance t (only the sun's two with
  // `only_sun`), σs J added to emissivity[j] (σs J_sun with `only_sun`), and
  // σs J_sun into sun[j] where `sun` is given.
  void add_light(double t, const double* sigma_s, const double* g, double* emissivity, double* sun,
                 bool only_sun) {
    if (sun)
      for (int j = 0; j < nodes_; ++j) sun[j] = 0.0;
    bool scatters = false;
    for (int j = 0; j < nodes_; ++j) scatters = scatters || sigma_s[j] > 0.0;
    if (!scatters) return;
    const LatticeCorners& at = corners_at(t);
    if (!at.inside) return;
    const auto& slot = at.slot;
    const auto& w = at.w;
    const LatticeVolume& volume = cache_.volume();
    const auto stride = static_cast<std::size_t>(volume.stride());
    for (int j = 0; j < nodes_; ++j) {
      if (!(sigma_s[j] > 0.0)) continue;
      std::array<float, record::kSh + HgConvolution::readable(kMaxShDegree)> v{};
      const float* records = volume.records(record_[j]);
      if (only_sun)
        interpolate<record::kSunVisibility + 1>(records, stride, slot, w, v.data());
      else
        with_sh_count(cache_.sh_degree(), [&](auto count) {
          interpolate<record::kSh + decltype(count)::value>(records, stride, slot, w, v.data());
        });
      const double gj = cache_clamped_g(g[j]);
      const float* light = v.data() + record::kTauSun;
      double sun_j = 0.0;  // the sun's part of J (read where `sun` is given)
      const double j_in =
          only_sun ? light_.sun_scattered(j, gj, light)
                   : light_.in_scattered(j, gj, light_.forward_fraction(gj), light, sun_j);
      emissivity[j] += sigma_s[j] * j_in;
      if (sun) sun[j] = sigma_s[j] * sun_j;
    }
  }

  // Channels kTauSun … kEnd − 1 of the eight corners' records at `slot`,
  // weighted by `w`, into v. In float, as the lattice march interpolates
  // (lattice_view_march.h), and with the channels' count a constant, so that
  // their sums stay in SIMD registers across the corners (with the count
  // read at run time they went through memory at every corner: half a slab
  // validation's time at degree 6, docs/performance.md).
  template <int kEnd>
  static void interpolate(const float* records, std::size_t stride,
                          const std::array<std::size_t, 8>& slot, const std::array<double, 8>& w,
                          float* v) {
    constexpr int kCount = kEnd - record::kTauSun;
    std::array<float, kCount> sum{};
    for (int c = 0; c < 8; ++c) {
      if (slot[c] == NodeLattice::kNoSlot || w[c] == 0.0) continue;
      const float* r = records + slot[c] * stride + record::kTauSun;
      const float wc = static_cast<float>(w[c]);
      for (int i = 0; i < kCount; ++i) sum[i] += wc * r[i];
    }
    for (int i = 0; i < kCount; ++i) v[record::kTauSun + i] = sum[i];
  }

  // The lattice's corners of the point at distance t. The marcher reads the
  // light and the sun's depth at the same points (a cell's exit is the next
  // one's entry), so the last three lookups are kept: per cell it reads the
  // light at the middle and the exit, then the sun's depth at the entry (the
  // last cell's exit, three lookups back) and the exit, so two lookups a cell
  // where two kept ones left three; the same values (docs/performance.md).
  struct LatticeCorners {
    double t = -1.0;  // no lookup yet: distances along a ray are >= 0
    bool inside = false;
    std::array<std::size_t, 8> slot;
    std::array<double, 8> w;
  };
  const LatticeCorners& corners_at(double t) {
    for (const LatticeCorners& kept : kept_)
      if (kept.t == t) return kept;
    LatticeCorners& fresh = kept_[next_];
    next_ = (next_ + 1) % static_cast<int>(kept_.size());
    fresh.t = t;
    fresh.inside = cache_.lattice().corners(ray_.at(t), fresh.slot, fresh.w);
    return fresh;
  }

  const Medium& medium_;
  const RadianceCache& cache_;
  const CacheLight& light_;
  const Ray& ray_;
  const int* record_;
  int nodes_;
  std::array<LatticeCorners, 3> kept_;
  int next_ = 0;
};

}  // namespace

std::uint64_t march_cache_lattice(const Scene& scene, const RadianceCache& cache,
                                  const CameraRay& camera, const SpectralNodes& nodes,
                                  const int* record, int peak_channel, double* radiance,
                                  double* transmittance, double* attenuation) {
  const RayLight light(scene, cache, camera.ray, nodes, peak_channel);
  const int n = static_cast<int>(nodes.size());
  if (peak_channel < 0)
    return march_records(cache, record, n, camera, DeltaMCacheSource{light.planck(), light.light()},
                         radiance, transmittance, attenuation);
  // The harmonics and the peak hold the whole phase function: the
  // background is seen through the transmittance.
  const std::uint64_t cells =
      march_records(cache, record, n, camera, CacheSource{light.planck(), light.light()}, radiance,
                    transmittance, nullptr);
  for (int j = 0; j < n; ++j) attenuation[j] = transmittance[j];
  return cells;
}

std::uint64_t march_cache_medium(const Scene& scene, const RadianceCache& cache,
                                 const CameraRay& camera, const SpectralNodes& nodes,
                                 const int* record, double* radiance, double* transmittance,
                                 double* attenuation) {
  const RayLight light(scene, cache, camera.ray, nodes);
  CacheInScattering in(*scene.medium, cache, light.light(), camera.ray, record,
                       static_cast<int>(nodes.size()));
  EmissionMarcher<CacheInScattering> marcher(nodes, in, radiance, transmittance, attenuation);
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
