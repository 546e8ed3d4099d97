#include "obscura/render/background.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace obscura {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Whether the surface point sees the sun, and if so the optical depth to it
// per medium sample in scratch.tau_sun.
bool sunlit(const Scene& scene, const CameraRay& camera, BackgroundScratch& scratch) {
  const Vec3 to_sun = scene.sun.direction();
  if (dot(camera.hit.normal, to_sun) <= 0.0) return false;
  const Vec3 p = camera.ray.at(camera.hit.t) + camera.hit.normal * 1e-9;
  SurfaceHit other;
  if (intersect_surfaces(scene.surfaces, Ray{p, to_sun}, 1e-9, kInf, other)) return false;
  scratch.tau_sun.assign(scene.medium ? scene.medium->wavelengths_um().size() : 1, 0.0);
  if (scene.medium)
    scene.medium->add_optical_depth(Ray{p, to_sun}, 0.0, kInf, scratch.tau_sun.data());
  return true;
}

}  // namespace

void background_radiance(const Scene& scene, const CameraRay& camera, const SpectralNodes& nodes,
                         BackgroundScratch& scratch, double* out) {
  const Sun& sun = scene.sun;
  if (!camera.on_surface) {
    const bool sees_sun = scene.settings.camera_sees_sun && sun.enabled &&
                          dot(camera.ray.direction, sun.direction()) >= sun.cos_half_angle();
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      const double wl = nodes.nodes()[j].wavelength_um;
      out[j] = scene.sky.radiance(camera.ray.direction, wl) + (sees_sun ? sun.radiance(wl) : 0.0);
    }
    return;
  }
  const SurfaceMaterial& m = scene.surfaces[camera.hit.surface]->material();
  const bool lit = sun.enabled && sunlit(scene, camera, scratch);
  const double cos_sun = lit ? dot(camera.hit.normal, sun.direction()) : 0.0;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    const SpectralNode& nd = nodes.nodes()[j];
    const double emissivity = m.emissivity_at(nd.wavelength_um);
    out[j] =
        emissivity * nd.planck(m.temperature_k) +
        (1.0 - emissivity) * scene.sky.cosine_weighted_mean(camera.hit.normal, nd.wavelength_um);
    if (lit) {
      const double rho = m.reflectance_at(nd.wavelength_um);
      const double tau = scene.medium ? nd.lerp()(scratch.tau_sun.data()) : 0.0;
      out[j] +=
          rho * std::numbers::inv_pi * cos_sun * sun.irradiance(nd.wavelength_um) * std::exp(-tau);
    }
  }
}

}  // namespace obscura
