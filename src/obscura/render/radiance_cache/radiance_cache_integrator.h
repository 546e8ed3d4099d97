#pragma once
// "method": "radiance-cache": per frame, one RadianceCache for every distinct
// spectral node of every sensor's bands; then each camera ray is a
// deterministic march (cache_march.h) that integrates the emission and the
// cached scattered light together with the exact transmittance of every cell:
// over the cache's records alone when its lattice is laid on the cloud's own
// voxel grid, else over the medium's cells. Behind the medium:
// render/background.h, as for emission–absorption, so that a frame without a
// cloud is the emission–absorption image exactly.
#include <memory>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"
#include "obscura/render/radiance_cache/radiance_cache.h"

namespace obscura {

class RadianceCacheIntegrator final : public Integrator {
 public:
  // `processes`: who shares the photon tracing (core/process_group.h);
  // `progress`: how far it is.
  RadianceCacheIntegrator(const Scene& scene, const FrameSpectra& spectra,
                          const ProcessGroup& processes = single_process(),
                          const PreparationProgress& progress = {});

  RenderMethod method() const override { return RenderMethod::kRadianceCache; }
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const override;
  // The frame's cache, reported with its first sensor.
  PreparationStats preparation(int sensor) const override;

  const RadianceCache* cache() const { return cache_.get(); }

 private:
  const Scene& scene_;
  const FrameSpectra& spectra_;
  DistinctNodes distinct_;                // the cache's nodes
  std::unique_ptr<RadianceCache> cache_;  // null without a medium
  PreparationStats preparation_;
};

}  // namespace obscura
