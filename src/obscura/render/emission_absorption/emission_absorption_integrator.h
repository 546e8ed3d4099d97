#pragma once
// "method": "emission-absorption": the medium's emission and transmittance
// integrated exactly along the camera ray (emission_absorption.h), in front
// of a background that needs no light transport: the sky, or an opaque
// Lambertian surface that emits ε B(T) and reflects (1 − ε) of the sky it
// faces (its cosine-weighted mean, Sky::cosine_weighted_mean). Clouds' light
// on surfaces, scattering and the sun are the Monte Carlo methods' job; the
// scene loader refuses a sun with this method. Deterministic: no random
// numbers are drawn.
#include "obscura/render/integrator.h"

namespace obscura {

class EmissionAbsorptionIntegrator final : public Integrator {
 public:
  EmissionAbsorptionIntegrator(const Scene& scene, const FrameSpectra& spectra)
      : scene_(scene), spectra_(spectra) {}

  RenderMethod method() const override { return RenderMethod::kEmissionAbsorption; }
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const override;

 private:
  const Scene& scene_;
  const FrameSpectra& spectra_;
};

}  // namespace obscura
