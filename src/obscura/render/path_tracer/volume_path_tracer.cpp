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

// Where a path is: the ray it follows, the radiance scored so far, its
// throughput β, and the density of the direction it follows (for MIS).
struct PathState {
  Ray ray;
  double radiance = 0.0, beta = 1.0;
  double last_scatter_pdf = 0.0;
};

// What every vertex of one path shares.
struct PathContext {
  const Scene& scene;
  const SpectralNode& node;
  SpectralLerp lambda;
  bool sky_lit;  // the sky is sampled directly at vertices
};

// A real collision at distance t; `point` holds the coefficients there
// (sample_free_flight's last evaluation). Scores the emission, the sun and
// the sky by next-event estimation, and scatters. False: the path ends.
bool collide(const PathContext& c, double t, MediumPoint& point, Rng& rng, PathState& s) {
  const double sigma_a = c.lambda(point.sigma_a.data());
  const double sigma_s = c.lambda(point.sigma_s.data());
  const double sigma_t = sigma_a + sigma_s;
  s.radiance += s.beta * (sigma_a / sigma_t) * c.node.planck(point.temperature_k);
  s.beta *= sigma_s / sigma_t;
  if (s.beta == 0.0) return false;
  const HenyeyGreenstein phase(std::clamp(c.lambda(point.g.data()), -0.999999, 0.999999));
  const Vec3 position = s.ray.at(t);
  const Vec3 incoming = s.ray.direction;
  if (c.scene.sun.enabled) {
    // Next-event estimation towards the sun: β Λ p(ω_i, ω_sun) E_λ T.
    const Vec3 to_sun = sample_sun_direction(c.scene.sun, rng);
    const double p = phase.eval(incoming, to_sun);
    if (p > 0.0)
      s.radiance += s.beta * p * c.scene.sun.irradiance(c.node.wavelength_um) *
                    transmittance_to_infinity(c.scene, position, to_sun, c.lambda, rng, point);
  }
  if (c.sky_lit)
    s.radiance += s.beta * sky_next_event(c.scene, position, c.node, c.lambda, rng, point,
                                          [&](const Vec3& d) { return phase.eval(incoming, d); });
  double pdf = 0.0;
  s.ray = Ray{position, phase.sample(incoming, rng.uniform(), rng.uniform(), &pdf)};
  s.last_scatter_pdf = pdf;
  return true;
}

// The path meets a surface: its emission ε B(T), the sun and the sky it
// reflects by next-event estimation, and a cosine-distributed bounce with
// weight ρ = 1 − ε. False: the path ends.
bool reflect(const PathContext& c, const SurfaceHit& hit, MediumPoint& scratch, Rng& rng,
             PathState& s) {
  const SurfaceMaterial& m = c.scene.surfaces[hit.surface]->material();
  const double emissivity = m.emissivity_at(c.node.wavelength_um);
  s.radiance += s.beta * emissivity * c.node.planck(m.temperature_k);
  s.beta *= 1.0 - emissivity;
  if (s.beta == 0.0) return false;
  const Vec3 position = s.ray.at(hit.t) + hit.normal * 1e-9;
  if (c.scene.sun.enabled) {
    // Lambertian reflection of the sun: β (ρ/π) cos θ_sun E_λ T, with ρ = 1 − ε.
    const Vec3 to_sun = sample_sun_direction(c.scene.sun, rng);
    const double cos_sun = dot(hit.normal, to_sun);
    if (cos_sun > 0.0)
      s.radiance += s.beta / std::numbers::pi * cos_sun *
                    c.scene.sun.irradiance(c.node.wavelength_um) *
                    transmittance_to_infinity(c.scene, position, to_sun, c.lambda, rng, scratch);
  }
  if (c.sky_lit)
    s.radiance +=
        s.beta *
        sky_next_event(c.scene, position, c.node, c.lambda, rng, scratch, [&](const Vec3& d) {
          return std::max(0.0, dot(hit.normal, d)) * std::numbers::inv_pi;
        });
  s.ray = Ray{position,
              local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()))};
  s.last_scatter_pdf = std::max(0.0, dot(hit.normal, s.ray.direction)) * std::numbers::inv_pi;
  return true;
}

// The path leaves the scene after `depth` bounces: the sky it finds (after a
// bounce combined by the power heuristic with the sky's own next-event
// estimate) and, for a camera ray only, the sun's disc.
void escape(const PathContext& c, int depth, PathState& s) {
  const Scene& scene = c.scene;
  const double sky = scene.sky.radiance(s.ray.direction, c.node.wavelength_um);
  s.radiance += s.beta * sky *
                (depth == 0 || !c.sky_lit
                     ? 1.0
                     : power_heuristic(s.last_scatter_pdf, scene.sky.pdf(s.ray.direction)));
  // After a bounce, next-event estimation already counts the sun.
  if (depth == 0 && scene.settings.camera_sees_sun && scene.sun.enabled &&
      dot(s.ray.direction, scene.sun.direction()) >= scene.sun.cos_half_angle())
    s.radiance += s.beta * scene.sun.radiance(c.node.wavelength_um);
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
  using SkySampling = PathTracerSettings::SkySampling;
  const PathContext c{scene, node, node.lerp(),
                      !scene.sky.is_black() && (settings.sky_next_event == SkySampling::kAlways ||
                                                (settings.sky_next_event == SkySampling::kAuto &&
                                                 scene.sky.is_table()))};
  MediumPoint point;
  PathState s;
  s.ray = camera.ray;
  for (int depth = 0; depth < settings.max_depth; ++depth) {
    // The camera ray's surface is known; every later segment looks for its own.
    SurfaceHit hit = camera.hit;
    const bool on_surface = depth == 0
                                ? camera.on_surface
                                : intersect_surfaces(scene.surfaces, s.ray, 1e-9,
                                                     std::numeric_limits<double>::infinity(), hit);
    const double t_surface = on_surface ? hit.t : std::numeric_limits<double>::infinity();
    const auto collision =
        medium ? sample_free_flight(*medium, s.ray, t_surface, c.lambda, rng, point) : std::nullopt;
    if (collision) {
      if (!collide(c, *collision, point, rng, s)) break;
    } else if (on_surface) {
      if (!reflect(c, hit, point, rng, s)) break;
    } else {
      escape(c, depth, s);
      break;
    }
    if (depth + 1 >= settings.russian_roulette_depth) {
      // Survival probability β, capped at 0.99 so that paths in lossless
      // enclosures still end; the cap costs little variance (1 % per bounce).
      const double survive = std::min(0.99, s.beta);
      if (rng.uniform() >= survive) break;
      s.beta /= survive;
    }
  }
  return s.radiance;
}

}  // namespace obscura
