#include "obscura/render/renderer.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/core/rng.h"
#include "obscura/render/emission_absorption/emission_absorption.h"
#include "obscura/render/photon_map/photon_map_integrator.h"
#include "obscura/render/spectral_nodes.h"
#include "obscura/render/path_tracer/volume_path_tracer.h"

namespace obscura {
namespace {

// Standard error of the mean of n independent samples with sum s and sum of squares s2.
double standard_error(double s, double s2, int n) {
  if (n < 2) return 0.0;
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
}

}  // namespace

SensorImage render_sensor(const Scene& scene, const Sensor& sensor, const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const RenderSettings& settings = scene.settings;
  const bool photon_mapping = settings.method == "photonmap";
  // Both Monte Carlo methods report standard errors and the exact line-of-sight transmittance.
  const bool path_tracer = settings.method == "path-tracer" || photon_mapping;
  if (!path_tracer && settings.method != "emission-absorption")
    throw Error("render: unknown method '" + settings.method + "'");
  const PinholeCamera& cam = sensor.camera;
  const int width = cam.width(), height = cam.height();
  const std::size_t pixels = static_cast<std::size_t>(width) * height;
  const std::vector<double> grey = {1.0};
  const std::vector<double>& medium_wl = scene.medium ? scene.medium->wavelengths_um() : grey;

  SensorImage image;
  image.sensor = sensor.name;
  image.width = width;
  image.height = height;
  std::vector<SpectralNodes> band_nodes;
  for (const Band& band : sensor.bands) {
    band_nodes.emplace_back(BandQuadrature(band, settings.spectral_nodes_per_band, 0.0), medium_wl);
    if (band_nodes.back().size() > static_cast<std::size_t>(kMaxSpectralNodes))
      throw InputError("", "band " + band.name(), "too many spectral nodes for one band");
    image.bands.push_back({band, std::vector<float>(pixels), std::vector<float>(pixels),
                           std::vector<float>(pixels),
                           path_tracer ? std::vector<float>(pixels) : std::vector<float>()});
  }

  // The atmosphere per band (scene/atmosphere.h): its extinction coefficient
  // (1/m) and its own band radiance, (1 − τ) of which joins every ray.
  std::vector<double> air_extinction_per_m(sensor.bands.size(), 0.0),
      air_band_radiance(sensor.bands.size(), 0.0);
  if (scene.atmosphere.enabled)
    for (std::size_t b = 0; b < sensor.bands.size(); ++b) {
      air_extinction_per_m[b] = scene.atmosphere.extinction_for(sensor.bands[b]);
      for (const SpectralNode& nd : band_nodes[b].nodes())
        air_band_radiance[b] += nd.weight_um * nd.planck(scene.atmosphere.temperature_k);
    }

  // Pass 1 of photon mapping: photon maps for every node of every band.
  std::unique_ptr<PhotonMapIntegrator> photon_map;
  if (photon_mapping) {
    const auto t0 = std::chrono::steady_clock::now();
    photon_map = std::make_unique<PhotonMapIntegrator>(scene, band_nodes, settings.photon_map,
                                                       options.seed, options.threads);
    image.stats.photons = photon_map->photon_count();
    image.stats.photon_bytes = photon_map->memory_bytes();
    image.stats.photon_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    image.stats.photon_trace_seconds = photon_map->tracing_seconds();
    image.stats.photon_build_seconds = photon_map->build_seconds();
  }
  image.samples_per_pixel.assign(pixels, 0);
  std::atomic<std::uint64_t> segments{0}, evals{0}, samples_taken{0};
  const double target = settings.target_relative_stderr;
  const int max_spp = std::max(settings.max_samples_per_pixel, settings.samples_per_pixel);
  std::atomic<int> rows_done{0};
  const int spp = settings.samples_per_pixel;
  // Stratify the pixel into a near-square grid of spp cells.
  const int strata_x = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(spp))));

  parallel_for(static_cast<std::size_t>(height), options.threads, [&](std::size_t row) {
    const int y = static_cast<int>(row);
    std::array<double, kMaxSpectralNodes> radiance, transmittance;
    EmissionAbsorptionStats stats;
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      Rng rng(options.seed, pixel);
      std::vector<double> sum_l(image.bands.size(), 0.0), sum_t(image.bands.size(), 0.0),
          sum_l2(image.bands.size(), 0.0);
      int n = 0;  // samples taken in this pixel
      // Rounds of spp stratified samples; more than one only for a path tracer
      // with a target relative standard error.
      for (bool more = true; more;) {
        for (int s = 0; s < spp; ++s, ++n) {
          double px = x + 0.5, py = y + 0.5;
          if (spp > 1) {
            const int sx = s % strata_x, sy = s / strata_x;
            const int strata_y = (spp + strata_x - 1) / strata_x;
            px = x + (sx + rng.uniform()) / strata_x;
            py = y + (sy + rng.uniform()) / strata_y;
          }
          const Ray ray = cam.generate_ray(px, py);
          SurfaceHit hit;
          const bool hit_surface = intersect_surfaces(scene.surfaces, ray, 0.0,
                                                      std::numeric_limits<double>::infinity(), hit);
          const double t_max = hit_surface ? hit.t : std::numeric_limits<double>::infinity();
          // The path tracer reports the exact line-of-sight transmittance: τ per
          // medium sample, once per ray for all bands.
          const std::vector<double> line_of_sight_tau =
              path_tracer && scene.medium
                  ? scene.medium->optical_depth(ray, 0.0, t_max)
                  : std::vector<double>(path_tracer ? medium_wl.size() : 0, 0.0);
          // How far the ray runs through the air before it meets the scene
          // (scene/atmosphere.h): to the surface, else through the clouds' box.
          double air_path_m = hit_surface ? hit.t : 0.0;
          if (scene.atmosphere.enabled && !hit_surface && scene.medium) {
            double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
            if (scene.medium->bounds().intersect(ray, t0, t1)) air_path_m = t1;
          }
          for (std::size_t b = 0; b < image.bands.size(); ++b) {
            const SpectralNodes& nodes = band_nodes[b];
            const int n = static_cast<int>(nodes.size());
            double band_l = 0, band_t = 0;
            if (path_tracer) {
              if (photon_mapping)
                photon_map->radiance(ray, static_cast<int>(b), rng, radiance.data());
              // One path per spectral node (or one photon-map estimate).
              for (int i = 0; i < n; ++i) {
                const SpectralNode& nd = nodes.nodes()[i];
                band_l +=
                    nd.weight_um * (photon_mapping ? radiance[i] : trace_path(scene, ray, nd, rng));
                band_t += nd.weight_um * std::exp(-nd.lerp()(line_of_sight_tau.data()));
              }
            } else {
              for (int i = 0; i < n; ++i) {
                radiance[i] = 0.0;
                transmittance[i] = 1.0;
              }
              integrate_emission_absorption(scene.medium.get(), ray, t_max, nodes,
                                            settings.relative_tolerance, radiance.data(),
                                            transmittance.data(), &stats);
              for (int i = 0; i < n; ++i) {
                const SpectralNode& nd = nodes.nodes()[i];
                double background = scene.sky.radiance(ray.direction, nd.wavelength_um);
                if (hit_surface) {
                  const SurfaceMaterial& m = scene.surfaces[hit.surface]->material();
                  // Opaque Lambertian surface: emits ε B(T) and reflects
                  // (1 − ε) of the sky it faces (clouds' light on surfaces is the
                  // path tracer's job).
                  const double emissivity = m.emissivity_at(nd.wavelength_um);
                  background = emissivity * nd.planck(m.temperature_k) +
                               (1.0 - emissivity) *
                                   scene.sky.cosine_weighted_mean(hit.normal, nd.wavelength_um);
                }
                band_l += nd.weight_um * (radiance[i] + transmittance[i] * background);
                band_t += nd.weight_um * transmittance[i];
              }
            }
            if (scene.atmosphere.enabled) {
              const double tau_air = std::exp(-air_extinction_per_m[b] * air_path_m);
              band_l = tau_air * band_l + (1.0 - tau_air) * air_band_radiance[b];
            }
            sum_l[b] += band_l;
            sum_l2[b] += band_l * band_l;
            sum_t[b] += band_t / nodes.quadrature().response_integral();
          }
        }
        more = false;
        if (path_tracer && target > 0.0 && n + spp <= max_spp)
          for (std::size_t b = 0; b < sum_l.size(); ++b)
            more = more || standard_error(sum_l[b], sum_l2[b], n) > target * std::abs(sum_l[b] / n);
      }
      samples_taken += n;
      image.samples_per_pixel[pixel] = static_cast<std::uint32_t>(n);
      for (std::size_t b = 0; b < image.bands.size(); ++b) {
        const double l = sum_l[b] / n;
        image.bands[b].radiance[pixel] = static_cast<float>(l);
        image.bands[b].transmittance[pixel] = static_cast<float>(sum_t[b] / n);
        image.bands[b].apparent_temperature[pixel] =
            static_cast<float>(band_nodes[b].quadrature().apparent_temperature(l));
        if (path_tracer)
          image.bands[b].radiance_stderr[pixel] =
              static_cast<float>(standard_error(sum_l[b], sum_l2[b], n));
      }
    }
    segments += stats.segments;
    evals += stats.integrand_evals;
    const int done = ++rows_done;
    if (options.progress) options.progress(done, height);
  });

  image.stats.rays = samples_taken;
  image.stats.segments = segments;
  image.stats.integrand_evals = evals;
  image.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return image;
}

}  // namespace obscura
