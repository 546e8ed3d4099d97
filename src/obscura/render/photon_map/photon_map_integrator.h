#pragma once
// Pass 2 of volume photon mapping: ray marching from the sensor with the
// photon maps of pass 1 (photon/photon_tracing.h) giving the in-scattered
// radiance (docs/physics.md, "Volume photon mapping").
//
// Along a camera ray up to the first surface:
//  * emission and transmittance exactly, by the emission–absorption
//    integrator;
//  * the in-scattering source J(t) = σs ∫ p L_in dω is integrated by jittered
//    ray marching: segments of length min(step_m, 0.5/σ̄) within each majorant
//    piece (σ̄ the local extinction bound), one uniformly placed sample per
//    segment weighted by the segment length and by the exact transmittance
//    e^{−τ(0,t)} to it — an unbiased quadrature of ∫ e^{−τ} J dt given
//    unbiased J;
//  * J at a sample: in the hybrid form, single scattering of the sun (one
//    direction over its disc, ratio-tracked shadow ray) and of the environment
//    (one HG-sampled direction, its transmittance and the sky or surface
//    radiance it finds), plus multiple scattering from the k nearest photons,
//    Σ p(ω_p, ω) ΔΦ_p / ((4/3) π r³) with r the distance to the k-th photon
//    (or the maximum radius); in the pure form (the paper's), photons only;
//  * the background, times the transmittance: the sky (and the sun's disc for
//    camera rays), or a surface's emission ε B(T), the sun it reflects (one
//    direction over the disc, ratio-tracked) and, by final gathering, ρ times
//    the radiance this integrator finds along one cosine-distributed ray from
//    it (continued with probability ρ = 1 − ε): light the cloud scatters or
//    emits onto the ground, other surfaces and the sky.
#include <memory>
#include <vector>

#include "obscura/core/rng.h"
#include "obscura/render/photon_map/photon_map.h"
#include "obscura/render/photon_map/photon_tracing.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura {

// Photon maps for every spectral node of every band of a sensor, traced once
// per staged scene; then radiance along rays.
class PhotonMapIntegrator {
 public:
  PhotonMapIntegrator(const Scene& scene, const std::vector<SpectralNodes>& band_nodes,
                      const PhotonMapSettings& settings, std::uint64_t seed, int threads);

  // Spectral radiance (W m⁻² sr⁻¹ µm⁻¹) arriving along −ray.direction at
  // ray.origin for every node of band `band`, written to out[node].
  // `depth` counts surface bounces of final gathering (0 for camera rays).
  void radiance(const Ray& ray, int band, Rng& rng, double* out, int depth = 0) const;

  const PhotonMapSettings& settings() const { return settings_; }
  // Stored photons over all maps, bytes they use, and what pass 1 launched.
  std::size_t photon_count() const;
  std::size_t memory_bytes() const;
  // Wall time of pass 1, s: tracing the photons, and building the kd-trees.
  double tracing_seconds() const { return tracing_seconds_; }
  double build_seconds() const { return build_seconds_; }
  const TracedPhotons& traced(int band, int node) const { return maps_[band][node].traced; }
  const PhotonMap& map(int band, int node) const { return *maps_[band][node].map; }

 private:
  struct NodeMap {
    TracedPhotons traced;  // photons moved into `map`; powers and counts kept
    std::unique_ptr<PhotonMap> map;
    double sun_irradiance =
        0.0;  // W m⁻² µm⁻¹ at the node, 0 without a sun (used at every marching step)
  };
  const Scene& scene_;
  const std::vector<SpectralNodes>& band_nodes_;
  PhotonMapSettings settings_;
  std::vector<std::vector<NodeMap>> maps_;
  double tracing_seconds_ = 0.0, build_seconds_ = 0.0;
};

}  // namespace obscura
