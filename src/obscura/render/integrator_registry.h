#pragma once
// From a render method to its integrator: one factory per RenderMethod
// (scene/render_settings.h names them). A new method adds its enum value,
// its name there and its factory here.
#include <memory>

#include "obscura/core/process_group.h"
#include "obscura/render/integrator.h"

namespace obscura {

// `processes` share what a method prepares per frame (photon tracing); every
// process of the group must make the integrator together. `progress` hears
// how far that preparation is (the photon methods').
using IntegratorFactory = std::unique_ptr<Integrator> (*)(const Scene& scene,
                                                          const FrameSpectra& spectra,
                                                          const ProcessGroup& processes,
                                                          const PreparationProgress& progress);

// The factory of `method`; throws Error for a method without one (a bug).
IntegratorFactory integrator_factory(RenderMethod method);

// The integrator of scene.settings.method, prepared for the staged scene and
// `spectra` (photon tracing and the like happen here). The integrator keeps
// references to both: they must outlive it. The CPU's only: a scene whose
// settings ask for the GPU is an InternalError here (the gpu layer's
// make_frame_integrator, gpu/frame_integrator.h, makes either).
std::unique_ptr<Integrator> make_integrator(const Scene& scene, const FrameSpectra& spectra,
                                            const ProcessGroup& processes = single_process(),
                                            const PreparationProgress& progress = {});

}  // namespace obscura
