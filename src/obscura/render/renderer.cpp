#include "obscura/render/renderer.h"

#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/parallel.h"
#include "obscura/core/rng.h"
#include "obscura/render/background.h"
#include "obscura/render/batch_integrator.h"

namespace obscura {
namespace {

using NodeArray = std::array<double, kMaxSpectralNodes>;

// Standard error of the mean of n independent samples with sum s and sum of squares s2.
double standard_error(double s, double s2, int n) {
  if (n < 2) return 0.0;
  const double mean = s / n;
  return std::sqrt(std::max(0.0, s2 / n - mean * mean) / (n - 1));
}

// The atmosphere between the sensor and the scene, per band
// (scene/atmosphere.h): its extinction coefficient (1/m) and its own band
// radiance, (1 − τ) of which joins every ray.
struct AirPath {
  std::vector<double> extinction_per_m, band_radiance;

  AirPath(const Scene& scene, const Sensor& sensor, const std::vector<SpectralNodes>& bands)
      : extinction_per_m(sensor.bands.size(), 0.0), band_radiance(sensor.bands.size(), 0.0) {
    if (!scene.atmosphere.enabled) return;
    for (std::size_t b = 0; b < sensor.bands.size(); ++b) {
      extinction_per_m[b] = scene.atmosphere.extinction_for(sensor.bands[b]);
      for (const SpectralNode& nd : bands[b].nodes())
        band_radiance[b] += nd.weight_um * nd.planck(scene.atmosphere.temperature_k);
    }
  }
};

// How far a camera ray runs through the air before it meets the scene: to
// the surface, else through the clouds' box (0 when it meets neither).
double air_path_m(const Scene& scene, const CameraRay& camera) {
  if (camera.on_surface) return camera.hit.t;
  double t0 = 0.0, t1 = std::numeric_limits<double>::infinity();
  if (scene.atmosphere.enabled && scene.medium &&
      scene.medium->bounds().intersect(camera.ray, t0, t1))
    return t1;
  return 0.0;
}

// Running sums of one pixel's samples, per band.
struct PixelSums {
  std::vector<double> l, l2, t;
  explicit PixelSums(std::size_t bands) : l(bands), l2(bands), t(bands) {}
  void clear() {
    std::fill(l.begin(), l.end(), 0.0);
    std::fill(l2.begin(), l2.end(), 0.0);
    std::fill(t.begin(), t.end(), 0.0);
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
    const CameraRay camera = find_camera_ray_hit(scene, sensor.camera.generate_ray(px, py));
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

}  // namespace

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

// What the rows of one image count, summed over the threads.
struct RowCounters {
  std::atomic<std::uint64_t> segments{0}, evals{0}, samples_taken{0};
  std::atomic<int> rows_done{0};
};

// Pixel `pixel`'s bands from the sums of its n samples.
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

// Camera samples per batch of a batched integrator: bounds the rays and
// results held at once (about 100 MB of camera rays).
constexpr std::size_t kBatchSamples = std::size_t{1} << 20;

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
  const std::size_t per_row = static_cast<std::size_t>(width) * spp;
  const int rows_per_batch =
      static_cast<int>(std::max<std::size_t>(1, kBatchSamples / std::max<std::size_t>(1, per_row)));
  const std::vector<int> first = band_output_offsets(job.bands);
  std::vector<CameraRay> rays;
  MediumBatch batch;
  for (int row0 = 0; row0 < rows; row0 += rows_per_batch) {
    const int batch_rows = std::min(rows_per_batch, rows - row0);
    auto image_row = [&](std::size_t r) {
      return options.row_offset + (row0 + static_cast<int>(r)) * options.row_stride;
    };
    rays.resize(static_cast<std::size_t>(batch_rows) * per_row);
    parallel_for(static_cast<std::size_t>(batch_rows), scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(r);
      for (int x = 0; x < width; ++x) {
        Rng rng(scene.settings.seed, static_cast<std::size_t>(y) * width + x);
        for (int s = 0; s < spp; ++s) {
          double px, py;
          job.sample_position(x, y, s, rng, px, py);
          rays[r * per_row + static_cast<std::size_t>(x) * spp + s] =
              find_camera_ray_hit(scene, job.sensor.camera.generate_ray(px, py));
        }
      }
    });
    integrator.march_batch(job.sensor_index, rays, batch);
    for (const std::uint64_t cells : batch.band_cells) counters.segments += cells;
    const std::size_t count = rays.size();
    parallel_for(static_cast<std::size_t>(batch_rows), scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(r);
      BackgroundScratch scratch;
      PixelSums sums(job.bands.size());
      NodeArray radiance, transmittance, behind;
      for (int x = 0; x < width; ++x) {
        sums.clear();
        for (int s = 0; s < spp; ++s) {
          const std::size_t i = r * per_row + static_cast<std::size_t>(x) * spp + s;
          const CameraRay& camera = rays[i];
          const double air_m = air_path_m(scene, camera);
          for (std::size_t b = 0; b < job.bands.size(); ++b) {
            const SpectralNodes& nodes = job.bands[b];
            integrator.behind_radiance(camera, job.sensor_index, static_cast<int>(b), nodes,
                                       scratch, behind.data());
            for (std::size_t j = 0; j < nodes.size(); ++j) {
              const std::size_t at = (first[b] + j) * count + i;
              transmittance[j] = batch.transmittance[at];
              radiance[j] = batch.radiance[at] + transmittance[j] * behind[j];
            }
            job.add_band(b, air_m, radiance.data(), transmittance.data(), sums);
          }
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
  if (const auto* batched = dynamic_cast<const BatchIntegrator*>(&integrator))
    render_batches(job, *batched, options, image, counters);
  else
    render_rays(job, options, image, counters);

  const PreparationStats prep = integrator.preparation(sensor_index);
  image.stats.rays = counters.samples_taken;
  image.stats.segments = counters.segments;
  image.stats.integrand_evals = counters.evals;
  image.stats.photons = prep.photons;
  image.stats.photon_bytes = prep.photon_bytes;
  image.stats.photon_seconds = prep.seconds;
  image.stats.photon_trace_seconds = prep.trace_seconds;
  image.stats.photon_build_seconds = prep.build_seconds;
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
