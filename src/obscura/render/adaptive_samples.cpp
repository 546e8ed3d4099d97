#include "obscura/render/adaptive_samples.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "obscura/core/interrupt.h"
#include "obscura/core/parallel.h"

namespace obscura::render_detail {
namespace {

// The centre samples an adaptive render compares: per needed row, pixel and
// band, the centre's band radiance and transmittance as one sample adds them
// to a pixel's sums (SensorRender::add_band).
class CentreSamples {
 public:
  CentreSamples(const SensorRender& job, const RenderOptions& options, int width, int height)
      : width_(width),
        height_(height),
        bands_(job.bands.size()),
        threshold_(job.scene.settings.adaptive_threshold),
        row_of_(static_cast<std::size_t>(height), -1) {
    auto rendered = [&](int y) {
      return y >= options.row_offset && y < height &&
             (y - options.row_offset) % options.row_stride == 0;
    };
    for (int y = 0; y < height; ++y)
      if (rendered(y) || rendered(y - 1) || rendered(y + 1)) {
        row_of_[static_cast<std::size_t>(y)] = static_cast<int>(rows_.size());
        rows_.push_back(y);
      }
    l_.resize(rows_.size() * static_cast<std::size_t>(width) * bands_);
    t_.resize(l_.size());
  }

  // The image rows whose centres are needed, in order.
  const std::vector<int>& rows() const { return rows_; }

  // Stores the centre of pixel x of needed row r from one sample's sums.
  void set(std::size_t r, int x, const double* l, const double* t) {
    const std::size_t at = slot(r, x);
    std::copy(l, l + bands_, l_.begin() + static_cast<std::ptrdiff_t>(at));
    std::copy(t, t + bands_, t_.begin() + static_cast<std::ptrdiff_t>(at));
  }

  // Whether pixel (x, y) takes its full samples: its centre differs from one
  // of its 8 neighbours' in some band, in band radiance by more than the
  // threshold of the larger magnitude, or in transmittance by more than it.
  bool refine(int x, int y) const {
    const std::size_t here = slot_of(x, y);
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || nx >= width_ || ny < 0 || ny >= height_) continue;
        const std::size_t there = slot_of(nx, ny);
        for (std::size_t b = 0; b < bands_; ++b) {
          const double la = l_[here + b], lb = l_[there + b];
          if (std::abs(la - lb) > threshold_ * std::max(std::abs(la), std::abs(lb)) ||
              std::abs(t_[here + b] - t_[there + b]) > threshold_)
            return true;
        }
      }
    return false;
  }

  // Adds pixel (x, y)'s centre to `sums` as one sample.
  void add_centre(int x, int y, PixelSums& sums) const {
    const std::size_t here = slot_of(x, y);
    sums.add(&l_[here], &t_[here]);
  }

 private:
  std::size_t slot(std::size_t r, int x) const {
    return (r * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x)) * bands_;
  }
  std::size_t slot_of(int x, int y) const {
    return slot(static_cast<std::size_t>(row_of_[static_cast<std::size_t>(y)]), x);
  }

  int width_, height_;
  std::size_t bands_;
  double threshold_;
  std::vector<int> rows_, row_of_;
  std::vector<double> l_, t_;
};

// The image row of rendered row `row` of `options`.
int image_row(const RenderOptions& options, std::size_t row) {
  return options.row_offset + static_cast<int>(row) * options.row_stride;
}

// Progress counts every row twice, its centres and then its samples (the
// rows of centres include the neighbours of a process's rows): the first
// pass is about as costly as the second, which refines a fraction of the
// pixels.
void finish_row(const RenderOptions& options, RowCounters& counters, int passes) {
  const int done = ++counters.rows_done;
  if (options.progress) options.progress(done, passes);
}

}  // namespace

void render_adaptive_rays(const SensorRender& job, const RenderOptions& options, SensorImage& image,
                          RowCounters& counters) {
  const Scene& scene = job.scene;
  const int width = image.width, rows = rendered_row_count(image.height, options);
  const std::size_t bands = job.bands.size();
  CentreSamples centres(job, options, width, image.height);
  const int passes = static_cast<int>(centres.rows().size()) + rows;
  parallel_for(centres.rows().size(), scene.settings.threads, [&](std::size_t r) {
    throw_if_interrupted();
    const int y = centres.rows()[r];
    const std::unique_ptr<RayWorkspace> ws = job.integrator.make_workspace();
    PixelSums sums(bands);
    for (int x = 0; x < width; ++x) {
      Rng rng(scene.settings.seed, static_cast<std::size_t>(y) * width + x);
      sums.clear();
      job.sample(x + 0.5, y + 0.5, rng, *ws, sums);
      centres.set(r, x, sums.l.data(), sums.t.data());
    }
    counters.samples_taken += width;
    counters.segments += ws->segments;
    counters.evals += ws->integrand_evals;
    finish_row(options, counters, passes);
  });
  parallel_for(static_cast<std::size_t>(rows), scene.settings.threads, [&](std::size_t row) {
    throw_if_interrupted();
    const int y = image_row(options, row);
    const std::unique_ptr<RayWorkspace> ws = job.integrator.make_workspace();
    PixelSums sums(bands);
    for (int x = 0; x < width; ++x) {
      const std::size_t pixel = static_cast<std::size_t>(y) * width + x;
      sums.clear();
      int n = 1;
      if (centres.refine(x, y)) {
        Rng rng(scene.settings.seed, pixel);
        n = job.pixel(x, y, rng, *ws, sums);
        counters.samples_taken += n;
      } else {
        centres.add_centre(x, y, sums);
      }
      store_pixel(job, pixel, sums, n, image);
    }
    counters.segments += ws->segments;
    counters.evals += ws->integrand_evals;
    finish_row(options, counters, passes);
  });
}

