#include "obscura/render/path_tracer/path_tracer_integrator.h"

#include "obscura/render/line_of_sight.h"
#include "obscura/render/path_tracer/volume_path_tracer.h"

namespace obscura {
namespace {

struct PathTracerWorkspace final : RayWorkspace {
  LineOfSight line_of_sight;
};

}  // namespace

std::unique_ptr<RayWorkspace> PathTracerIntegrator::make_workspace() const {
  return std::make_unique<PathTracerWorkspace>();
}

void PathTracerIntegrator::begin_ray(const CameraRay& camera, RayWorkspace& workspace) const {
  static_cast<PathTracerWorkspace&>(workspace).line_of_sight.compute(scene_.medium.get(), camera);
}

void PathTracerIntegrator::band_radiance(const CameraRay& camera, int sensor, int band, Rng& rng,
                                         RayWorkspace& workspace, double* radiance,
                                         double* transmittance) const {
  const auto& ws = static_cast<const PathTracerWorkspace&>(workspace);
  const SpectralNodes& nodes = spectra_[sensor][band];
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const SpectralNode& nd = nodes.nodes()[i];
    radiance[i] = trace_path(scene_, camera, nd, rng);
    transmittance[i] = ws.line_of_sight.transmittance(nd);
  }
}

}  // namespace obscura
