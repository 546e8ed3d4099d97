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
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("scene", o->scene, "Scene file (JSON, docs/formats.md)")->required();
  cmd->add_option("-o,--output", o->output, "Output folder (created if missing)")->required();
  cmd->add_option("--threads", o->threads, "Worker threads (default: the scene's, 0 = all cores)")
      ->check(CLI::Range(0, 4096));
  cmd->add_option("--seed", o->seed, "Random seed for pixel jitter (default: the scene's)");
  cmd->add_flag("--json", o->json, "Print a JSON summary on stdout");
  return {cmd, [o, invocation]() {
            Scene scene = load_scene(o->scene);
            if (o->threads) scene.settings.threads = *o->threads;
            if (o->seed) scene.settings.seed = *o->seed;
            const Provenance prov =
                make_provenance(invocation.command_line, scene.settings.seed, scene.input_files);
            const std::filesystem::path dir(o->output);

            nlohmann::json summary = {{"provenance", prov.to_json()},
                                      {"scene", scene.source},
                                      {"threads", resolve_thread_count(scene.settings.threads)},
                                      {"sensors", nlohmann::json::array()}};
            std::vector<std::filesystem::path> written;
            for (const Sensor& sensor : scene.sensors) {
              ProgressPrinter progress(sensor.name);
              RenderOptions options;
              options.threads = scene.settings.threads;
              options.seed = scene.settings.seed;
              options.progress = [&](int done, int total) { progress.update(done, total); };
              const SensorImage image = render_sensor(scene, sensor, options);
              progress.finish();
              const auto files = write_sensor_image(dir, image, prov);
              written.insert(written.end(), files.begin(), files.end());
              nlohmann::json s = {{"name", sensor.name},
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
              std::cout << fmt::format("sensor {} ({}x{} px, {:.2f} s, {} rays)\n",
                                       s["name"].get<std::string>(), s["width"].get<int>(),
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
            for (const auto& p : written) std::cout << "  " << p.filename().string() << "\n";
            return 0;
          }};
}

}  // namespace obscura::cli
