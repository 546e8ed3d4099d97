#pragma once
// The integrator of a frame on the device its settings name (docs/gpu.md):
// "device": "cpu", the method's own integrator (render/integrator_registry.h);
// "device": "gpu", the lattice march on the GPU (lattice_batch_integrator.h),
// or an Error saying why the GPU cannot run. What render_frame
// (sequence/sequence_runner.h) and the Python module make.
#include <memory>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"

namespace obscura {

std::unique_ptr<Integrator> make_frame_integrator(const Scene& scene, const FrameSpectra& spectra,
                                                  const ProcessGroup& processes = single_process(),
                                                  const PreparationProgress& progress = {});

}  // namespace obscura
