#include "obscura/render/direct_lighting.h"

#include <limits>
#include <numbers>

#include "obscura/core/sampling.h"

namespace obscura {

double transmittance_to_infinity(const Scene& scene, const Vec3& origin, const Vec3& direction,
                                 const SpectralLerp& lambda, Rng& rng, MediumPoint& scratch) {
  const Ray ray{origin, direction};
  SurfaceHit hit;
  if (intersect_surfaces(scene.surfaces, ray, 1e-9, std::numeric_limits<double>::infinity(), hit))
    return 0.0;
  if (!scene.medium) return 1.0;
  return estimate_transmittance(*scene.medium, ray, std::numeric_limits<double>::infinity(), lambda,
                                rng, scratch);
}

Vec3 sample_sun_direction(const Sun& sun, Rng& rng) {
  return local_to_world(sun.direction(),
                        sample_uniform_cone(rng.uniform(), rng.uniform(), sun.cos_half_angle()));
}

double surface_radiance(const Scene& scene, const SurfaceHit& hit, const Vec3& position,
                        const SpectralNode& node, Rng& rng, MediumPoint& scratch) {
  const SurfaceMaterial& m = scene.surfaces[hit.surface]->material();
  const double emissivity = m.emissivity_at(node.wavelength_um);
  double l = emissivity * node.planck(m.temperature_k);
  const double reflectance = 1.0 - emissivity;
  if (reflectance <= 0.0) return l;
  const SpectralLerp lambda = node.lerp();
  const Vec3 p = position + hit.normal * 1e-9;
  if (scene.sun.enabled) {
    const Vec3 to_sun = sample_sun_direction(scene.sun, rng);
    const double cos_sun = dot(hit.normal, to_sun);
    if (cos_sun > 0.0)
      l += reflectance * std::numbers::inv_pi * cos_sun * scene.sun.irradiance(node.wavelength_um) *
           transmittance_to_infinity(scene, p, to_sun, lambda, rng, scratch);
  }
  // (1/π) ∫ L cos dω by one cosine-distributed direction: the estimate is L·T.
  const Vec3 d = local_to_world(hit.normal, sample_cosine_hemisphere(rng.uniform(), rng.uniform()));
  SurfaceHit other;
  const Ray ray{p, d};
  if (intersect_surfaces(scene.surfaces, ray, 1e-9, std::numeric_limits<double>::infinity(),
                         other)) {
    const SurfaceMaterial& o = scene.surfaces[other.surface]->material();
    const double t = scene.medium
                         ? estimate_transmittance(*scene.medium, ray, other.t, lambda, rng, scratch)
                         : 1.0;
    l += reflectance * o.emissivity_at(node.wavelength_um) * node.planck(o.temperature_k) * t;
  } else {
    const double sky = scene.sky.radiance(d, node.wavelength_um);
    if (sky > 0.0)
      l += reflectance * sky *
           (scene.medium ? estimate_transmittance(*scene.medium, ray,
                                                  std::numeric_limits<double>::infinity(), lambda,
                                                  rng, scratch)
                         : 1.0);
  }
  return l;
}

double environment_radiance(const Scene& scene, const Vec3& origin, const Vec3& toward,
                            const SpectralNode& node, Rng& rng, MediumPoint& scratch) {
  SurfaceHit hit;
  const Ray ray{origin, toward};
  if (intersect_surfaces(scene.surfaces, ray, 1e-9, std::numeric_limits<double>::infinity(), hit))
    return surface_radiance(scene, hit, ray.at(hit.t), node, rng, scratch);
  return scene.sky.radiance(toward, node.wavelength_um);
}

}  // namespace obscura
