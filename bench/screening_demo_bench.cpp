// Where a frame of `make demo` spends its time (docs/performance.md): the
// smoke-screen cloud is prepared once (dispersion model + optics →
// keyframes), then at each time the scene is staged and each sensor (one band
// each in the demo) rendered, with the photon map unless --method says
// otherwise. Prints, per band, the wall time per frame and its share in
// staging, photon tracing, building (the photon map's kd-tree; the radiance
// cache's splatting and sun depths) and
// ray marching, plus the one-off preparation. Nothing asserted.
//   bench_screening_demo [--scene examples/demo/scene.json]
//                        [--prepare examples/smoke-screen/prepare.json]
//                        [--times 0:30:6] [--threads 0]
//                        [--method M] [--size WxH] [--photons N] [--spp N]
//                        [--photons-by-band BAND=N[,BAND=N…]] [--adaptive-threshold T]
// --method, --size (every sensor), --photons (per spectral node, photon
// map or radiance cache), --photons-by-band (the radiance cache's count for
// the nodes of those bands, /render/radiance_cache/photons), --spp
// (samples per pixel) and --adaptive-threshold (/render/adaptive_threshold:
// the samples only where the image has an edge) override the scene's. Also prints the mean
// and the peak wall time per frame (all sensors). For the radiance cache the per-frame cache
// (shared by the sensors) is charged to the first sensor. Run from the repository root (default
// paths are relative to it).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "bench_timer.h"
#include "obscura/prep/prepare.h"
#include "obscura/scene/scene.h"
#include "obscura/sequence/sequence_runner.h"

using namespace obscura;
using bench::Clock;
using bench::seconds_since;
namespace fs = std::filesystem;

