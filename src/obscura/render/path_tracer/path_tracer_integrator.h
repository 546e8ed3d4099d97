#pragma once
// "method": "path-tracer": one path per spectral node and sample
// (volume_path_tracer.h), started from the camera ray's known first surface,
// beside the exact line-of-sight transmittance.
#include "obscura/render/integrator.h"

namespace obscura {

class PathTracerIntegrator final : public Integrator {
 public:
  PathTracerIntegrator(const Scene& scene, const FrameSpectra& spectra)
      : scene_(scene), spectra_(spectra) {}

  RenderMethod method() const override { return RenderMethod::kPathTracer; }
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  void begin_ray(const CameraRay& ray, RayWorkspace& workspace) const override;
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const override;

 private:
  const Scene& scene_;
  const FrameSpectra& spectra_;
};

}  // namespace obscura
