#pragma once
// render.nc: every frame, sensor and band of a render in one NetCDF-CF
// (CF-1.10, netCDF-4) file that xarray.open_dataset reads as one Dataset
// (docs/formats.md, "NetCDF render output", lists every dimension, variable
// and attribute). Sensors may differ in image size and bands, so each sensor
// S has its own dimensions band_S, y_S, x_S and variables radiance_S(time,
// band_S, y_S, x_S), transmittance_S, apparent_temperature_S,
// radiance_stderr_S (Monte Carlo methods) and, with a target, target_mask_S
// and the screening metrics over time (time, band_S); `time` is shared.
//
// The file is written as the frames arrive (write_frame: one record of the
// unlimited time dimension per frame, at the frame's index), under a
// temporary name, and renamed into place by finish(), which adds the target
// masks and metrics. After a failure part-way, finish_failed() keeps it only
// when the frames written are exactly frames 0 … k−1 (so every record of the
// file is a complete frame) and records the failure in its global
// attributes; otherwise the temporary is removed.
#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "obscura/io/netcdf_output_file.h"
#include "obscura/io/provenance.h"
#include "obscura/sequence/sequence_runner.h"

namespace obscura {

// The file name in the output folder.
inline constexpr const char* kNetcdfRenderFile = "render.nc";

// The suffix of a sensor's dimensions and variables: its name with every
// character but A–Z, a–z, 0–9 and '_' replaced by '_' ("seeker-2" → "seeker_2").
std::string netcdf_sensor_suffix(const std::string& sensor_name);

class NetcdfRenderOutput {
 public:
  // Creates the temporary file and defines the time axis and every sensor's
  // dimensions, coordinates and image variables. `times_s`: the frames
  // planned, in frame order; `title`: what was rendered (the scene file's
  // name). Throws InputError when two sensor names give the same suffix or an
  // image would not fit in memory, Error when the file cannot be written.
  NetcdfRenderOutput(const std::filesystem::path& path, const Scene& scene,
                     std::vector<double> times_s, const Provenance& provenance,
                     const std::string& title);
  ~NetcdfRenderOutput();
  NetcdfRenderOutput(const NetcdfRenderOutput&) = delete;
  NetcdfRenderOutput& operator=(const NetcdfRenderOutput&) = delete;

  // The frame's time and images into record frame.index.
  void write_frame(const RenderedFrame& frame);
  // The target masks and metrics (with a target), the run's status; then the
  // rename. `result` must be of the frames written.
  void finish(const SequenceResult& result);
  // After a failure: true when the file was kept (see above), false when it
  // was removed. Never throws: a failure while finishing removes the file.
  bool finish_failed(const std::string& error) noexcept;

  const std::filesystem::path& path() const { return path_; }

 private:
  struct SensorVariables;
  void define_sensor(std::size_t index, const Sensor& sensor);
  void write_metrics(const SequenceResult& result);

  std::filesystem::path path_;
  const Scene& scene_;
  std::vector<double> times_s_;
  std::unique_ptr<NetcdfOutputFile> file_;
  int time_dim_ = -1, time_var_ = -1;
  std::vector<SensorVariables> sensors_;
  std::vector<std::size_t> frames_written_;
};

}  // namespace obscura
