#pragma once
// "method": "photonmap", pass 2 of volume photon mapping: ray marching from
// the sensor with the photon maps of pass 1 (photon_tracing.h) giving the
// in-scattered radiance (docs/physics.md, "Volume photon mapping").
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

#include "obscura/core/process_group.h"
#include "obscura/core/rng.h"
#include "obscura/medium/phase_function.h"
#include "obscura/render/integrator.h"
#include "obscura/render/photon_map/photon_map.h"
#include "obscura/render/photon_map/photon_tracing.h"

namespace obscura {

// Photon maps for every spectral node of every band of every sensor, traced
// once per staged scene when the integrator is made; then radiance along rays.
class PhotonMapIntegrator final : public Integrator {
 public:
  // `processes`: who shares the photon tracing (core/process_group.h);
  // `progress`: how far it is.
  PhotonMapIntegrator(const Scene& scene, const FrameSpectra& spectra,
                      const ProcessGroup& processes = single_process(),
                      const PreparationProgress& progress = {});

  RenderMethod method() const override { return RenderMethod::kPhotonMap; }
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  void begin_ray(const CameraRay& ray, RayWorkspace& workspace) const override;
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const override;
  PreparationStats preparation(int sensor) const override { return preparation_[sensor]; }

  // Stored photons over all maps and the bytes they use.
  std::size_t photon_count() const;
  std::size_t memory_bytes() const;
  const TracedPhotons& traced(int sensor, int band, int node) const {
    return maps_[sensor][band][node].traced;
  }
  const PhotonMap& map(int sensor, int band, int node) const {
    return *maps_[sensor][band][node].map;
  }

 private:
  struct NodeMap {
    TracedPhotons traced;  // photons moved into `map`; powers and counts kept
    std::unique_ptr<PhotonMap> map;
    double sun_irradiance = 0.0;  // W m⁻² µm⁻¹ at the node, 0 without a sun
  };
  struct Workspace;
  using BandMaps = std::vector<NodeMap>;  // one per spectral node of a band

  // Spectral radiance along `camera` at every node of `nodes`; `depth` counts
  // surface bounces of final gathering (0 for camera rays).
  void radiance_along(const CameraRay& camera, const SpectralNodes& nodes, const BandMaps& maps,
                      Rng& rng, Workspace& ws, double* out, int depth) const;
  // ∫ e^{−τ} J dt along the camera ray, per node, added to scattered[node].
  void march_in_scattering(const CameraRay& camera, const SpectralNodes& nodes,
                           const BandMaps& maps, Rng& rng, Workspace& ws, double* scattered) const;
  // σs times the single scattering of the sun and the environment at x
  // towards −direction (the hybrid form's shadow rays).
  double single_scattering(const Vec3& x, const Vec3& direction, const SpectralNode& node,
                           const NodeMap& map, double sigma_s, const HenyeyGreenstein& phase,
                           Rng& rng, Workspace& ws) const;
  // σs times the in-scattered radiance the k nearest photons give at x.
  double photon_estimate(const Vec3& x, const Vec3& toward_camera, const SpectralLerp& lambda,
                         const PhotonMap& map, double sigma_s, double sigma_t,
                         const HenyeyGreenstein& phase, Workspace& ws) const;
  // What the camera ray sees behind the medium, per node.
  void background(const CameraRay& camera, const SpectralNodes& nodes, const BandMaps& maps,
                  Rng& rng, Workspace& ws, int depth, double* out) const;

  const Scene& scene_;
  const FrameSpectra& spectra_;
  PhotonMapSettings settings_;
  std::vector<std::vector<BandMaps>> maps_;    // [sensor][band][node]
  std::vector<PreparationStats> preparation_;  // per sensor
};

}  // namespace obscura
