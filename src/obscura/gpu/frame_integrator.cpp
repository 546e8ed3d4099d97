#include "obscura/gpu/frame_integrator.h"

#include "obscura/gpu/gpu_device.h"
#include "obscura/gpu/lattice_batch_integrator.h"
#include "obscura/render/integrator_registry.h"

namespace obscura {

std::unique_ptr<Integrator> make_frame_integrator(const Scene& scene, const FrameSpectra& spectra,
                                                  const ProcessGroup& processes,
                                                  const PreparationProgress& progress) {
  if (scene.settings.device == RenderDevice::kCpu)
    return make_integrator(scene, spectra, processes, progress);
  return std::make_unique<LatticeBatchIntegrator>(scene, spectra, make_gpu_executor(), processes,
                                                  progress);
}

}  // namespace obscura
