#include "obscura/sequence/sequence_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include "obscura/core/error.h"
#include "obscura/render/renderer.h"

namespace obscura {
namespace {

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
}

SensorFrameStats frame_stats(const SensorImage& image, double time_s, double staging_s) {
  SensorFrameStats s;
  s.sensor = image.sensor;
  s.time_s = time_s;
  s.width = image.width;
  s.height = image.height;
  s.stats = image.stats;
  s.staging_seconds = staging_s;
  for (const BandImage& b : image.bands) {
    const auto [tmin, tmax] =
        std::minmax_element(b.apparent_temperature.begin(), b.apparent_temperature.end());
    s.bands.push_back({b.band, mean(b.radiance), mean(b.transmittance), *tmin, *tmax});
  }
  return s;
}

}  // namespace

std::vector<double> parse_time_range(const std::string& text, const std::string& field) {
  auto bad = [&](const std::string& why) {
    return InputError("", field, fmt::format(fmt::runtime(why), text));
  };
  std::vector<double> v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t colon = i < 2 ? text.find(':', pos) : text.size();
    if (colon == std::string::npos) throw bad("'{}' is not A:B:STEP in seconds");
    try {
      std::size_t used = 0;
      const std::string part = text.substr(pos, colon - pos);
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw bad("'{}' is not A:B:STEP in seconds");
    }
    pos = colon + 1;
  }
  const double a = v[0], b = v[1], step = v[2];
  if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(step) && step > 0 && b >= a))
    throw bad("'{}' needs finite A <= B and STEP > 0");
  const double n = std::floor((b - a) / step + 1e-9);
  if (n > 100000) throw bad("'{}' gives more than 100000 frames");
  std::vector<double> times;
  for (int k = 0; k <= static_cast<int>(n); ++k) times.push_back(a + k * step);
  return times;
}

std::vector<TargetMask> scene_target_masks(const Scene& scene) {
  std::vector<TargetMask> masks;
  if (!scene_has_target(scene)) return masks;
  for (const Sensor& sensor : scene.sensors)
    masks.push_back(compute_target_mask(scene, sensor, scene.metrics.background_margin_px,
                                        scene.settings.threads));
  return masks;
}

RenderedFrame render_frame(const Scene& scene, std::size_t index, std::size_t frames,
                           const std::function<void(const RenderProgress&)>& progress) {
  RenderedFrame frame;
  frame.index = index;
  frame.time_s = scene.time_s;
  const FrameSpectra spectra = frame_spectra(scene);
  const std::unique_ptr<Integrator> integrator = make_integrator(scene, spectra);
  for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
    RenderOptions options;
    if (progress)
      options.progress = [&](int done, int total) {
        progress({index, frames, scene.time_s, static_cast<int>(s), done, total});
      };
    frame.images.push_back(
        render_sensor(scene, static_cast<int>(s), *integrator, spectra, options));
  }
  return frame;
}

SequenceResult render_sequence(Scene& scene, const std::vector<double>& times_s,
                               const SequenceOptions& options) {
  SequenceResult result;
  result.times_s = times_s;
  // Target masks once: surfaces do not move.
  result.masks = scene_target_masks(scene);
  result.with_metrics = !result.masks.empty();
  if (options.on_masks) options.on_masks(result.masks);
  const int nodes_per_band = scene.settings.spectral_nodes_per_band;
  for (std::size_t f = 0; f < times_s.size(); ++f) {
    const auto staging_start = std::chrono::steady_clock::now();
    stage_scene(scene, times_s[f]);
    const double staging_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - staging_start).count();
    RenderedFrame frame = render_frame(scene, f, times_s.size(), options.progress);
    frame.staging_seconds = staging_s;
    for (std::size_t s = 0; s < frame.images.size(); ++s) {
      const SensorImage& image = frame.images[s];
      result.sensor_frames.push_back(frame_stats(image, times_s[f], staging_s));
      for (RegionStats& r : region_stats(image, scene.regions, nodes_per_band))
        result.time_series.push_back({times_s[f], image.sensor, std::move(r)});
      if (result.with_metrics) {
        auto rows =
            screening_metrics(image, result.masks[s], scene.metrics, nodes_per_band, times_s[f]);
        result.metrics.insert(result.metrics.end(), rows.begin(), rows.end());
      }
    }
    if (options.on_frame) options.on_frame(frame);
  }
  if (result.with_metrics) {
    result.reference_time_s = screening_reference_time_s(scene);
    result.series = summarize_screening(result.metrics, scene.metrics, result.reference_time_s);
  }
  return result;
}

}  // namespace obscura
