// `obscura render`: renders every sensor of a scene into an output folder.
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <mutex>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "obscura/analysis/region_stats.h"
#include "obscura/core/error.h"
#include "obscura/core/parallel.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/provenance.h"
#include "obscura/io/render_output.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/scene.h"

namespace obscura::cli {
namespace {

// Progress on stderr for runs longer than a second: a rewritten line on a
// terminal, an occasional line otherwise (logs, CI).
class ProgressPrinter {
 public:
  explicit ProgressPrinter(std::string label)
      : label_(std::move(label)), start_(std::chrono::steady_clock::now()),
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
  if (n > 100000) throw InputError("", "--time", fmt::format("'{}' gives more than 100000 frames", text));
  std::vector<double> times;
  for (int k = 0; k <= static_cast<int>(n); ++k) times.push_back(a + k * step);
  return times;
}

double mean(const std::vector<float>& v) {
  double s = 0;
  for (float x : v) s += x;
  return v.empty() ? 0.0 : s / v.size();
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
                  "per frame and time_series.csv with region means")
      ->excludes(at);
  cmd->add_flag("--json", o->json, "Print a JSON summary on stdout");
  return {cmd, [o, invocation]() {
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
            std::string csv =
                "time_s,sensor,region,band,pixels,mean_radiance_W_m-2_sr-1,mean_transmittance,"
                "apparent_temperature_of_mean_K\n";
            for (std::size_t f = 0; f < times.size(); ++f) {
              stage_scene(scene, times[f]);
              const std::string suffix = sequence ? fmt::format("_f{:04d}", f) : "";
              for (const Sensor& sensor : scene.sensors) {
                const std::string label =
                    sequence ? fmt::format("{} frame {}/{} (t = {:.4g} s)", sensor.name, f + 1,
                                           times.size(), times[f])
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
                for (const RegionStats& r :
                     region_stats(image, scene.regions, scene.settings.spectral_nodes_per_band))
                  csv += fmt::format("{:.9g},{},{},{},{},{:.9g},{:.9g},{:.6f}\n", times[f],
                                     sensor.name, r.region, r.band, r.pixels, r.mean_radiance,
                                     r.mean_transmittance, r.mean_apparent_temperature);
                nlohmann::json s = {{"name", sensor.name},
                                    {"time_s", times[f]},
                                    {"width", image.width},
                                    {"height", image.height},
                                    {"exr", files.front().string()},
                                    {"seconds", image.stats.seconds},
                                    {"rays", image.stats.rays},
                                    {"voxel_segments", image.stats.segments},
                                    {"bands", nlohmann::json::array()}};
                for (const BandImage& b : image.bands) {
                  const auto [tmin, tmax] = std::minmax_element(b.apparent_temperature.begin(),
                                                                b.apparent_temperature.end());
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
            if (sequence) {
              const auto csv_path = dir / "time_series.csv";
              write_text_file_atomic(csv_path, csv);
              written.push_back(csv_path);
            }
            const auto summary_path = dir / "summary.json";
            summary["units"] = {{"radiance", "W m-2 sr-1"}, {"apparent_temperature", "K"},
                                {"transmittance", "1"}};
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
                                       s["width"].get<int>(),
                                       s["height"].get<int>(), s["seconds"].get<double>(),
                                       s["rays"].get<std::uint64_t>());
              for (const auto& b : s["bands"])
                std::cout << fmt::format(
                    "  {:<10} mean radiance {:.5g} W m⁻² sr⁻¹, mean transmittance {:.4f}, "
                    "apparent temperature {:.2f}–{:.2f} K\n",
                    b["name"].get<std::string>(), b["mean_radiance"].get<double>(),
                    b["mean_transmittance"].get<double>(),
                    b["min_apparent_temperature"].get<double>(),
                    b["max_apparent_temperature"].get<double>());
            }
            std::cout << "wrote " << written.size() << " files to " << dir.string() << "/\n";
            if (written.size() <= 16) {
              for (const auto& p : written) std::cout << "  " << p.filename().string() << "\n";
            } else {
              std::cout << "  " << written.front().filename().string() << " … "
                        << written[written.size() - 3].filename().string() << ", "
                        << "time_series.csv, summary.json\n";
            }
            return 0;
          }};
}

}  // namespace obscura::cli
