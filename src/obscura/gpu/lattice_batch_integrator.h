#pragma once
// "device": "gpu" (docs/gpu.md): emission–absorption or the radiance cache
// with the camera march of every image on a LatticeExecutor (lattice_executor.h),
// a CUDA device in a render, the CPU's threads in the host-side tests. Per
// frame, on the CPU: the cloud's records (render/lattice/lattice_volume.h)
// and, for the radiance cache, its photon tracing, splatting and the sun's
// visibility past surfaces (Embree); then on the executor: the sun's optical
// depths (sun_depth_job.h) and, per sensor image, the march of all its camera
// rays (march_job.h). The renderer makes the camera rays, finds their first
// surfaces and adds the background on the CPU (render/batch_integrator.h).
//
// Only a cloud that is one voxel grid, which the lattice's records reproduce
// exactly (LatticeVolume::aligned_grid), is marched: anything else is an
// InputError naming render/device, not a silent CPU render.
#include <memory>
#include <vector>

#include "obscura/core/process_group.h"
#include "obscura/gpu/lattice_executor.h"
#include "obscura/render/batch_integrator.h"
#include "obscura/render/lattice/lattice_volume.h"
#include "obscura/render/radiance_cache/radiance_cache.h"

namespace obscura {

class LatticeBatchIntegrator final : public BatchIntegrator {
 public:
  // For the staged scene's settings.method (emission-absorption or
  // radiance-cache) and `spectra`, on `executor`.
  LatticeBatchIntegrator(const Scene& scene, const FrameSpectra& spectra,
                         std::unique_ptr<LatticeExecutor> executor,
                         const ProcessGroup& processes = single_process(),
                         const PreparationProgress& progress = {});
  ~LatticeBatchIntegrator() override;

  RenderMethod method() const override { return scene().settings.method; }
  void march_batch(int sensor, std::span<const CameraRay> rays, MediumBatch& out) const override;
  PreparationStats preparation(int sensor) const override;

  const LatticeExecutor& executor() const { return *executor_; }
  // The radiance cache (null for emission–absorption and without a medium).
  const RadianceCache* cache() const { return cache_.get(); }
  // The records the executor holds a copy of (null without a medium).
  const LatticeVolume* volume() const;

 private:
  void add_surface_light(const CameraRay& ray, int sensor, int band, double* behind) const override;

  DistinctNodes distinct_;
  GridRecords grid_;                      // emission–absorption's records
  std::unique_ptr<RadianceCache> cache_;  // the radiance cache's
  std::unique_ptr<LatticeExecutor> executor_;
  std::vector<MarchRequest> requests_;  // per sensor
  PreparationStats preparation_;
};

}  // namespace obscura