namespace {

struct Totals {
  double staging = 0, tracing = 0, build = 0, marching = 0;
  int frames = 0;
  double total() const { return staging + tracing + build + marching; }
};

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = "examples/demo/scene.json",
              prepare_path = "examples/smoke-screen/prepare.json";
  double t0 = 0, t1 = 30, step = 6;
  int threads = 0, width = 0, height = 0;
  long long photons = 0;
  std::map<std::string, long long> photons_by_band;
  int spp = 0;
  double adaptive_threshold = -1.0;
  std::string method;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--scene" && has_value)
      scene_path = argv[++i];
    else if (a == "--prepare" && has_value)
      prepare_path = argv[++i];
    else if (a == "--threads" && has_value)
      threads = std::atoi(argv[++i]);
    else if (a == "--method" && has_value)
      method = argv[++i];
    else if (a == "--photons" && has_value)
      photons = std::atoll(argv[++i]);
    else if (a == "--photons-by-band" && has_value) {
      const std::string list = argv[++i];
      for (std::size_t start = 0; start <= list.size();) {
        const std::size_t end = std::min(list.find(',', start), list.size());
        const std::string item = list.substr(start, end - start);
        const std::size_t eq = item.find('=');
        const long long n = eq == std::string::npos ? 0 : std::atoll(item.c_str() + eq + 1);
        if (n < 1) {
          std::fprintf(stderr,
                       "bench_screening_demo: --photons-by-band expects BAND=N[,BAND=N…]\n");
          return 2;
        }
        photons_by_band[item.substr(0, eq)] = n;
        start = end + 1;
      }
    } else if (a == "--spp" && has_value) {
      spp = std::atoi(argv[++i]);
      if (spp < 1) {
        std::fprintf(stderr, "bench_screening_demo: --spp expects a count of at least 1\n");
        return 2;
      }
    } else if (a == "--adaptive-threshold" && has_value) {
      adaptive_threshold = std::atof(argv[++i]);
      if (!(adaptive_threshold >= 0.0 && adaptive_threshold < 1.0)) {
        std::fprintf(stderr, "bench_screening_demo: --adaptive-threshold expects [0, 1)\n");
        return 2;
      }
    } else if (a == "--size" && has_value) {
      if (std::sscanf(argv[++i], "%dx%d", &width, &height) != 2 || width < 1 || height < 1) {
        std::fprintf(stderr, "bench_screening_demo: --size expects WxH\n");
        return 2;
      }
    } else if (a == "--times" && has_value) {
      if (std::sscanf(argv[++i], "%lf:%lf:%lf", &t0, &t1, &step) != 3 || !(step > 0) || t1 < t0) {
        std::fprintf(stderr, "bench_screening_demo: --times expects A:B:STEP\n");
        return 2;
      }
    } else {
      std::fprintf(stderr,
                   "usage: bench_screening_demo [--scene S] [--prepare P] [--times A:B:STEP] "
                   "[--threads N] [--method M] [--size WxH] [--photons N] [--spp N] "
                   "[--photons-by-band BAND=N[,BAND=N…]] [--adaptive-threshold T]\n");
      return 2;
    }
  }
  try {
    const fs::path dir =
        fs::temp_directory_path() / ("obscura_bench_demo_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    // The scene refers to cloud/cloud.json and tank.obj beside it.
    {
      // The scene, with --size applied to every sensor.
      std::ifstream in(scene_path);
      nlohmann::json doc = nlohmann::json::parse(in);
      if (width > 0)
        for (auto& sensor : doc.at("sensors")) {
          sensor["width"] = width;
          sensor["height"] = height;
        }
      std::ofstream(dir / "scene.json") << doc.dump(2);
    }
    fs::copy_file(fs::path(scene_path).parent_path() / "../tank/tank.obj", dir / "tank.obj");
    const auto p0 = Clock::now();
    const PrepareReport report = prepare_cloud(prepare_path, dir / "cloud");
    const double prepare_s = seconds_since(p0);

    Scene scene = load_scene(dir / "scene.json");
    scene.settings.threads = threads;
    if (!method.empty()) {
      const auto m = parse_render_method(method);
      if (!m) throw std::runtime_error("unknown method " + method);
      scene.settings.method = *m;
    }
    if (photons > 0) {
      scene.settings.photon_map.photons_per_node = photons;
      scene.settings.radiance_cache.photons_per_node = photons;
    }
    for (const auto& [band, n] : photons_by_band)
      scene.settings.radiance_cache.photons_by_band[band] = n;
    if (spp > 0) scene.settings.samples_per_pixel = spp;
    if (adaptive_threshold >= 0.0) scene.settings.adaptive_threshold = adaptive_threshold;
    std::vector<double> times;
    for (double t = t0; t <= t1 + 1e-9 * step; t += step) times.push_back(t);
    const int frames = static_cast<int>(times.size());
    // The frames as `obscura render --time` renders them (sequence/sequence_runner.h).
    const SequenceResult result = render_sequence(scene, times);
    std::map<std::string, Totals> per_band;
    std::map<double, double> per_frame;  // time → wall seconds of all its sensors
    std::vector<std::string> order;
    std::uint64_t traced = 0, colliding = 0, collisions = 0;  // the photons' walks
    for (const SensorFrameStats& frame : result.sensor_frames) {
      traced += frame.stats.photons_traced;
      colliding += frame.stats.photons_colliding;
      collisions += frame.stats.photon_collisions;
      per_frame[frame.time_s] += frame.staging_seconds / scene.sensors.size() + frame.stats.seconds;
      const Sensor& sensor = *std::find_if(scene.sensors.begin(), scene.sensors.end(),
                                           [&](const Sensor& s) { return s.name == frame.sensor; });
      std::string label = sensor.name + " (";
      for (std::size_t b = 0; b < sensor.bands.size(); ++b)
        label += (b ? "+" : "") + sensor.bands[b].name();
      label += ")";
      if (!per_band.count(label)) order.push_back(label);
      Totals& tot = per_band[label];
      // Staging is shared by the frame's sensors: each is charged its share.
      tot.staging += frame.staging_seconds / scene.sensors.size();
      tot.tracing += frame.stats.photon_trace_seconds;
      tot.build += frame.stats.photon_build_seconds;
      tot.marching += frame.stats.seconds - frame.stats.photon_seconds;
      ++tot.frames;
    }
    const int w = scene.sensors.front().camera.width(), h = scene.sensors.front().camera.height();
    std::printf(
        "scene %s: %d frames at t = %g…%g s, %d×%d px, method %s, %lld photons per node, %d "
        "threads\n",
        scene_path.c_str(), frames, t0, t1, w, h,
        std::string(render_method_name(scene.settings.method)).c_str(),
        scene.settings.method == RenderMethod::kRadianceCache
            ? scene.settings.radiance_cache.photons_per_node
            : scene.settings.photon_map.photons_per_node,
        threads);
    if (scene.settings.method == RenderMethod::kRadianceCache)
      for (const auto& [band, n] : scene.settings.radiance_cache.photons_by_band)
        std::printf("  band %s: %lld photons per node\n", band.c_str(), n);
    std::printf(
        "preparation (once): %.2f s (concentrations %.2f, optics %.2f, keyframes %.2f), %zu "
        "keyframes\n",
        prepare_s, report.seconds_concentrations, report.seconds_optics, report.seconds_keyframes,
        report.keyframes.size());
    std::printf("%-26s %10s %9s %9s %9s %9s\n", "sensor (band)", "s/frame", "staging", "tracing",
                "building", "marching");
    Totals all;
    for (const std::string& label : order) {
      const Totals& t = per_band[label];
      const double total = t.total();
      std::printf("%-26s %10.3f %8.1f%% %8.1f%% %8.1f%% %8.1f%%\n", label.c_str(), total / t.frames,
                  100 * t.staging / total, 100 * t.tracing / total, 100 * t.build / total,
                  100 * t.marching / total);
      all.staging += t.staging;
      all.tracing += t.tracing;
      all.build += t.build;
      all.marching += t.marching;
    }
    std::printf("%-26s %10.3f %8.1f%% %8.1f%% %8.1f%% %8.1f%%\n", "all sensors",
                all.total() / frames, 100 * all.staging / all.total(),
                100 * all.tracing / all.total(), 100 * all.build / all.total(),
                100 * all.marching / all.total());
    double peak = 0, peak_time = 0;
    for (const auto& [time, seconds] : per_frame)
      if (seconds > peak) std::tie(peak, peak_time) = std::pair(seconds, time);
    std::printf("per frame: mean %.3f s, peak %.3f s (t = %g s)\n", all.total() / frames, peak,
                peak_time);
    std::printf("whole run: preparation %.1f s + frames %.1f s\n", prepare_s, all.total());
    // Where the photons' time goes: a photon that meets no smoke costs little.
    if (traced > 0)
      std::printf(
          "photons per frame: %.3g traced, %.1f %% met the smoke with %.1f real collisions "
          "each\n",
          static_cast<double>(traced) / frames, 100.0 * colliding / traced,
          colliding ? static_cast<double>(collisions) / colliding : 0.0);
    fs::remove_all(dir);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_screening_demo: %s\n", e.what());
    return 1;
  }
  return 0;
}
