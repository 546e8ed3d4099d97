#include "obscura/sequence/sequence_runner.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "obscura/core/byte_stream.h"
#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/interrupt.h"
#include "obscura/core/time_steps.h"
#include "obscura/film/sensor_image_rows.h"
#include "obscura/gpu/frame_integrator.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/spectral_coverage.h"
#include "obscura/sequence/frame_message.h"

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
  if (time_step_count(a, b, step) > 100001) throw bad("'{}' gives more than 100000 frames");
  return time_steps(a, b, step);
}

std::vector<TargetMask> scene_target_masks(const Scene& scene) {
  std::vector<TargetMask> masks;
  if (!scene_has_target(scene)) return masks;
  for (const Sensor& sensor : scene.sensors)
    masks.push_back(compute_target_mask(scene, sensor, scene.metrics.background_margin_px,
                                        scene.settings.threads));
  return masks;
}

WorkSharing parse_work_sharing(const std::string& text, const std::string& field) {
  for (WorkSharing w : {WorkSharing::kAuto, WorkSharing::kFrames, WorkSharing::kTiles})
    if (text == work_sharing_name(w)) return w;
  throw InputError("", field, "'" + text + "' is not one of auto, frames, tiles");
}

const char* work_sharing_name(WorkSharing sharing) {
  switch (sharing) {
    case WorkSharing::kFrames:
      return "frames";
    case WorkSharing::kTiles:
      return "tiles";
    default:
      return "auto";
  }
}

RenderedFrame render_frame(const Scene& scene, std::size_t index, std::size_t frames,
                           const std::function<void(const RenderProgress&)>& progress,
                           const ProcessGroup& processes) {
  RenderedFrame frame;
  frame.index = index;
  frame.time_s = scene.time_s;
  const FrameSpectra spectra = frame_spectra(scene);
  PreparationProgress preparation;
  if (progress)
    preparation = [&](long long done, long long total) {
      RenderProgress p{index, frames, scene.time_s, -1, 0, 0};
      p.photons_done = done;
      p.photons_total = total;
      progress(p);
    };
  const std::unique_ptr<Integrator> integrator =
      make_frame_integrator(scene, spectra, processes, preparation);
  for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
    RenderOptions options;
    options.row_offset = processes.rank();
    options.row_stride = processes.size();
    if (progress)
      options.progress = [&](int done, int total) {
        progress({index, frames, scene.time_s, static_cast<int>(s), done, total});
      };
    SensorImage image = render_sensor(scene, static_cast<int>(s), *integrator, spectra, options);
    if (processes.size() > 1) {
      // Rank 0 takes every other process's rows into its image.
      const std::vector<std::string> shares =
          processes.gather(encode_image_rows(image, options.row_offset, options.row_stride));
      for (std::size_t r = 1; r < shares.size(); ++r) decode_image_rows(shares[r], image);
    }
    frame.images.push_back(std::move(image));
  }
  return frame;
}

namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The frame loop, on every process of the group.
class SequenceRun {
 public:
  SequenceRun(Scene& scene, const std::vector<double>& times_s, const SequenceOptions& options)
      : scene_(scene), times_(times_s), options_(options), group_(*options.processes) {
    result_.times_s = times_s;
  }

  SequenceResult run() {
    // Target masks once, on rank 0 (surfaces do not move).
    run_together(group_, [&] {
      if (group_.is_root()) result_.masks = scene_target_masks(scene_);
    });
    result_.with_metrics = !result_.masks.empty();
    if (group_.is_root() && options_.on_masks) options_.on_masks(result_.masks);
    // The frames to render: all but those an earlier run completed.
    completed_.assign(times_.size(), false);
    for (std::size_t f : options_.completed) completed_.at(f) = true;
    for (std::size_t f = 0; f < times_.size(); ++f)
      if (!completed_[f]) to_render_.push_back(f);
    OBSCURA_CHECK(to_render_.size() == times_.size() || options_.load_completed);
    const std::size_t ranks = static_cast<std::size_t>(group_.size());
    const bool by_frames = options_.sharing == WorkSharing::kFrames ||
                           (options_.sharing == WorkSharing::kAuto && to_render_.size() >= ranks);
    if (ranks == 1)
      for (std::size_t f : to_render_) frame_alone(f);
    else if (by_frames)
      frames_by_rank();
    else
      for (std::size_t f : to_render_) frame_by_tiles(f);
    run_together(group_, [&] { take_completed_before(times_.size()); });
    if (result_.with_metrics) {
      result_.reference_time_s = screening_reference_time_s(scene_);
      result_.series =
          summarize_screening(result_.metrics, scene_.metrics, result_.reference_time_s);
    }
    return std::move(result_);
  }

