#include "obscura/render/renderer.h"

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

#include "obscura/core/check.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/parallel.h"
#include "obscura/core/rng.h"
#include "obscura/render/adaptive_samples.h"
#include "obscura/render/batch_integrator.h"
#include "obscura/render/sensor_render.h"

namespace obscura {

SensorImage blank_sensor_image(const Sensor& sensor, bool monte_carlo) {
  SensorImage image;
  image.sensor = sensor.name;
  image.width = sensor.camera.width();
  image.height = sensor.camera.height();
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (const Band& band : sensor.bands)
    image.bands.push_back({band, std::vector<float>(pixels), std::vector<float>(pixels),
                           std::vector<float>(pixels),
                           monte_carlo ? std::vector<float>(pixels) : std::vector<float>()});
  image.samples_per_pixel.assign(pixels, 0);
  return image;
}

int rendered_row_count(int height, const RenderOptions& options) {
  OBSCURA_CHECK(options.row_stride >= 1 && options.row_offset >= 0 &&
                options.row_offset < options.row_stride);
  return std::max(0, (height - options.row_offset + options.row_stride - 1) / options.row_stride);
}

namespace {

using namespace render_detail;

// The rows of `options`, ray by ray: rows go to the threads, each pixel asks
// the integrator for every band of each of its camera samples.
void render_rays(const SensorRender& job, const RenderOptions& options, SensorImage& image,
                 RowCounters& counters) {
  const Scene& scene = job.scene;
  const int width = image.width, rows = rendered_row_count(image.height, options);
  parallel_for(static_cast<std::size_t>(rows), scene.settings.threads, [&](std::size_t row) {
    throw_if_interrupted();  // Ctrl-C stops a render at the next row (core/interrupt.h)
    const int y = options.row_offset + static_cast<int>(row) * options.row_stride;
    const std::unique_ptr<RayWorkspace> ws = job.integrator.make_workspace();
    PixelSums sums(job.bands.size());
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      Rng rng(scene.settings.seed, pixel);
      sums.clear();
      const int n = job.pixel(x, y, rng, *ws, sums);
      counters.samples_taken += n;
      store_pixel(job, pixel, sums, n, image);
    }
    counters.segments += ws->segments;
    counters.evals += ws->integrand_evals;
    const int done = ++counters.rows_done;
    if (options.progress) options.progress(done, rows);
  });
}

// The rows of `options` through a batched integrator (render/batch_integrator.h),
// in batches of whole rows: every camera ray of the batch and its first
// surface on the threads, the medium along all of them at once, then per
// pixel what lies behind the medium and the same band sums as ray by ray.
// Only for deterministic methods: every pixel takes samples_per_pixel samples.
void render_batches(const SensorRender& job, const BatchIntegrator& integrator,
                    const RenderOptions& options, SensorImage& image, RowCounters& counters) {
  OBSCURA_CHECK(!job.monte_carlo);
  const Scene& scene = job.scene;
  const int width = image.width, rows = rendered_row_count(image.height, options);
  const int spp = scene.settings.samples_per_pixel;
  const std::size_t bands = job.bands.size();
  const std::size_t per_row = static_cast<std::size_t>(width) * spp;
  const int rows_per_batch =
      static_cast<int>(std::max<std::size_t>(1, kBatchSamples / std::max<std::size_t>(1, per_row)));
  std::vector<CameraRay> rays;
  std::vector<double> l, t;
  for (int row0 = 0; row0 < rows; row0 += rows_per_batch) {
    const int batch_rows = std::min(rows_per_batch, rows - row0);
    auto image_row = [&](std::size_t r) {
      return options.row_offset + (row0 + static_cast<int>(r)) * options.row_stride;
    };
    rays.resize(static_cast<std::size_t>(batch_rows) * per_row);
    parallel_for(static_cast<std::size_t>(batch_rows), scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(r);
      for (int x = 0; x < width; ++x)
        job.pixel_rays(x, y, &rays[r * per_row + static_cast<std::size_t>(x) * spp]);
    });
    batch_sample_sums(job, integrator, rays, l, t, counters);
    parallel_for(static_cast<std::size_t>(batch_rows), scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(r);
      PixelSums sums(bands);
      for (int x = 0; x < width; ++x) {
        sums.clear();
        for (int s = 0; s < spp; ++s) {
          const std::size_t i = (r * per_row + static_cast<std::size_t>(x) * spp + s) * bands;
          sums.add(&l[i], &t[i]);
        }
        counters.samples_taken += spp;
        store_pixel(job, static_cast<std::size_t>(y) * width + x, sums, spp, image);
      }
      const int done = ++counters.rows_done;
      if (options.progress) options.progress(done, rows);
    });
  }
}

// `sensor` through `integrator`, which knows its bands' nodes as
// spectra[sensor_index] (= `bands`).
SensorImage render(const Scene& scene, const Sensor& sensor, int sensor_index,
                   const Integrator& integrator, const std::vector<SpectralNodes>& bands,
                   const RenderOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const bool monte_carlo = method_is_monte_carlo(integrator.method());
  const SensorRender job{
      scene, sensor, integrator, bands, sensor_index, AirPath(scene, sensor, bands), monte_carlo};
  SensorImage image = blank_sensor_image(sensor, monte_carlo);
  RowCounters counters;
  const bool adaptive = !monte_carlo && scene.settings.adaptive_threshold > 0.0 &&
                        scene.settings.samples_per_pixel > 1;
  if (const auto* batched = dynamic_cast<const BatchIntegrator*>(&integrator)) {
    if (adaptive)
      render_adaptive_batches(job, *batched, options, image, counters);
    else
      render_batches(job, *batched, options, image, counters);
  } else if (adaptive) {
    render_adaptive_rays(job, options, image, counters);
  } else {
    render_rays(job, options, image, counters);
  }

  const PreparationStats prep = integrator.preparation(sensor_index);
  image.stats.rays = counters.samples_taken;
  image.stats.segments = counters.segments;
  image.stats.integrand_evals = counters.evals;
  image.stats.photons = prep.photons;
  image.stats.photon_bytes = prep.photon_bytes;
  image.stats.photon_seconds = prep.seconds;
  image.stats.photon_trace_seconds = prep.trace_seconds;
  image.stats.photon_build_seconds = prep.build_seconds;
  image.stats.photons_traced = prep.walks.photons;
  image.stats.photons_colliding = prep.walks.colliding;
  image.stats.photon_collisions = prep.walks.collisions;
  // The sensor's cost: its pixels and what was prepared for it.
  image.stats.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() +
      prep.seconds;
  return image;
}

}  // namespace

SensorImage render_sensor(const Scene& scene, int sensor, const Integrator& integrator,
                          const FrameSpectra& spectra, const RenderOptions& options) {
  const auto i = static_cast<std::size_t>(sensor);
  OBSCURA_CHECK(i < scene.sensors.size() && i < spectra.size());
  return render(scene, scene.sensors[i], sensor, integrator, spectra[i], options);
}

SensorImage render_sensor(const Scene& scene, const Sensor& sensor, const RenderOptions& options) {
  const FrameSpectra spectra = {sensor_spectra(scene, sensor)};
  const std::unique_ptr<Integrator> integrator = make_integrator(scene, spectra);
  return render(scene, sensor, 0, *integrator, spectra[0], options);
}

}  // namespace obscura