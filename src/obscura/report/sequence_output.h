#pragma once
// Writes what `obscura render` produces for a frame sequence
// (sequence/sequence_runner.h) into an output folder (docs/formats.md,
// "Render outputs"):
//  * per frame and sensor, the multi-channel EXR and the PNG previews
//    (report/render_output.h), numbered "_f0003" in a sequence;
//  * for a sequence, time_series.csv (region means per frame, sensor, region
//    and band) and contact_sheet.png (a few frames of every sensor and band);
//  * with a target, metrics.csv and metrics.json, and for a sequence the
//    metric plots and the target masks (report/screening_output.h);
//  * summary.json: provenance, the scene, per frame and sensor the figures and
//    timings, the screening summary, units;
//  * when the scene's outputs name netcdf (scene/output_formats.h), render.nc:
//    every frame, sensor and band in one NetCDF-CF file
//    (report/netcdf_render_output.h), written frame by frame.
// Frames are written as the runner hands them over (write_frame), the rest by
// finish(), or by finish_failed() when a frame fails. Every file goes through
// an AtomicFile (temporary name, rename); temporaries that killed runs left in
// the folder are removed when a writer is made (io/stale_temporaries.h).
#include <cstddef>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "obscura/io/provenance.h"
#include "obscura/report/contact_sheet.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura {

class NetcdfRenderOutput;

class SequenceWriter {
 public:
  // `sequence`: a --time run (numbered frames and the sequence's own files);
  // else one frame. `title` heads the contact sheet (e.g. the scene file's name).
  SequenceWriter(std::filesystem::path dir, const Scene& scene, std::vector<double> times_s,
                 bool sequence, Provenance provenance, const std::string& title);
  ~SequenceWriter();

  // The frame's files, and its thumbnails for the contact sheet.
  void write_frame(const RenderedFrame& frame);
  // The time series, contact sheet, metrics, plots, masks and summary.json.
  void finish(const SequenceResult& result);
  // After a failure part-way: summary.json records the error and the frames
  // that completed (their files stay: each was written whole, atomically);
  // render.nc stays when its records are exactly frames 0 … k−1, and records
  // the failure too (report/netcdf_render_output.h).
  void finish_failed(const std::string& error);
  // Whether finish_failed() kept render.nc.
  bool netcdf_kept() const { return netcdf_kept_; }
  // Records in summary.json that `frames` were read back from an earlier run
  // (report/sequence_resume.h), not rendered by this one.
  void record_resumed(const std::vector<std::size_t>& frames);
  // The frames written so far, in order.
  const std::vector<std::size_t>& frames_done() const { return frames_done_; }

  const std::filesystem::path& dir() const { return dir_; }
  // summary.json's content, plus "outputs" (every file written).
  const nlohmann::json& summary() const { return summary_; }
  const std::vector<std::filesystem::path>& written() const { return written_; }
  // How many of written() are frame files (they come first).
  std::size_t frame_file_count() const { return frame_files_; }
  // The screening summary for a terminal ("" without a target).
  const std::string& metrics_text() const { return metrics_text_; }

 private:
  void write_metrics(const SequenceResult& result);
  void write_contact_sheet();

  std::filesystem::path dir_;
  const Scene& scene_;
  std::vector<double> times_s_;
  bool sequence_;
  Provenance provenance_;
  std::string provenance_text_;
  std::vector<std::size_t> sheet_frames_;
  ContactSheet sheet_;
  std::vector<std::string> exr_files_;  // per frame and sensor, in order
  nlohmann::json summary_;
  std::vector<std::filesystem::path> written_;
  std::size_t frame_files_ = 0;
  std::vector<std::size_t> frames_done_;
  std::string metrics_text_;
  std::unique_ptr<NetcdfRenderOutput> netcdf_;  // null unless the outputs name netcdf
  bool netcdf_kept_ = false;
};

// What `obscura render` prints when it is done: per frame and sensor the
// image size, time, rays and per band the mean radiance, transmittance and
// apparent-temperature range; the screening summary; the files written.
std::string sequence_summary_text(const SequenceWriter& writer);

}  // namespace obscura
