#include "obscura/render/sensor_render.h"

#include <algorithm>
#include <limits>

#include "obscura/core/interrupt.h"
#include "obscura/core/parallel.h"
#include "obscura/render/background.h"

namespace obscura::render_detail {

double standard_error(double s, double s2, int n) {
  if (n < 2) return 0.0;
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
}

AirPath::AirPath(const Scene& scene, const Sensor& sensor, const std::vector<SpectralNodes>& bands)
    : extinction_per_m(sensor.bands.size(), 0.0), band_radiance(sensor.bands.size(), 0.0) {
  if (!scene.atmosphere.enabled) return;
  for (std::size_t b = 0; b < sensor.bands.size(); ++b) {
    extinction_per_m[b] = scene.atmosphere.extinction_for(sensor.bands[b]);
    for (const SpectralNode& nd : bands[b].nodes())
      band_radiance[b] += nd.weight_um * nd.planck(scene.atmosphere.temperature_k);
  }
}

double air_path_m(const Scene& scene, const CameraRay& camera) {
  if (camera.on_surface) return camera.hit.t;
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  if (scene.atmosphere.enabled && scene.medium &&
      scene.medium->bounds().intersect(camera.ray, t0, t1))
    return t1;
  return 0.0;
}

void store_pixel(const SensorRender& job, std::size_t pixel, const PixelSums& sums, int n,
                 SensorImage& image) {
  image.samples_per_pixel[pixel] = static_cast<std::uint32_t>(n);
  for (std::size_t b = 0; b < job.bands.size(); ++b) {
    BandImage& out = image.bands[b];
    const double l = sums.l[b] / n;
    out.radiance[pixel] = static_cast<float>(l);
    out.transmittance[pixel] = static_cast<float>(sums.t[b] / n);
    out.apparent_temperature[pixel] =
        static_cast<float>(job.bands[b].quadrature().apparent_temperature(l));
    if (job.monte_carlo)
      out.radiance_stderr[pixel] = static_cast<float>(standard_error(sums.l[b], sums.l2[b], n));
  }
}

void batch_sample_sums(const SensorRender& job, const BatchIntegrator& integrator,
                       const std::vector<CameraRay>& rays, std::vector<double>& l,
                       std::vector<double>& t, RowCounters& counters) {
  const Scene& scene = job.scene;
  const std::size_t bands = job.bands.size();
  l.assign(rays.size() * bands, 0.0);
  t.assign(l.size(), 0.0);
  const std::vector<int> first = band_output_offsets(job.bands);
  MediumBatch batch;
  for (std::size_t start = 0; start < rays.size(); start += kBatchSamples) {
    const std::size_t count = std::min(kBatchSamples, rays.size() - start);
    integrator.march_batch(job.sensor_index, {rays.data() + start, count}, batch);
    for (const std::uint64_t cells : batch.band_cells) counters.segments += cells;
    // The background and the band sums, in chunks of samples on the threads.
    constexpr std::size_t kChunk = 1024;
    parallel_for((count + kChunk - 1) / kChunk, scene.settings.threads, [&](std::size_t c) {
      throw_if_interrupted();
      BackgroundScratch scratch;
      PixelSums sums(bands);
      NodeArray radiance, transmittance, behind;
      for (std::size_t i = c * kChunk; i < std::min(count, (c + 1) * kChunk); ++i) {
        const CameraRay& camera = rays[start + i];
        const double air_m = air_path_m(scene, camera);
        sums.clear();
        for (std::size_t b = 0; b < bands; ++b) {
          const SpectralNodes& nodes = job.bands[b];
          integrator.behind_radiance(camera, job.sensor_index, static_cast<int>(b), nodes, scratch,
                                     behind.data());
          for (std::size_t j = 0; j < nodes.size(); ++j) {
            const std::size_t at = (first[b] + j) * count + i;
            transmittance[j] = batch.transmittance[at];
            radiance[j] = batch.radiance[at] + batch.attenuation[at] * behind[j];
          }
          job.add_band(b, air_m, radiance.data(), transmittance.data(), sums);
        }
        std::copy(sums.l.begin(), sums.l.end(),
                  l.begin() + static_cast<std::ptrdiff_t>((start + i) * bands));
        std::copy(sums.t.begin(), sums.t.end(),
                  t.begin() + static_cast<std::ptrdiff_t>((start + i) * bands));
      }
    });
  }
}

}  // namespace obscura::render_detail