 private:
  // Rank 0: the completed frames before frame f, read back, in their turn.
  void take_completed_before(std::size_t f) {
    if (!group_.is_root()) return;
    while (next_ < f) {
      OBSCURA_CHECK_MSG(completed_[next_], "a frame to render was skipped");
      take(options_.load_completed(next_));  // take() moves next_ on
    }
  }

  void warn_once(const std::vector<std::string>& warnings) {
    if (!options_.on_warning) return;
    for (const std::string& w : warnings)
      if (warned_.insert(w).second) options_.on_warning(w);
  }

  // Stages frame f and renders it, or this process's share of it.
  RenderedFrame stage_and_render(std::size_t f, const ProcessGroup& processes) {
    throw_if_interrupted();
    const auto start = std::chrono::steady_clock::now();
    stage_scene(scene_, times_[f]);
    warn_once(scene_.warnings);
    warn_once(bands_beyond_cloud_samples(scene_));
    const double staging_s = seconds_since(start);
    RenderedFrame frame = render_frame(scene_, f, times_.size(), options_.progress, processes);
    frame.staging_seconds = staging_s;
    if (options_.on_rendered)
      options_.on_rendered({f, times_.size(), times_[f], seconds_since(start), group_.rank(),
                            group_.size(), processes.size() > 1});
    return frame;
  }

  // Frame f on this process alone.
  void frame_alone(std::size_t f) {
    RenderedFrame frame = stage_and_render(f, single_process());
    take_completed_before(f);
    take(std::move(frame));
  }

  // The message for a frame a process rendered: its rank, then a failure or
  // the frame.
  std::string outcome_message(const std::optional<RenderedFrame>& frame,
                              const std::exception_ptr& failure) const {
    ByteWriter out;
    out.put<std::int32_t>(group_.rank());
    out.put_string(encode_failure(failure));
    out.put_string(frame && !failure ? encode_frame(*frame) : std::string());
    return out.take();
  }

