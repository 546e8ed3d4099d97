#include "obscura/render/volume_path_tracer.h"

#include <algorithm>
#include <limits>

#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"

namespace obscura {

double trace_path(const Scene& scene, const Ray& camera_ray, const SpectralNode& node, Rng& rng,
                  const PathTracerSettings& settings) {
  const Medium* medium = scene.medium.get();
  const SpectralLerp lambda =
      medium ? SpectralLerp{node.sample0, node.sample1, node.frac} : SpectralLerp{};
  MediumPoint point;
  Ray ray = camera_ray;
  double radiance = 0.0, beta = 1.0;
  for (int depth = 0; depth < settings.max_depth; ++depth) {
    SurfaceHit hit;
    const bool on_surface = intersect_surfaces(scene.surfaces, ray, 1e-9,
                                               std::numeric_limits<double>::infinity(), hit);
    const double t_surface = on_surface ? hit.t : std::numeric_limits<double>::infinity();
    const auto collision =
        medium ? sample_free_flight(*medium, ray, t_surface, lambda, rng, point) : std::nullopt;
    if (collision) {
      // `point` holds the coefficients at the accepted collision (sample_free_flight's last evaluation).
      const double sigma_a = lambda(point.sigma_a.data());
      const double sigma_s = lambda(point.sigma_s.data());
      const double sigma_t = sigma_a + sigma_s;
      radiance += beta * (sigma_a / sigma_t) * node.planck(point.temperature_k);
      beta *= sigma_s / sigma_t;
      if (beta == 0.0) break;
      const HenyeyGreenstein phase(std::clamp(lambda(point.g.data()), -0.999999, 0.999999));
      const Vec3 position = ray.at(*collision);
      ray = Ray{position, phase.sample(ray.direction, rng.uniform(), rng.uniform(), nullptr)};
    } else if (on_surface) {
      const SurfaceMaterial& m = scene.surfaces[hit.surface]->material();
      radiance += beta * m.emissivity * node.planck(m.temperature_k);
      beta *= 1.0 - m.emissivity;
      if (beta == 0.0) break;
      const Vec3 position = ray.at(hit.t) + hit.normal * 1e-9;
      ray = Ray{position, local_to_world(hit.normal,
                                         sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
    } else {
      radiance += beta * scene.sky.radiance(node.wavelength_um);
      break;
    }
    if (depth + 1 >= settings.russian_roulette_depth) {
      // Survival probability β, capped at 0.99 so that paths in lossless
      // enclosures still end; the cap costs little variance (1 % per bounce).
      const double survive = std::min(0.99, beta);
      if (rng.uniform() >= survive) break;
      beta /= survive;
    }
  }
  return radiance;
}

}  // namespace obscura
