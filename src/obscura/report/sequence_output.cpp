#include "obscura/report/sequence_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/stale_temporaries.h"
#include "obscura/report/netcdf_render_output.h"
#include "obscura/report/render_output.h"
#include "obscura/report/screening_output.h"

namespace obscura {
namespace {

// The contact sheet shows at most this many frames, each cell a thumbnail of
// at most kSheetThumbnailPx a side: memory stays bounded however long the sequence.
constexpr std::size_t kSheetColumns = 10;
constexpr int kSheetThumbnailPx = 256;

// What a contact-sheet row shows of a band: radiance for visible/NIR bands,
// apparent temperature for thermal ones, transmittance for the others.
enum class SheetQuantity { kRadiance, kApparentTemperature, kTransmittance };

SheetQuantity sheet_quantity(const Band& band) {
  if (is_reflective_band(band)) return SheetQuantity::kRadiance;
  if (is_thermal_band(band)) return SheetQuantity::kApparentTemperature;
  return SheetQuantity::kTransmittance;
}

ContactSheetRow sheet_row(const Sensor& sensor, const Band& band, std::size_t columns) {
  ContactSheetRow row;
  row.label = sensor.name + " / " + band.name();
  switch (sheet_quantity(band)) {
    case SheetQuantity::kRadiance:
      row.quantity = "band radiance";
      row.units = "W m⁻² sr⁻¹";
      break;
    case SheetQuantity::kApparentTemperature:
      row.quantity = "apparent temperature";
      row.units = "K";
      break;
    case SheetQuantity::kTransmittance:
      row.quantity = "transmittance";
      row.colormap = Colormap::kGray;
      row.min = 0.0;
      row.max = 1.0;
      break;
  }
  row.cells.resize(columns);
  return row;
}

const std::vector<float>& sheet_values(const BandImage& b) {
  switch (sheet_quantity(b.band)) {
    case SheetQuantity::kRadiance:
      return b.radiance;
    case SheetQuantity::kApparentTemperature:
      return b.apparent_temperature;
    case SheetQuantity::kTransmittance:
      break;
  }
  return b.transmittance;
}

// Radiance rows are scaled to their 0.5th–99.5th percentiles: a few Monte
// Carlo outliers (or a sun glint) would otherwise set the scale and leave
// every other pixel dark. The labels give the scale used; values beyond it
// are drawn at its ends.
void scale_radiance_rows(ContactSheet& sheet) {
  for (ContactSheetRow& row : sheet.rows) {
    if (row.min || row.max || row.quantity != "band radiance") continue;
    std::vector<double> values;
    for (const ContactSheetCell& cell : row.cells)
      for (float v : cell.values)
        if (std::isfinite(v)) values.push_back(v);
    if (values.empty()) continue;
    std::sort(values.begin(), values.end());
    const double lo = percentile_of_sorted(values, 0.005), hi = percentile_of_sorted(values, 0.995);
    if (hi > lo) {
      row.min = lo;
      row.max = hi;
    }
  }
}

std::string time_series_csv(const std::vector<TimeSeriesRow>& rows) {
  std::string csv =
      "time_s,sensor,region,band,pixels,mean_radiance_W_m-2_sr-1,mean_transmittance,"
      "apparent_temperature_of_mean_K\n";
  for (const TimeSeriesRow& row : rows) {
    const RegionStats& r = row.stats;
    csv += fmt::format("{:.9g},{},{},{},{},{:.9g},{:.9g},{:.6f}\n", row.time_s, row.sensor,
                       r.region, r.band, r.pixels, r.mean_radiance, r.mean_transmittance,
                       r.mean_apparent_temperature);
  }
  return csv;
}

nlohmann::json sensor_frame_json(const SensorFrameStats& s, const std::string& exr) {
  nlohmann::json j = {{"name", s.sensor},
                      {"time_s", s.time_s},
                      {"width", s.width},
                      {"height", s.height},
                      {"exr", exr},
                      {"seconds", s.stats.seconds},
                      {"rays", s.stats.rays},
                      {"voxel_segments", s.stats.segments},
                      // Where the time went, s: staging the clouds at this time
                      // (once per frame, shared by its sensors), then photon
                      // tracing and their building (photon methods), and
                      // how the photons went: traced, meeting the medium,
                      // their real collisions (what their time is spent on).
                      {"staging_seconds", s.staging_seconds},
                      {"photons", s.stats.photons},
                      {"photon_trace_seconds", s.stats.photon_trace_seconds},
                      {"photon_build_seconds", s.stats.photon_build_seconds},
                      {"photons_traced", s.stats.photons_traced},
                      {"photons_colliding", s.stats.photons_colliding},
                      {"photon_collisions", s.stats.photon_collisions},
                      {"bands", nlohmann::json::array()}};
  for (const SensorFrameStats::BandFigures& b : s.bands)
    j["bands"].push_back({{"name", b.band.name()},
                          {"min_um", b.band.lo_um()},
                          {"max_um", b.band.hi_um()},
                          {"mean_radiance", b.mean_radiance},
                          {"mean_transmittance", b.mean_transmittance},
                          {"min_apparent_temperature", b.min_apparent_temperature_k},
                          {"max_apparent_temperature", b.max_apparent_temperature_k}});
  return j;
}

// A folder where a file is to be written would fail only after the render,
// with part of a frame on disk: refuse it before anything is rendered. Every
// output is an .exr, .png, .csv, .json or .nc file directly in the folder.
void check_no_folder_takes_an_output_name(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw InputError(dir.string(), "", "the output folder's name is taken by a file");
  fs::directory_iterator it(dir, ec);
  if (ec) return;  // missing: created when the first file is written
  for (const fs::directory_entry& e : it) {
    const std::string ext = e.path().extension().string();
    if (e.is_directory(ec) && (ext == ".exr" || ext == ".png" || ext == ".csv" || ext == ".json" ||
                               ext == ".nc" || ext == ".img" || ext == ".hdr"))
      throw InputError(e.path().string(), "",
                       "is a folder where obscura writes a file: move it or choose another "
                       "output folder");
  }
}

}  // namespace

SequenceWriter::SequenceWriter(std::filesystem::path dir, const Scene& scene,
                               std::vector<double> times_s, bool sequence, Provenance provenance,
                               const std::string& title)
    : dir_(std::move(dir)),
      scene_(scene),
      times_s_(std::move(times_s)),
      sequence_(sequence),
      provenance_(std::move(provenance)),
      provenance_text_(provenance_.to_string()) {
  if (sequence_) sheet_frames_ = contact_sheet_frames(times_s_.size(), kSheetColumns);
  sheet_.title = fmt::format("{} · {} frames, t = {:g}…{:g} s", title, times_s_.size(),
                             times_s_.front(), times_s_.back());
  for (std::size_t k : sheet_frames_) sheet_.times_s.push_back(times_s_[k]);
  for (const Sensor& sensor : scene.sensors)
    for (const Band& band : sensor.bands)
      sheet_.rows.push_back(sheet_row(sensor, band, sheet_frames_.size()));
  check_no_folder_takes_an_output_name(dir_);
  remove_stale_temporaries(dir_);
  summary_ = {{"provenance", provenance_.to_json()},
              {"scene", scene.source},
              {"threads", resolve_thread_count(scene.settings.threads)},
              {"times_s", times_s_},
              {"sensors", nlohmann::json::array()}};
  if (has_output_format(scene.outputs, OutputFormat::kNetcdf))
    netcdf_ = std::make_unique<NetcdfRenderOutput>(dir_ / kNetcdfRenderFile, scene, times_s_,
                                                   provenance_, title);
}

SequenceWriter::~SequenceWriter() = default;

void SequenceWriter::write_frame(const RenderedFrame& frame) {
  const std::string suffix = sequence_ ? fmt::format("_f{:04d}", frame.index) : "";
  const auto column = std::find(sheet_frames_.begin(), sheet_frames_.end(), frame.index);
  std::size_t row = 0;
  for (const SensorImage& image : frame.images) {
    const auto files = write_sensor_image(dir_, image, provenance_, suffix, frame.time_s);
    written_.insert(written_.end(), files.begin(), files.end());
    if (has_output_format(scene_.outputs, OutputFormat::kEnvi)) {
      const auto cube = write_sensor_radiance_cube(dir_, image, suffix, frame.time_s);
      written_.insert(written_.end(), cube.begin(), cube.end());
    }
    exr_files_.push_back(files.front().string());
    for (const BandImage& b : image.bands) {
      ContactSheetRow& r = sheet_.rows[row++];
      if (column != sheet_frames_.end())
        r.cells[column - sheet_frames_.begin()] =
            contact_sheet_thumbnail(image.width, image.height, sheet_values(b), kSheetThumbnailPx);
    }
  }
  if (netcdf_) netcdf_->write_frame(frame);
  frame_files_ = written_.size();
  frames_done_.push_back(frame.index);
}

void SequenceWriter::record_resumed(const std::vector<std::size_t>& frames) {
  summary_["resumed_frames"] = frames;
}

void SequenceWriter::finish_failed(const std::string& error) {
  netcdf_kept_ = netcdf_ && netcdf_->finish_failed(error);
  if (netcdf_kept_) written_.push_back(netcdf_->path());
  summary_["failed"] = {
      {"error", error}, {"frames_completed", frames_done_}, {"frames_planned", times_s_.size()}};
  summary_["outputs"] = nlohmann::json::array();
  for (const auto& p : written_) summary_["outputs"].push_back(p.string());
  const auto summary_path = dir_ / "summary.json";
  write_text_file_atomic(summary_path, summary_.dump(2) + "\n");
  written_.push_back(summary_path);
}

void SequenceWriter::write_contact_sheet() {
  scale_radiance_rows(sheet_);
  write_contact_sheet_png(dir_ / "contact_sheet.png", sheet_, provenance_text_);
  written_.push_back(dir_ / "contact_sheet.png");
}

void SequenceWriter::write_metrics(const SequenceResult& result) {
  const MetricsSettings& settings = scene_.metrics;
  write_text_file_atomic(dir_ / "metrics.csv", screening_metrics_csv(result.metrics));
  written_.push_back(dir_ / "metrics.csv");
  write_text_file_atomic(
      dir_ / "metrics.json",
      screening_metrics_json(provenance_.to_json(), settings, result.reference_time_s, result.masks,
                             result.metrics, result.series)
              .dump(2) +
          "\n");
  written_.push_back(dir_ / "metrics.json");
  metrics_text_ = screening_summary_text(result.series, settings, result.reference_time_s);
  if (sequence_) {
    const ScreeningPlotFiles plots =
        write_screening_plots(dir_, result.metrics, settings, provenance_text_);
    written_.insert(written_.end(), plots.written.begin(), plots.written.end());
    for (const std::string& why : plots.skipped) metrics_text_ += "  (not written: " + why + ")\n";
    for (const TargetMask& m : result.masks) {
      const auto path = dir_ / ("target_mask_" + file_safe_name(m.sensor) + ".png");
      write_target_mask_png(path, m, provenance_text_);
      written_.push_back(path);
    }
  }
  summary_["metrics"] = {{"settings", screening_settings_json(settings, result.reference_time_s)},
                         {"targets", target_masks_json(result.masks)},
                         {"series", screening_series_json(result.series)}};
}

void SequenceWriter::finish(const SequenceResult& result) {
  for (std::size_t i = 0; i < result.sensor_frames.size(); ++i)
    summary_["sensors"].push_back(sensor_frame_json(
        result.sensor_frames[i], i < exr_files_.size() ? exr_files_[i] : std::string()));
  if (sequence_) {
    write_text_file_atomic(dir_ / "time_series.csv", time_series_csv(result.time_series));
    written_.push_back(dir_ / "time_series.csv");
    write_contact_sheet();
  }
  if (result.with_metrics) write_metrics(result);
  if (netcdf_) {
    netcdf_->finish(result);
    written_.push_back(netcdf_->path());
  }
  summary_["units"] = {
      {"radiance", "W m-2 sr-1"}, {"apparent_temperature", "K"}, {"transmittance", "1"}};
  const auto summary_path = dir_ / "summary.json";
  write_text_file_atomic(summary_path, summary_.dump(2) + "\n");
  written_.push_back(summary_path);
  summary_["outputs"] = nlohmann::json::array();
  for (const auto& p : written_) summary_["outputs"].push_back(p.string());
}

std::string sequence_summary_text(const SequenceWriter& writer) {
  std::string text;
  for (const auto& s : writer.summary()["sensors"]) {
    text += fmt::format("sensor {} at t = {} s ({}x{} px, {:.2f} s, {} rays)\n",
                        s["name"].get<std::string>(), s["time_s"].get<double>(),
                        s["width"].get<int>(), s["height"].get<int>(), s["seconds"].get<double>(),
                        s["rays"].get<std::uint64_t>());
    for (const auto& b : s["bands"])
      text += fmt::format(
          "  {:<10} mean radiance {:.5g} W m⁻² sr⁻¹, mean transmittance {:.4f}, "
          "apparent temperature {:.2f}–{:.2f} K\n",
          b["name"].get<std::string>(), b["mean_radiance"].get<double>(),
          b["mean_transmittance"].get<double>(), b["min_apparent_temperature"].get<double>(),
          b["max_apparent_temperature"].get<double>());
  }
  text += writer.metrics_text();
  const auto& written = writer.written();
  text += fmt::format("wrote {} files to {}/\n", written.size(), writer.dir().string());
  if (written.size() <= 16) {
    for (const auto& p : written) text += "  " + p.filename().string() + "\n";
  } else {
    // The per-frame files in one line, then every file of the whole run.
    const std::size_t frame_files = writer.frame_file_count();
    text += fmt::format("  {} … {} ({} files of frames)\n", written.front().filename().string(),
                        written[frame_files - 1].filename().string(), frame_files);
    for (std::size_t i = frame_files; i < written.size(); ++i)
      text += "  " + written[i].filename().string() + "\n";
  }
  return text;
}

}  // namespace obscura
