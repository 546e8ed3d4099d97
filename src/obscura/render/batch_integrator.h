#pragma once
// Integrators that march a whole image's camera rays at once (the GPU's:
// gpu/gpu_integrator.h) rather than ray by ray. The renderer
// (render/renderer.h) makes every camera ray of a batch of rows and finds its
// first surface on the CPU, asks march_batch for the medium's radiance and
// transmittance along all of them, and then adds what lies behind the medium
// itself (render/background.h), as the emission–absorption and radiance-cache
// integrators do per ray: radiance + transmittance × background.
#include <cstdint>
#include <span>
#include <vector>

#include "obscura/render/background.h"
#include "obscura/render/integrator.h"

namespace obscura {

// The medium's part of `count` camera rays of one sensor. Outputs are the
// nodes of the sensor's bands in order (band 0's nodes, then band 1's, …);
// output k of ray i is at [k · count + i].
struct MediumBatch {
  std::size_t count = 0;
  // The radiance (W m⁻² sr⁻¹ µm⁻¹) the medium sends back along the ray up to
  // its end, the medium's transmittance to there, and what the radiance
  // behind it is seen through (the transmittance, or more where the
  // radiance cache takes delta-M: render/radiance_cache/cache_march.h).
  std::vector<double> radiance, transmittance, attenuation;
  // Per band: the medium cells its rays visited (RenderStats::segments; the
  // CPU's integrators count a ray's cells once per band).
  std::vector<std::uint64_t> band_cells;
};

class BatchIntegrator : public Integrator {
 public:
  // The medium's part of `rays` of sensor `sensor` into `out`. Called from
  // one thread at a time.
  virtual void march_batch(int sensor, std::span<const CameraRay> rays, MediumBatch& out) const = 0;

  // One ray: march_batch of it alone, plus the background (what the
  // renderer does for a whole image).
  void band_radiance(const CameraRay& ray, int sensor, int band, Rng& rng, RayWorkspace& workspace,
                     double* radiance, double* transmittance) const final;
  std::unique_ptr<RayWorkspace> make_workspace() const override;
  // What lies behind the medium along `ray` for band `band` (nodes `nodes`)
  // of sensor `sensor`, per node into `behind`: the background
  // (render/background.h) plus add_surface_light.
  void behind_radiance(const CameraRay& ray, int sensor, int band, const SpectralNodes& nodes,
                       BackgroundScratch& scratch, double* behind) const;

 protected:
  // Light a surface seen by `ray` receives that its own radiance
  // (render/background.h) leaves out, added to `behind`: the radiance
  // cache's cloud light on the ground.
  virtual void add_surface_light(const CameraRay& /*ray*/, int /*sensor*/, int /*band*/,
                                 double* /*behind*/) const {}

  // The staged scene and the nodes of every sensor's bands (spectra[sensor]
  // in the order of march_batch's outputs); both must outlive the integrator.
  BatchIntegrator(const Scene& scene, const FrameSpectra& spectra)
      : scene_(scene), spectra_(spectra) {}
  const Scene& scene() const { return scene_; }
  const FrameSpectra& spectra() const { return spectra_; }

 private:
  const Scene& scene_;
  const FrameSpectra& spectra_;
};

// The first output of each band of `bands` (a sensor's), and past the last.
std::vector<int> band_output_offsets(const std::vector<SpectralNodes>& bands);

}  // namespace obscura
