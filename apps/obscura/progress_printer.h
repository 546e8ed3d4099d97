#pragma once
// Progress of a render on stderr for runs longer than a second: a rewritten
// line on a terminal, an occasional line otherwise (logs, CI). One line per
// sensor and frame, labelled "tv frame 3/16 (t = 4 s)" in a sequence, and
// before a frame's sensors one for its photons where a photon method traces
// them ("photons frame 3/16 (t = 4 s)").
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <iostream>
#include <mutex>
#include <string>

#include "obscura/scene/scene.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura::cli {

class ProgressPrinter {
 public:
  ProgressPrinter(const Scene& scene, bool sequence)
      : scene_(scene), sequence_(sequence), tty_(isatty(STDERR_FILENO) != 0) {}

  // May be called from any thread.
  void update(const RenderProgress& p) {
    std::lock_guard lock(mutex_);
    if (p.frame != frame_ || p.sensor != sensor_) start(p);
    const double elapsed = seconds();
    if (elapsed < 1.0) return;
    const double interval = tty_ ? 0.25 : 5.0;
    const bool photons = p.sensor < 0;
    const double done = photons ? static_cast<double>(p.photons_done) : p.rows_done,
                 total = photons ? static_cast<double>(p.photons_total) : p.rows_total;
    if (done != total && elapsed - last_ < interval) return;
    last_ = elapsed;
    const double eta = done > 0 ? elapsed * (total - done) / done : 0.0;
    const std::string count = photons ? fmt::format("{:.3g}/{:.3g} photons", done, total)
                                      : fmt::format("{}/{} rows", p.rows_done, p.rows_total);
    std::cerr << fmt::format("{}render {}: {:5.1f}% ({}, {:.1f} s, ~{:.0f} s left){}",
                             tty_ ? "\r" : "", label_, total > 0 ? 100.0 * done / total : 100.0,
                             count, elapsed, eta, tty_ ? "" : "\n");
    printed_ = true;
  }
  // Ends the current line on a terminal.
  void finish() {
    std::lock_guard lock(mutex_);
    end_line();
  }

 private:
  void start(const RenderProgress& p) {
    end_line();
    frame_ = p.frame;
    sensor_ = p.sensor;
    const std::string name =
        p.sensor < 0 ? "photons" : scene_.sensors[static_cast<std::size_t>(p.sensor)].name;
    label_ = sequence_ ? fmt::format("{} frame {}/{} (t = {:.4g} s)", name, p.frame + 1, p.frames,
                                     p.time_s)
                       : name;
    start_ = std::chrono::steady_clock::now();
    last_ = -1e9;
  }
  void end_line() {
    if (printed_ && tty_) std::cerr << "\n";
    printed_ = false;
  }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  const Scene& scene_;
  bool sequence_;
  bool tty_;
  std::mutex mutex_;
  std::size_t frame_ = static_cast<std::size_t>(-1);
  int sensor_ = -1;
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  double last_ = -1e9;
  bool printed_ = false;
};

}  // namespace obscura::cli