  // By frames: every process draws the next frame to render from a shared
  // counter (to_render_[k] for the k it draws), so a process that finishes a
  // cheap frame takes the next one and frames of unequal cost leave nobody
  // idle; each sends its frame to rank 0 as it completes (tag k) and stops
  // drawing at its first failure. Rank 0 renders the frames it draws and
  // between them takes, in frame order, whatever has arrived. Once any
  // failure is known it ends the drawing (adding past the end), waits for
  // every frame already drawn, and takes those before the first failure in
  // frame order; every message sent is received, so every send completes.
  // Which process rendered a frame does not change its pixels.
  void frames_by_rank() {
    const std::size_t n = to_render_.size();
    std::unique_ptr<SharedCounter> counter = group_.make_counter();
    if (!group_.is_root()) {
      for (std::size_t k; (k = counter->fetch_add(1)) < n;) {
        std::optional<RenderedFrame> frame;
        std::exception_ptr failure;
        try {
          frame = stage_and_render(to_render_[k], single_process());
        } catch (...) {
          failure = std::current_exception();
        }
        group_.send(0, static_cast<int>(k), outcome_message(frame, failure));
        if (failure) break;
      }
      group_.finish_sends();
      counter.reset();
      share_failure(group_, nullptr);  // rank 0 has the failure, if any
      return;
    }
    // Rank 0. Outcomes of the frames it drew, and of the others as they arrive.
    struct Outcome {
      std::optional<RenderedFrame> frame;
      std::exception_ptr failure;
    };
    std::map<std::size_t, Outcome> own;
    std::vector<bool> drawn_here(n, false);
    std::exception_ptr stop;     // the first failure in frame order
    bool failure_known = false;  // some failure has been seen: draw no more
    std::size_t next = 0;        // to_render_[next] is the next to take
    std::size_t drawn = n;       // frames drawn by anyone (all, unless a failure ended it)
    // Takes to_render_[next] if its outcome is here (waiting when `wait`).
    const auto take_next = [&](bool wait) {
      Outcome o;
      if (drawn_here[next]) {
        const auto it = own.find(next);
        if (it == own.end()) return false;  // not rendered yet
        o = std::move(it->second);
        own.erase(it);
      } else {
        std::optional<std::string> message =
            wait ? std::optional<std::string>(group_.receive(static_cast<int>(next)))
                 : group_.try_receive(static_cast<int>(next));
        if (!message) return false;
        ByteReader in(*message);
        const int from = in.get<std::int32_t>();
        const std::string failure = in.get_string();
        if (!failure.empty())
          o.failure = decode_failure(failure, from);
        else if (!stop)
          o.frame = decode_frame(in.get_string(), scene_);
      }
      if (o.failure) {
        failure_known = true;
        if (!stop) stop = o.failure;
      } else if (!stop) {
        try {
          take_completed_before(to_render_[next]);
          take(std::move(*o.frame));
        } catch (...) {
          stop = std::current_exception();
          failure_known = true;
        }
      }
      ++next;
      return true;
    };
    while (!failure_known) {
      const std::size_t k = counter->fetch_add(1);
      if (k >= n) break;
      drawn_here[k] = true;
      Outcome& o = own[k];
      try {
        o.frame = stage_and_render(to_render_[k], single_process());
      } catch (...) {
        o.failure = std::current_exception();
        failure_known = true;
      }
      while (next < n && take_next(false)) {
      }
    }
    // After a failure nobody draws again: the frames drawn so far are all
    // that will come.
    if (failure_known) drawn = std::min<std::size_t>(counter->fetch_add(n), n);
    while (next < drawn) take_next(true);
    group_.finish_sends();
    counter.reset();
    share_failure(group_, stop);
  }

  // Frame f, every process rendering its rows; rank 0 takes it.
  void frame_by_tiles(std::size_t f) {
    // Staging fails (a corrupt keyframe) on every process alike: shared, so
    // that rank 0 reports it once.
    std::optional<RenderedFrame> frame;
    std::exception_ptr failure;
    try {
      frame = stage_and_render(f, group_);
    } catch (...) {
      failure = std::current_exception();
    }
    share_failure(group_, failure);
    std::exception_ptr stop;
    if (group_.is_root()) try {
        take_completed_before(f);
        take(std::move(*frame));
      } catch (...) {
        stop = std::current_exception();
      }
    share_failure(group_, stop);
  }

  // Rank 0: measures a whole frame and hands it on.
  void take(RenderedFrame frame) {
    const double t = frame.time_s;
    for (std::size_t s = 0; s < frame.images.size(); ++s) {
      const SensorImage& image = frame.images[s];
      result_.sensor_frames.push_back(frame_stats(image, t, frame.staging_seconds));
      for (RegionStats& r : region_stats(image, scene_.regions, scene_.settings))
        result_.time_series.push_back({t, image.sensor, std::move(r)});
      if (result_.with_metrics) {
        auto rows = screening_metrics(image, result_.masks[s], scene_.metrics, scene_.settings, t);
        result_.metrics.insert(result_.metrics.end(), rows.begin(), rows.end());
      }
    }
    if (options_.on_frame) options_.on_frame(frame);
    next_ = frame.index + 1;
  }

  Scene& scene_;
  const std::vector<double>& times_;
  const SequenceOptions& options_;
  const ProcessGroup& group_;
  SequenceResult result_;
  std::vector<bool> completed_;         // per frame: an earlier run completed it
  std::vector<std::size_t> to_render_;  // the frames to render, in order
  std::size_t next_ = 0;                // rank 0: the next frame to take
  std::set<std::string> warned_;        // warnings already given
};

}  // namespace

SequenceResult render_sequence(Scene& scene, const std::vector<double>& times_s,
                               const SequenceOptions& options) {
  return SequenceRun(scene, times_s, options).run();
}

}  // namespace obscura
