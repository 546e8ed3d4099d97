#include "obscura/render/path_tracer/volume_path_tracer.h"

#include <algorithm>
#include <limits>
#include <numbers>

#include "obscura/core/sampling.h"
#include "obscura/medium/phase_function.h"
#include "obscura/render/direct_lighting.h"

namespace obscura {
namespace {

// Power heuristic (Veach 1997, eq. 9.13, β = 2) for a sample of density `a`
// combined with one of density `b`.
double power_heuristic(double a, double b) {
  const double a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0 ? a2 / (a2 + b2) : 0.0;
}

// Next-event estimation of the sky at a vertex: one sky direction from the
// sky's density, weighted against the vertex's own direction sampling
// (`scatter_pdf`, also its throughput factor f: HG is sampled exactly and the
// Lambertian lobe by its cosine, so f = pdf for both). Returns f L T w / p_sky.
template <typename ScatterPdf>
double sky_next_event(const Scene& scene, const Vec3& position, const SpectralNode& node,
                      const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch,
                      ScatterPdf&& scatter_pdf) {
  double sky_pdf = 0.0;
  const Vec3 d = scene.sky.sample(rng.uniform(), rng.uniform(), &sky_pdf);
  const double f = scatter_pdf(d);
  if (!(sky_pdf > 0.0) || !(f > 0.0)) return 0.0;
  const double l = scene.sky.radiance(d, node.wavelength_um);
  if (l == 0.0) return 0.0;
  return f * l / sky_pdf * power_heuristic(sky_pdf, f) *
         transmittance_to_infinity(scene, position, d, lambda, rng, scratch);
}

}  // namespace

double trace_path(const Scene& scene, const Ray& ray, const SpectralNode& node, Rng& rng) {
  CameraRay camera;
  camera.ray = ray;
  camera.on_surface = intersect_surfaces(scene.surfaces, ray, 1e-9,
                                         std::numeric_limits<double>::infinity(), camera.hit);
  return trace_path(scene, camera, node, rng);
}

double trace_path(const Scene& scene, const CameraRay& camera, const SpectralNode& node, Rng& rng) {
  const PathTracerSettings& settings = scene.settings.path_tracer;
  const Medium* medium = scene.medium.get();
  const SpectralLerp lambda = node.lerp();
  MediumPoint point;
  Ray ray = camera.ray;
  double radiance = 0.0, beta = 1.0;
  using SkySampling = PathTracerSettings::SkySampling;
  const bool sky_lit = !scene.sky.is_black() &&
                       (settings.sky_next_event == SkySampling::kAlways ||
                        (settings.sky_next_event == SkySampling::kAuto && scene.sky.is_table()));
  double last_scatter_pdf = 0.0;  // density of the direction the path now follows
  for (int depth = 0; depth < settings.max_depth; ++depth) {
    // The camera ray's surface is known; every later segment looks for its own.
    SurfaceHit hit = camera.hit;
    const bool on_surface = depth == 0
                                ? camera.on_surface
                                : intersect_surfaces(scene.surfaces, ray, 1e-9,
                                                     std::numeric_limits<double>::infinity(), hit);
    const double t_surface = on_surface ? hit.t : std::numeric_limits<double>::infinity();
    const auto collision =
        medium ? sample_free_flight(*medium, ray, t_surface, lambda, rng, point) : std::nullopt;
    if (collision) {
      // `point` holds the coefficients at the accepted collision (sample_free_flight's last
      // evaluation).
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
                      transmittance_to_infinity(scene, position, to_sun, lambda, rng, point);
      }
      if (sky_lit)
        radiance +=
            beta * sky_next_event(scene, position, node, lambda, rng, point,
                                  [&](const Vec3& d) { return phase.eval(ray.direction, d); });
      double pdf = 0.0;
      ray = Ray{position, phase.sample(ray.direction, rng.uniform(), rng.uniform(), &pdf)};
      last_scatter_pdf = pdf;
    } else if (on_surface) {
      const SurfaceMaterial& m = scene.surfaces[hit.surface]->material();
      const double emissivity = m.emissivity_at(node.wavelength_um);
      radiance += beta * emissivity * node.planck(m.temperature_k);
      beta *= 1.0 - emissivity;
      if (beta == 0.0) break;
      const Vec3 position = ray.at(hit.t) + hit.normal * 1e-9;
      if (scene.sun.enabled) {
        // Lambertian reflection of the sun: β (ρ/π) cos θ_sun E_λ T, with ρ = 1 − ε.
        const Vec3 to_sun = sample_sun_direction(scene.sun, rng);
        const double cos_sun = dot(hit.normal, to_sun);
        if (cos_sun > 0.0)
          radiance += beta / std::numbers::pi * cos_sun * scene.sun.irradiance(node.wavelength_um) *
                      transmittance_to_infinity(scene, position, to_sun, lambda, rng, point);
      }
      if (sky_lit)
        radiance +=
            beta * sky_next_event(scene, position, node, lambda, rng, point, [&](const Vec3& d) {
              return std::max(0.0, dot(hit.normal, d)) * std::numbers::inv_pi;
            });
      ray = Ray{position,
                local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
      last_scatter_pdf = std::max(0.0, dot(hit.normal, ray.direction)) * std::numbers::inv_pi;
    } else {
      // After a bounce the sky was also sampled by next-event estimation: the
      // two estimators are combined with the power heuristic.
      const double sky = scene.sky.radiance(ray.direction, node.wavelength_um);
      radiance += beta * sky *
                  (depth == 0 || !sky_lit
                       ? 1.0
                       : power_heuristic(last_scatter_pdf, scene.sky.pdf(ray.direction)));
      // The sun's disc is seen directly only by camera rays: after a bounce,
      // next-event estimation already counts it.
      if (depth == 0 && scene.settings.camera_sees_sun && scene.sun.enabled &&
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
