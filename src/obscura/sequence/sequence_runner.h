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
//
// Shared among processes (core/process_group.h, MPI ranks): by frames, each
// process draws the next frame from a shared counter, renders it and hands it
// to rank 0; or by tiles, every process renders every N-th row of each frame
// and a share of its photons.
// Rank 0 measures every frame and calls on_frame in frame order, so what it
// gets is bit for bit what one process gets (docs/cluster.md).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "obscura/analysis/region_stats.h"
#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/core/process_group.h"
#include "obscura/film/sensor_image.h"
#include "obscura/scene/scene.h"

namespace obscura {

// Where a render is, for progress displays: called from any thread.
struct RenderProgress {
  std::size_t frame = 0, frames = 0;  // 0-based frame index, frame count
  double time_s = 0;                  // the frame's scene time
  int sensor = 0;                     // index into scene.sensors; −1 while the frame is prepared
  int rows_done = 0, rows_total = 0;  // of that sensor's image (each row twice with an
                                      // adaptive threshold: RenderOptions::progress)
  // While the frame is prepared (sensor −1), before any sensor's rows: the
  // photons the photon methods have traced, of all they trace for it.
  long long photons_done = 0, photons_total = 0;
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

// How the processes of a run share a sequence: every N-th frame each, or
// every N-th row of every frame (and its photons); auto: by frames when there
// are at least as many frames as processes, else by tiles.
enum class WorkSharing { kAuto, kFrames, kTiles };
// "auto", "frames", "tiles"; InputError naming `field` otherwise.
WorkSharing parse_work_sharing(const std::string& text, const std::string& field = "--share");
const char* work_sharing_name(WorkSharing sharing);

// A frame, or this process's share of it, just rendered on this process.
struct FrameRendered {
  std::size_t frame = 0, frames = 0;
  double time_s = 0;
  double seconds = 0;  // staging and rendering, on this process
  int rank = 0, ranks = 1;
  bool by_tiles = false;
};

struct SequenceOptions {
  // Progress of this process's own rendering.
  std::function<void(const RenderProgress&)> progress;
  // On the process that rendered a frame (or its share), when it is done.
  std::function<void(const FrameRendered&)> on_rendered;
  // Called once the target masks are known, before the first frame is staged
  // (a caller can warn about sensors that do not see the target).
  std::function<void(const std::vector<TargetMask>&)> on_masks;
  // Called once for each distinct warning about a staged frame's inputs, on
  // the process that staged it: a sensor band reaching beyond the clouds'
  // spectral samples (scene/spectral_coverage.h).
  std::function<void(const std::string&)> on_warning;
  // Called with each frame when it is complete, in frame order (on rank 0 only).
  std::function<void(const RenderedFrame&)> on_frame;
  // Who shares the work, and how. Every process of the group calls
  // render_sequence with the same scene, times and sharing.
  const ProcessGroup* processes = &single_process();
  WorkSharing sharing = WorkSharing::kAuto;
  // Frames an earlier run completed (a resumed run, report/sequence_resume.h):
  // not rendered again; rank 0 gets each from load_completed in its turn and
  // measures and hands it on like a rendered one. The same on every process.
  std::vector<std::size_t> completed;
  std::function<RenderedFrame(std::size_t frame)> load_completed;
};

// "A:B:STEP" in seconds: A, A + STEP, … up to B inclusive (to 1e-9 of a
// step). Throws InputError naming `field` for anything else, a non-finite
// value, B < A, STEP <= 0 or more than 100 000 frames.
std::vector<double> parse_time_range(const std::string& text, const std::string& field = "--time");

// The target masks of every sensor (empty vector when no surface is a target).
std::vector<TargetMask> scene_target_masks(const Scene& scene);

// Renders `scene` at each of `times_s` (any order; frames are numbered in the
// order given). Leaves the scene staged at the last time this process
// rendered. Settings (method, threads, seed) are scene.settings. The result is
// complete on rank 0; the other processes get only times_s. A failure on any
// process ends the run on all of them (rank 0 throws the error, the others a
// PeerFailure) after rank 0 has had every frame before it.
SequenceResult render_sequence(Scene& scene, const std::vector<double>& times_s,
                               const SequenceOptions& options = {});

// One frame of the staged scene: every sensor through one prepared integrator.
// With a group of processes, every one of them calls it: each renders every
// N-th row and traces a share of the photons; rank 0 gets the whole frame,
// the others their share.
RenderedFrame render_frame(const Scene& scene, std::size_t index = 0, std::size_t frames = 1,
                           const std::function<void(const RenderProgress&)>& progress = {},
                           const ProcessGroup& processes = single_process());

}  // namespace obscura
