#pragma once
// Renders a scene over a list of times: the library form of `obscura render`
// that the CLI, the benches and (later) Python and MPI call. Per frame it
// stages the scene at the time (scene/scene.h), prepares the render method
// once for every sensor (render/integrator_registry.h), renders each sensor,
// and measures the frame: region means (analysis/region_stats.h) and, when a
// surface is a target, screening metrics (analysis/screening_metrics.h).
// Frames are handed to a callback as they complete, so that a writer can put
// them on disk and the images need not stay in memory; what the sequence
// measured comes back as data (report/sequence_output.h writes it).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "obscura/analysis/region_stats.h"
#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/film/sensor_image.h"
#include "obscura/scene/scene.h"

namespace obscura {

// Where a render is, for progress displays: called from any thread.
struct RenderProgress {
  std::size_t frame = 0, frames = 0;  // 0-based frame index, frame count
  double time_s = 0;                  // the frame's scene time
  int sensor = 0;                     // index into scene.sensors
  int rows_done = 0, rows_total = 0;  // of that sensor's image
};

// One region-mean row of the time series: a frame, a sensor, a region
// ("image" for the whole image) and a band.
struct TimeSeriesRow {
  double time_s = 0;
  std::string sensor;
  RegionStats stats;
};

// One rendered frame: every sensor's image, as the renderer made them.
struct RenderedFrame {
  std::size_t index = 0;  // in the sequence
  double time_s = 0;
  double staging_seconds = 0;       // staging the clouds at time_s, shared by the sensors
  std::vector<SensorImage> images;  // one per scene sensor, in scene order
};

// The per-sensor figures of one frame that a summary reports.
struct SensorFrameStats {
  std::string sensor;
  double time_s = 0;
  int width = 0, height = 0;
  RenderStats stats;
  double staging_seconds = 0;
  struct BandFigures {
    Band band;
    double mean_radiance = 0;       // W m⁻² sr⁻¹, over the image
    double mean_transmittance = 0;  // 1
    double min_apparent_temperature_k = 0, max_apparent_temperature_k = 0;
  };
  std::vector<BandFigures> bands;
};

// What a sequence measured, as data.
struct SequenceResult {
  std::vector<double> times_s;
  std::vector<SensorFrameStats> sensor_frames;  // frame-major, then sensor order
  std::vector<TimeSeriesRow> time_series;       // frame-major, then sensor, region, band
  // Screening (only when some surface is a target): one mask per sensor, the
  // metrics of every frame, sensor and band, and their summary per series.
  bool with_metrics = false;
  double reference_time_s = 0;  // when screening is measured from
  std::vector<TargetMask> masks;
  std::vector<ScreeningMetrics> metrics;
  std::vector<ScreeningSeries> series;
};

struct SequenceOptions {
  std::function<void(const RenderProgress&)> progress;
  // Called once the target masks are known, before the first frame is staged
  // (a caller can warn about sensors that do not see the target).
  std::function<void(const std::vector<TargetMask>&)> on_masks;
  // Called with each frame when it is complete, before the next is staged.
  std::function<void(const RenderedFrame&)> on_frame;
};

// "A:B:STEP" in seconds: A, A + STEP, … up to B inclusive (to 1e-9 of a
// step). Throws InputError naming `field` for anything else, a non-finite
// value, B < A, STEP <= 0 or more than 100 000 frames.
std::vector<double> parse_time_range(const std::string& text, const std::string& field = "--time");

// The target masks of every sensor (empty vector when no surface is a target).
std::vector<TargetMask> scene_target_masks(const Scene& scene);

// Renders `scene` at each of `times_s` (any order; frames are numbered in the
// order given). Leaves the scene staged at the last time. Settings (method,
// threads, seed) are scene.settings.
SequenceResult render_sequence(Scene& scene, const std::vector<double>& times_s,
                               const SequenceOptions& options = {});

// One frame of the staged scene: every sensor through one prepared integrator.
RenderedFrame render_frame(const Scene& scene, std::size_t index = 0, std::size_t frames = 1,
                           const std::function<void(const RenderProgress&)>& progress = {});

}  // namespace obscura