void render_adaptive_batches(const SensorRender& job, const BatchIntegrator& integrator,
                             const RenderOptions& options, SensorImage& image,
                             RowCounters& counters) {
  const Scene& scene = job.scene;
  const int width = image.width, rows = rendered_row_count(image.height, options);
  const int spp = scene.settings.samples_per_pixel;
  const std::size_t bands = job.bands.size();
  CentreSamples centres(job, options, width, image.height);
  const int passes = static_cast<int>(centres.rows().size()) + rows;
  std::vector<CameraRay> rays;
  std::vector<double> l, t;

  // The centres, in batches of whole rows.
  const std::size_t centre_rows = centres.rows().size();
  const std::size_t centre_batch = std::max<std::size_t>(1, kBatchSamples / width);
  for (std::size_t r0 = 0; r0 < centre_rows; r0 += centre_batch) {
    const std::size_t batch_rows = std::min(centre_batch, centre_rows - r0);
    rays.resize(batch_rows * width);
    parallel_for(batch_rows, scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = centres.rows()[r0 + r];
      for (int x = 0; x < width; ++x) rays[r * width + x] = job.camera_ray(x + 0.5, y + 0.5);
    });
    batch_sample_sums(job, integrator, rays, l, t, counters);
    for (std::size_t r = 0; r < batch_rows; ++r) {
      for (int x = 0; x < width; ++x) {
        const std::size_t i = (r * width + x) * bands;
        centres.set(r0 + r, x, &l[i], &t[i]);
      }
      finish_row(options, counters, passes);
    }
    counters.samples_taken += rays.size();
  }

  // The rendered rows in batches that hold every pixel's samples at most:
  // which pixels are refined, their samples' rays from their own streams,
  // the march, then each pixel from its samples or its centre.
  const std::size_t per_row = static_cast<std::size_t>(width) * spp;
  const std::size_t row_batch = std::max<std::size_t>(1, kBatchSamples / per_row);
  std::vector<std::uint8_t> refined;
  std::vector<std::size_t> first;  // per row of the batch: its first sample
  for (std::size_t row0 = 0; row0 < static_cast<std::size_t>(rows); row0 += row_batch) {
    const std::size_t batch_rows = std::min(row_batch, static_cast<std::size_t>(rows) - row0);
    refined.assign(batch_rows * width, 0);
    parallel_for(batch_rows, scene.settings.threads, [&](std::size_t r) {
      const int y = image_row(options, row0 + r);
      for (int x = 0; x < width; ++x) refined[r * width + x] = centres.refine(x, y) ? 1 : 0;
    });
    first.assign(batch_rows + 1, 0);
    for (std::size_t r = 0; r < batch_rows; ++r)
      first[r + 1] =
          first[r] + spp * static_cast<std::size_t>(std::count(
                               refined.begin() + static_cast<std::ptrdiff_t>(r * width),
                               refined.begin() + static_cast<std::ptrdiff_t>((r + 1) * width),
                               std::uint8_t{1}));
    rays.resize(first[batch_rows]);
    parallel_for(batch_rows, scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(options, row0 + r);
      std::size_t next = first[r];
      for (int x = 0; x < width; ++x)
        if (refined[r * width + x]) {
          job.pixel_rays(x, y, &rays[next]);
          next += spp;
        }
    });
    batch_sample_sums(job, integrator, rays, l, t, counters);
    parallel_for(batch_rows, scene.settings.threads, [&](std::size_t r) {
      throw_if_interrupted();
      const int y = image_row(options, row0 + r);
      PixelSums sums(bands);
      std::size_t next = first[r];
      for (int x = 0; x < width; ++x) {
        sums.clear();
        int n = 1;
        if (refined[r * width + x]) {
          for (int s = 0; s < spp; ++s, ++next) sums.add(&l[next * bands], &t[next * bands]);
          n = spp;
          counters.samples_taken += spp;
        } else {
          centres.add_centre(x, y, sums);
        }
        store_pixel(job, static_cast<std::size_t>(y) * width + x, sums, n, image);
      }
      finish_row(options, counters, passes);
    });
  }
}

}  // namespace obscura::render_detail
