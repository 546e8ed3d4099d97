// `obscura render`: renders every sensor of a scene into an output folder.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "obscura/analysis/region_stats.h"
#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/io/atomic_file.h"
#include "obscura/report/contact_sheet.h"
#include "obscura/io/provenance.h"
#include "obscura/report/render_output.h"
#include "obscura/report/screening_output.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/scene.h"

namespace obscura::cli {
namespace {

// Progress on stderr for runs longer than a second: a rewritten line on a
// terminal, an occasional line otherwise (logs, CI).
class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string label)
      : label_(std::move(label)),
        start_(std::chrono::steady_clock::now()),
        tty_(isatty(STDERR_FILENO) != 0) {}

  void update(int done, int total) {
    std::lock_guard lock(mutex_);
    const double elapsed = seconds();
    if (elapsed < 1.0) return;
    const double interval = tty_ ? 0.25 : 5.0;
    if (done != total && elapsed - last_ < interval) return;
    last_ = elapsed;
    const double eta = done > 0 ? elapsed * (total - done) / done : 0.0;
    std::cerr << fmt::format("{}render {}: {:5.1f}% ({}/{} rows, {:.1f} s, ~{:.0f} s left){}",
                             tty_ ? "\r" : "", label_, 100.0 * done / total, done, total, elapsed,
                             eta, tty_ ? "" : "\n");
    printed_ = true;
  }
  void finish() {
    if (printed_ && tty_) std::cerr << "\n";
  }
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::string label_;
  std::chrono::steady_clock::time_point start_;
  bool tty_;
  std::mutex mutex_;
  double last_ = -1e9;
  bool printed_ = false;
};

// "A:B:STEP" in seconds: A, A + STEP, … up to B inclusive (to 1e-9 of a step).
std::vector<double> parse_time_range(const std::string& text) {
  std::vector<double> v;
  std::size_t pos = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t colon = i < 2 ? text.find(':', pos) : text.size();
    if (colon == std::string::npos)
      throw InputError("", "--time", fmt::format("'{}' is not A:B:STEP in seconds", text));
    try {
      std::size_t used = 0;
      const std::string part = text.substr(pos, colon - pos);
      v.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw InputError("", "--time", fmt::format("'{}' is not A:B:STEP in seconds", text));
    }
    pos = colon + 1;
  }
  const double a = v[0], b = v[1], step = v[2];
  if (!(std::isfinite(a) && std::isfinite(b) && std::isfinite(step) && step > 0 && b >= a))
    throw InputError("", "--time", fmt::format("'{}' needs finite A <= B and STEP > 0", text));
  const double n = std::floor((b - a) / step + 1e-9);
  if (n > 100000)
    throw InputError("", "--time", fmt::format("'{}' gives more than 100000 frames", text));
  std::vector<double> times;
  for (int k = 0; k <= static_cast<int>(n); ++k) times.push_back(a + k * step);
  return times;
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
}

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

}  // namespace

