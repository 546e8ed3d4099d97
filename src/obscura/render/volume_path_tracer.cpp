#include "obscura/render/volume_path_tracer.h"

#include <algorithm>
#include <limits>
#include <numbers>

#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"

namespace obscura {
namespace {

// Transmittance from `origin` towards the sun along `direction`: zero when a
// surface is in the way, else ratio tracking through the medium.
double transmittance_to_sun(const Scene& scene, const Vec3& origin, const Vec3& direction,
                            const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  const Ray ray{origin, direction};
  SurfaceHit hit;
  if (intersect_surfaces(scene.surfaces, ray, 1e-9, std::numeric_limits<double>::infinity(), hit))
    return 0.0;
  if (!scene.medium) return 1.0;
  return estimate_transmittance(*scene.medium, ray, std::numeric_limits<double>::infinity(), lambda,
                                rng, scratch);
}

// A direction drawn uniformly over the sun's disc (pdf 1/Ω, so that the
// estimator of ∫ L_sun f dω is E_λ f(ω)).
Vec3 sample_sun_direction(const Sun& sun, Rng& rng) {
  return local_to_world(sun.direction(),
                        sample_uniform_cone(rng.uniform(), rng.uniform(), sun.cos_half_angle()));
}

}  // namespace

double trace_path(const Scene& scene, const Ray& camera_ray, const SpectralNode& node, Rng& rng,
                  const PathTracerSettings& settings) {
  const Medium* medium = scene.medium.get();
  const SpectralLerp lambda = node.lerp();
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
      if (scene.sun.enabled) {
        // Next-event estimation towards the sun: β Λ p(ω_i, ω_sun) E_λ T.
        const Vec3 to_sun = sample_sun_direction(scene.sun, rng);
        const double p = phase.eval(ray.direction, to_sun);
        if (p > 0.0)
          radiance += beta * p * scene.sun.irradiance(node.wavelength_um) *
                      transmittance_to_sun(scene, position, to_sun, lambda, rng, point);
      }
      ray = Ray{position, phase.sample(ray.direction, rng.uniform(), rng.uniform(), nullptr)};
    } else if (on_surface) {
      const SurfaceMaterial& m = scene.surfaces[hit.surface]->material();
      radiance += beta * m.emissivity * node.planck(m.temperature_k);
      beta *= 1.0 - m.emissivity;
      if (beta == 0.0) break;
      const Vec3 position = ray.at(hit.t) + hit.normal * 1e-9;
      if (scene.sun.enabled) {
        // Lambertian reflection of the sun: β (ρ/π) cos θ_sun E_λ T, with ρ = 1 − ε.
        const Vec3 to_sun = sample_sun_direction(scene.sun, rng);
        const double cos_sun = dot(hit.normal, to_sun);
        if (cos_sun > 0.0)
          radiance += beta / std::numbers::pi * cos_sun * scene.sun.irradiance(node.wavelength_um) *
                      transmittance_to_sun(scene, position, to_sun, lambda, rng, point);
      }
      ray = Ray{position, local_to_world(hit.normal,
                                         sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
    } else {
      radiance += beta * scene.sky.radiance(node.wavelength_um);
      // The sun's disc is seen directly only by camera rays: after a bounce,
      // next-event estimation already counts it.
      if (depth == 0 && scene.sun.enabled &&
          dot(ray.direction, scene.sun.direction()) >= scene.sun.cos_half_angle())
        radiance += beta * scene.sun.radiance(node.wavelength_um);
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
