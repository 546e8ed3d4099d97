#include "obscura/render/integrator_registry.h"

#include <string>
#include <type_traits>

#include "obscura/core/check.h"
#include "obscura/render/emission_absorption/emission_absorption_integrator.h"
#include "obscura/render/path_tracer/path_tracer_integrator.h"
#include "obscura/render/photon_map/photon_map_integrator.h"
#include "obscura/render/radiance_cache/radiance_cache_integrator.h"

namespace obscura {
namespace {

template <typename T>
std::unique_ptr<Integrator> make(const Scene& scene, const FrameSpectra& spectra,
                                 const ProcessGroup& processes,
                                 const PreparationProgress& progress) {
  if constexpr (std::is_constructible_v<T, const Scene&, const FrameSpectra&, const ProcessGroup&,
                                        const PreparationProgress&>)
    return std::make_unique<T>(scene, spectra, processes, progress);
  else
    return std::make_unique<T>(scene, spectra);  // prepares nothing worth sharing or waiting for
}

struct Entry {
  RenderMethod method;
  IntegratorFactory factory;
};

constexpr Entry kRegistry[] = {
    {RenderMethod::kEmissionAbsorption, &make<EmissionAbsorptionIntegrator>},
    {RenderMethod::kPathTracer, &make<PathTracerIntegrator>},
    {RenderMethod::kPhotonMap, &make<PhotonMapIntegrator>},
    {RenderMethod::kRadianceCache, &make<RadianceCacheIntegrator>},
};

}  // namespace

IntegratorFactory integrator_factory(RenderMethod method) {
  for (const Entry& e : kRegistry)
    if (e.method == method) return e.factory;
  throw Error("render: no integrator registered for method '" +
              std::string(render_method_name(method)) + "'");
}

std::unique_ptr<Integrator> make_integrator(const Scene& scene, const FrameSpectra& spectra,
                                            const ProcessGroup& processes,
                                            const PreparationProgress& progress) {
  // Never the CPU in the GPU's stead: the GPU's integrator is the gpu layer's.
  OBSCURA_CHECK_MSG(scene.settings.device == RenderDevice::kCpu,
                    "\"device\": \"gpu\" takes make_frame_integrator (gpu/frame_integrator.h)");
  return integrator_factory(scene.settings.method)(scene, spectra, processes, progress);
}

}  // namespace obscura