Command add_render_command(CLI::App& app, const Invocation& invocation) {
  auto* cmd = app.add_subcommand("render", "Render every sensor of a scene file");
  struct Options {
    std::string scene;
    std::string output;
    std::optional<int> threads;
    std::optional<std::uint64_t> seed;
    double at = 0.0;
    std::string time_range;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("scene", o->scene, "Scene file (JSON, docs/formats.md)")->required();
  cmd->add_option("-o,--output", o->output, "Output folder (created if missing)")->required();
  cmd->add_option("--threads", o->threads, "Worker threads (default: the scene's, 0 = all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--seed", o->seed, "Random seed for pixel jitter (default: the scene's)");
  auto* at = cmd->add_option("--at", o->at, "Scene time to render, seconds (default 0)");
  cmd->add_option("--time", o->time_range,
                  "Render a frame sequence at times A:B:STEP (seconds): numbered EXR and PNG files "
                  "per frame, time_series.csv with region means, contact_sheet.png, and with a "
                  "target surface screening metrics and their plots (docs/metrics.md)")
      ->excludes(at);
  cmd->add_flag("--json", o->json, "Print a JSON summary on stdout");
  return {
      cmd, [o, invocation]() {
        // Cheap checks of the command line first, before reading any file.
        if (!std::isfinite(o->at)) throw InputError("", "--at", "must be a finite time in seconds");
        const bool sequence = !o->time_range.empty();
        const std::vector<double> times =
            sequence ? parse_time_range(o->time_range) : std::vector<double>{o->at};
        Scene scene = load_scene(o->scene);
        if (o->threads) scene.settings.threads = *o->threads;
        if (o->seed) scene.settings.seed = *o->seed;
        const Provenance prov =
            make_provenance(invocation.command_line, scene.settings.seed, scene.input_files);
        const std::filesystem::path dir(o->output);
        nlohmann::json summary = {{"provenance", prov.to_json()},
                                  {"scene", scene.source},
                                  {"threads", resolve_thread_count(scene.settings.threads)},
                                  {"times_s", times},
                                  {"sensors", nlohmann::json::array()}};
        std::vector<std::filesystem::path> written;
        const std::string prov_text = prov.to_string();
        // Screening metrics need a target; its masks are computed once per
        // sensor (surfaces do not move).
        const bool with_metrics = scene_has_target(scene);
        std::vector<TargetMask> masks;
        std::vector<ScreeningMetrics> metric_rows;
        if (with_metrics) {
          std::string blind;
          for (const Sensor& sensor : scene.sensors) {
            masks.push_back(compute_target_mask(scene, sensor, scene.metrics.background_margin_px,
                                                scene.settings.threads));
            if (masks.back().empty()) blind += (blind.empty() ? "" : ", ") + sensor.name;
          }
          if (!blind.empty())
            std::cerr << fmt::format(
                "obscura: warning: no target pixel in view of sensor {}: "
                "its screening metrics are empty (null)\n",
                blind);
        }
        // The contact sheet keeps thumbnails of a few frames only.
        const std::vector<std::size_t> sheet_frames =
            sequence ? contact_sheet_frames(times.size(), kSheetColumns)
                     : std::vector<std::size_t>{};
        ContactSheet sheet;
        sheet.title = fmt::format("{} · {} frames, t = {:g}…{:g} s",
                                  std::filesystem::path(o->scene).filename().string(), times.size(),
                                  times.front(), times.back());
        for (std::size_t k : sheet_frames) sheet.times_s.push_back(times[k]);
        for (const Sensor& sensor : scene.sensors)
          for (const Band& band : sensor.bands)
            sheet.rows.push_back(sheet_row(sensor, band, sheet_frames.size()));
        std::string csv =
            "time_s,sensor,region,band,pixels,mean_radiance_W_m-2_sr-1,mean_transmittance,"
            "apparent_temperature_of_mean_K\n";
        for (std::size_t f = 0; f < times.size(); ++f) {
          const auto staging_start = std::chrono::steady_clock::now();
          stage_scene(scene, times[f]);
          const double staging_s =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - staging_start)
                  .count();
          const std::string suffix = sequence ? fmt::format("_f{:04d}", f) : "";
          const auto column = std::find(sheet_frames.begin(), sheet_frames.end(), f);
          std::size_t sheet_row_index = 0;
          for (std::size_t si = 0; si < scene.sensors.size(); ++si) {
            const Sensor& sensor = scene.sensors[si];
            const std::string label = sequence
                                          ? fmt::format("{} frame {}/{} (t = {:.4g} s)",
                                                        sensor.name, f + 1, times.size(), times[f])
                                          : sensor.name;
            ProgressPrinter progress(label);
            RenderOptions options;
            options.threads = scene.settings.threads;
            options.seed = scene.settings.seed;
            options.progress = [&](int done, int total) { progress.update(done, total); };
            const SensorImage image = render_sensor(scene, sensor, options);
            progress.finish();
            const auto files = write_sensor_image(dir, image, prov, suffix, times[f]);
            written.insert(written.end(), files.begin(), files.end());
            if (with_metrics) {
              auto rows = screening_metrics(image, masks[si], scene.metrics,
                                            scene.settings.spectral_nodes_per_band, times[f]);
              metric_rows.insert(metric_rows.end(), rows.begin(), rows.end());
            }
            for (const BandImage& b : image.bands) {
              ContactSheetRow& row = sheet.rows[sheet_row_index++];
              if (column != sheet_frames.end())
                row.cells[column - sheet_frames.begin()] = contact_sheet_thumbnail(
                    image.width, image.height, sheet_values(b), kSheetThumbnailPx);
            }
            for (const RegionStats& r :
                 region_stats(image, scene.regions, scene.settings.spectral_nodes_per_band))
              csv += fmt::format("{:.9g},{},{},{},{},{:.9g},{:.9g},{:.6f}\n", times[f], sensor.name,
                                 r.region, r.band, r.pixels, r.mean_radiance, r.mean_transmittance,
                                 r.mean_apparent_temperature);
            nlohmann::json s = {{"name", sensor.name},
                                {"time_s", times[f]},
                                {"width", image.width},
                                {"height", image.height},
                                {"exr", files.front().string()},
                                {"seconds", image.stats.seconds},
                                {"rays", image.stats.rays},
                                {"voxel_segments", image.stats.segments},
                                // Where the time went, s: staging the clouds at this
                                // time (once per frame, shared by its sensors), then
                                // photon tracing and kd-trees (photon map only).
                                {"staging_seconds", staging_s},
                                {"photons", image.stats.photons},
                                {"photon_trace_seconds", image.stats.photon_trace_seconds},
                                {"photon_build_seconds", image.stats.photon_build_seconds},
                                {"bands", nlohmann::json::array()}};
            for (const BandImage& b : image.bands) {
              const auto [tmin, tmax] =
                  std::minmax_element(b.apparent_temperature.begin(), b.apparent_temperature.end());
              s["bands"].push_back({{"name", b.band.name()},
                                    {"min_um", b.band.lo_um()},
                                    {"max_um", b.band.hi_um()},
                                    {"mean_radiance", mean(b.radiance)},
                                    {"mean_transmittance", mean(b.transmittance)},
                                    {"min_apparent_temperature", *tmin},
                                    {"max_apparent_temperature", *tmax}});
            }
            summary["sensors"].push_back(s);
          }
        }
        const std::size_t frame_files = written.size();
        if (sequence) {
          const auto csv_path = dir / "time_series.csv";
          write_text_file_atomic(csv_path, csv);
          written.push_back(csv_path);
          // Radiance rows are scaled to their 0.5th–99.5th percentiles: a
          // few Monte Carlo outliers (or a sun glint) would otherwise set
          // the scale and leave every other pixel dark. The labels give
          // the scale used; values beyond it are drawn at its ends.
          for (ContactSheetRow& row : sheet.rows) {
            if (row.min || row.max) continue;
            std::vector<double> values;
            for (const ContactSheetCell& cell : row.cells)
              for (float v : cell.values)
                if (std::isfinite(v)) values.push_back(v);
            if (values.empty() || row.quantity != "band radiance") continue;
            std::sort(values.begin(), values.end());
            const double lo = percentile_of_sorted(values, 0.005),
                         hi = percentile_of_sorted(values, 0.995);
            if (hi > lo) {
              row.min = lo;
              row.max = hi;
            }
          }
          write_contact_sheet_png(dir / "contact_sheet.png", sheet, prov_text);
          written.push_back(dir / "contact_sheet.png");
        }
        std::string metrics_text;
        if (with_metrics) {
          const double reference_s = screening_reference_time_s(scene);
          const auto series = summarize_screening(metric_rows, scene.metrics, reference_s);
          write_text_file_atomic(dir / "metrics.csv", screening_metrics_csv(metric_rows));
          written.push_back(dir / "metrics.csv");
          write_text_file_atomic(dir / "metrics.json",
                                 screening_metrics_json(prov.to_json(), scene.metrics, reference_s,
                                                        masks, metric_rows, series)
                                         .dump(2) +
                                     "\n");
          written.push_back(dir / "metrics.json");
          metrics_text = screening_summary_text(series, scene.metrics, reference_s);
          if (sequence) {
            const ScreeningPlotFiles plots =
                write_screening_plots(dir, metric_rows, scene.metrics, prov_text);
            written.insert(written.end(), plots.written.begin(), plots.written.end());
            for (const std::string& why : plots.skipped)
              metrics_text += "  (not written: " + why + ")\n";
            for (const TargetMask& m : masks) {
              const auto path = dir / ("target_mask_" + file_safe_name(m.sensor) + ".png");
              write_target_mask_png(path, m, prov_text);
              written.push_back(path);
            }
          }
          summary["metrics"] = {{"settings", screening_settings_json(scene.metrics, reference_s)},
                                {"targets", target_masks_json(masks)},
                                {"series", screening_series_json(series)}};
        }
        const auto summary_path = dir / "summary.json";
        summary["units"] = {
            {"radiance", "W m-2 sr-1"}, {"apparent_temperature", "K"}, {"transmittance", "1"}};
        write_text_file_atomic(summary_path, summary.dump(2) + "\n");
        written.push_back(summary_path);
        summary["outputs"] = nlohmann::json::array();
        for (const auto& p : written) summary["outputs"].push_back(p.string());

        if (o->json) {
          summary.erase("scene");
          std::cout << summary.dump(2) << "\n";
          return 0;
        }
        for (const auto& s : summary["sensors"]) {
          std::cout << fmt::format("sensor {} at t = {} s ({}x{} px, {:.2f} s, {} rays)\n",
                                   s["name"].get<std::string>(), s["time_s"].get<double>(),
                                   s["width"].get<int>(), s["height"].get<int>(),
                                   s["seconds"].get<double>(), s["rays"].get<std::uint64_t>());
          for (const auto& b : s["bands"])
            std::cout << fmt::format(
                "  {:<10} mean radiance {:.5g} W m⁻² sr⁻¹, mean transmittance {:.4f}, "
                "apparent temperature {:.2f}–{:.2f} K\n",
                b["name"].get<std::string>(), b["mean_radiance"].get<double>(),
                b["mean_transmittance"].get<double>(), b["min_apparent_temperature"].get<double>(),
                b["max_apparent_temperature"].get<double>());
        }
        std::cout << metrics_text;
        std::cout << "wrote " << written.size() << " files to " << dir.string() << "/\n";
        if (written.size() <= 16) {
          for (const auto& p : written) std::cout << "  " << p.filename().string() << "\n";
        } else {
          // The per-frame files in one line, then every file of the whole run.
          std::cout << fmt::format("  {} … {} ({} files of frames)\n",
                                   written.front().filename().string(),
                                   written[frame_files - 1].filename().string(), frame_files);
          for (std::size_t i = frame_files; i < written.size(); ++i)
            std::cout << "  " << written[i].filename().string() << "\n";
        }
        return 0;
      }};
}

}  // namespace obscura::cli
