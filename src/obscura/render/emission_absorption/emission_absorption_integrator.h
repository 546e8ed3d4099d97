#pragma once
// "method": "emission-absorption": the medium's emission and transmittance
// integrated exactly along the camera ray (emission_absorption.h), in front
// of a background that needs no light transport: the sky, or an opaque
// Lambertian surface that emits ε B(T) and reflects (1 − ε) of the sky it
// faces (its cosine-weighted mean, Sky::cosine_weighted_mean). Clouds' light
// on surfaces, scattering and the sun are the Monte Carlo methods' job; the
// scene loader refuses a sun with this method. Deterministic: no random
// numbers are drawn.
//
// A cloud that is one voxel grid is marched, with the cell quadrature, over
// per-frame records of its values at the frame's wavelengths
// (render/lattice/lattice_march.h): the same cells, points and quadrature as
// the medium's own march, read from one interleaved record per corner.
// Other media, and "emission_quadrature": "adaptive", take the medium's march.
#include <memory>

#include "obscura/render/integrator.h"
#include "obscura/render/lattice/lattice_volume.h"

namespace obscura {

class EmissionAbsorptionIntegrator final : public Integrator {
 public:
  EmissionAbsorptionIntegrator(const Scene& scene, const FrameSpectra& spectra);
  ~EmissionAbsorptionIntegrator() override;

  RenderMethod method() const override { return RenderMethod::kEmissionAbsorption; }
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const override;
  PreparationStats preparation(int sensor) const override;

  // Whether the rays march over the lattice records.
  bool marches_lattice() const { return volume_ != nullptr; }

 private:
  const Scene& scene_;
  const FrameSpectra& spectra_;
  DistinctNodes distinct_;
  std::unique_ptr<NodeLattice> lattice_;
  std::unique_ptr<LatticeVolume> volume_;  // null: the medium's own march
  PreparationStats preparation_;
};

}  // namespace obscura
