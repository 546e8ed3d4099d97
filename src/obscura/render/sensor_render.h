#pragma once
// The renderer's own parts, shared by render/renderer.cpp and
// render/adaptive_samples.cpp (not an interface for other layers:
// render/renderer.h is): one sensor's render as its rows share it — the air
// between the sensor and the scene, a pixel's running band sums, one camera
// sample through the integrator, a pixel's stratified samples, storing a
// pixel — and the band sums of many camera samples through a batched
// integrator.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <vector>

#include "obscura/core/rng.h"
#include "obscura/film/sensor_image.h"
#include "obscura/render/batch_integrator.h"
#include "obscura/render/integrator.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/scene/scene.h"

namespace obscura::render_detail {

using NodeArray = std::array<double, kMaxSpectralNodes>;

// Standard error of the mean of n independent samples with sum s and sum of squares s2.
double standard_error(double s, double s2, int n);

// The atmosphere between the sensor and the scene, per band
// (scene/atmosphere.h): its extinction coefficient (1/m) and its own band
// radiance, (1 − τ) of which joins every ray.
struct AirPath {
  std::vector<double> extinction_per_m, band_radiance;

  AirPath(const Scene& scene, const Sensor& sensor, const std::vector<SpectralNodes>& bands);
};

// How far a camera ray runs through the air before it meets the scene: to
// the surface, else through the clouds' box (0 when it meets neither).
double air_path_m(const Scene& scene, const CameraRay& camera);

// Running sums of one pixel's samples, per band.
struct PixelSums {
  std::vector<double> l, l2, t;
  explicit PixelSums(std::size_t bands) : l(bands), l2(bands), t(bands) {}
  void clear() {
    std::fill(l.begin(), l.end(), 0.0);
    std::fill(l2.begin(), l2.end(), 0.0);
    std::fill(t.begin(), t.end(), 0.0);
  }
  // Adds one sample's band radiances l[b] and transmittances t[b].
  void add(const double* sample_l, const double* sample_t) {
    for (std::size_t b = 0; b < l.size(); ++b) {
      l[b] += sample_l[b];
      l2[b] += sample_l[b] * sample_l[b];
      t[b] += sample_t[b];
    }
  }
};

// Everything one sensor's render shares between its rows.
struct SensorRender {
  const Scene& scene;
  const Sensor& sensor;
  const Integrator& integrator;
  const std::vector<SpectralNodes>& bands;
  int sensor_index;
  AirPath air;
  bool monte_carlo;

  // One camera sample at image position (px, py): band radiance and
  // response-weighted transmittance added to `sums`.
  void sample(double px, double py, Rng& rng, RayWorkspace& ws, PixelSums& sums) const {
    const CameraRay camera = camera_ray(px, py);
    integrator.begin_ray(camera, ws);
    const double air_m = air_path_m(scene, camera);
    NodeArray radiance, transmittance;
    for (std::size_t b = 0; b < bands.size(); ++b) {
      integrator.band_radiance(camera, sensor_index, static_cast<int>(b), rng, ws, radiance.data(),
                               transmittance.data());
      add_band(b, air_m, radiance.data(), transmittance.data(), sums);
    }
  }

  // Band b of one camera sample, from the radiance and transmittance at its
  // nodes, weighted by the band's quadrature, through the air path.
  void add_band(std::size_t b, double air_m, const double* radiance, const double* transmittance,
                PixelSums& sums) const {
    const SpectralNodes& nodes = bands[b];
    double band_l = 0, band_t = 0;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      band_l += nodes.nodes()[i].weight_um * radiance[i];
      band_t += nodes.nodes()[i].weight_um * transmittance[i];
    }
    if (scene.atmosphere.enabled) {
      const double tau_air = std::exp(-air.extinction_per_m[b] * air_m);
      band_l = tau_air * band_l + (1.0 - tau_air) * air.band_radiance[b];
    }
    sums.l[b] += band_l;
    sums.l2[b] += band_l * band_l;
    sums.t[b] += band_t / nodes.quadrature().response_integral();
  }

  // The image position of sample s of pixel (x, y): the pixel centre for one
  // sample per pixel, else a point jittered in the sample's cell of a
  // near-square grid of samples_per_pixel cells.
  void sample_position(int x, int y, int s, Rng& rng, double& px, double& py) const {
    const int spp = scene.settings.samples_per_pixel;
    px = x + 0.5;
    py = y + 0.5;
    if (spp <= 1) return;
    const int strata_x = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(spp))));
    const int strata_y = (spp + strata_x - 1) / strata_x;
    px = x + (s % strata_x + rng.uniform()) / strata_x;
    py = y + (s / strata_x + rng.uniform()) / strata_y;
  }

  // The camera ray through image position (px, py) with its first surface.
  CameraRay camera_ray(double px, double py) const {
    return find_camera_ray_hit(scene, sensor.camera.generate_ray(px, py));
  }

  // The samples_per_pixel camera rays of pixel (x, y) into out[0…spp), drawn
  // from the pixel's own stream as pixel() draws them (for batched
  // integrators, whose pixels must equal the ray-by-ray ones).
  void pixel_rays(int x, int y, CameraRay* out) const {
    const int spp = scene.settings.samples_per_pixel;
    Rng rng(scene.settings.seed, static_cast<std::size_t>(y) * sensor.camera.width() + x);
    for (int s = 0; s < spp; ++s) {
      double px, py;
      sample_position(x, y, s, rng, px, py);
      out[s] = camera_ray(px, py);
    }
  }

  // All samples of pixel (x, y): rounds of samples_per_pixel stratified
  // samples, more than one round only for a Monte Carlo method with a target
  // relative standard error. Returns the samples taken.
  int pixel(int x, int y, Rng& rng, RayWorkspace& ws, PixelSums& sums) const {
    const RenderSettings& settings = scene.settings;
    const int spp = settings.samples_per_pixel;
    const int max_spp = std::max(settings.max_samples_per_pixel, spp);
    const double target = settings.target_relative_stderr;
    int n = 0;
    for (bool more = true; more;) {
      for (int s = 0; s < spp; ++s, ++n) {
        double px, py;
        sample_position(x, y, s, rng, px, py);
        sample(px, py, rng, ws, sums);
      }
      more = false;
      if (monte_carlo && target > 0.0 && n + spp <= max_spp)
        for (std::size_t b = 0; b < sums.l.size(); ++b)
          more =
              more || standard_error(sums.l[b], sums.l2[b], n) > target * std::abs(sums.l[b] / n);
    }
    return n;
  }
};

// What the rows of one image count, summed over the threads.
struct RowCounters {
  std::atomic<std::uint64_t> segments{0}, evals{0}, samples_taken{0};
  std::atomic<int> rows_done{0};
};

// Pixel `pixel`'s bands from the sums of its n samples.
void store_pixel(const SensorRender& job, std::size_t pixel, const PixelSums& sums, int n,
                 SensorImage& image);

// Camera samples per batch of a batched integrator: bounds the rays and
// results held at once (about 100 MB of camera rays).
inline constexpr std::size_t kBatchSamples = std::size_t{1} << 20;

// Camera samples `rays` (with their first surfaces) through a batched
// integrator, kBatchSamples at a time: per sample i and band b, what
// SensorRender::add_band adds for it to a pixel's sums, the band radiance
// in l[i · bands + b] and the response-weighted transmittance in t[…].
void batch_sample_sums(const SensorRender& job, const BatchIntegrator& integrator,
                       const std::vector<CameraRay>& rays, std::vector<double>& l,
                       std::vector<double>& t, RowCounters& counters);

}  // namespace obscura::render_detail
