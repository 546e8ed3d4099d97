// The two keyframe forms side by side (docs/formats.md): the smoke-screen
// example prepared as full spectral keyframes and as compact species
// keyframes, then compared for file size, memory, the time to read (and
// expand) a keyframe, and the time to stage and render one frame of the
// example's scene. Prints the figures; nothing asserted.
//   bench_species_form [--config examples/smoke-screen/prepare.json]
//                      [--scene examples/smoke-screen/scene.json] [--wavelengths N]
//                      [--width 120] [--height 60] [--at 10.5] [--dir /tmp/...]
// Run from the repository root (the default paths are relative to it).
// --wavelengths N replaces the config's wavelengths by N samples spread over
// 0.55–1.064, 3–5 and 8–12 µm, to see how the forms scale with the spectral
// resolution.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bench_timer.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/prep/prepare.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/scene.h"

using namespace obscura;
using bench::Clock;
using bench::seconds_since;
namespace fs = std::filesystem;

namespace {

struct FormFigures {
  PrepareReport report;
  double mean_file_bytes = 0;
  std::size_t expanded_bytes = 0, compact_bytes = 0;
  double read_s = 0;    // mean over the keyframes, best of 3 passes
  double stage_s = 0;   // stage_scene at the chosen time, cold cache
  double render_s = 0;  // best of 3
  SensorImage image;
};

FormFigures run_form(const nlohmann::json& config, const std::string& form,
                     const nlohmann::json& scene_doc, const fs::path& scene_path,
                     const fs::path& dir, double at) {
  FormFigures f;
  nlohmann::json c = config;
  c["output_form"] = form;
  const fs::path config_path = dir / (form + ".json");
  std::ofstream(config_path) << c.dump(2);
  f.report = prepare_cloud(config_path, dir / form);
  const std::size_t n = f.report.keyframes.size();
  for (const fs::path& k : f.report.keyframes) f.mean_file_bytes += fs::file_size(k);
  f.mean_file_bytes /= n;
  const KeyframeInfo info = inspect_cloud_keyframe(f.report.keyframes[n / 3]);
  f.expanded_bytes = info.memory_bytes;
  f.compact_bytes = info.form == "species" ? info.compact_bytes : 0;

  f.read_s = 1e30;
  for (int pass = 0; pass < 3; ++pass) {
    const auto t0 = Clock::now();
    for (const fs::path& k : f.report.keyframes) read_cloud_keyframe(k);
    f.read_s = std::min(f.read_s, seconds_since(t0) / n);
  }

  nlohmann::json s = scene_doc;
  s["clouds"][0]["manifest"] = fs::absolute(dir / form / "cloud.json").string();
  Scene scene = parse_scene(s, scene_path);  // staged at 0 s
  auto t0 = Clock::now();
  stage_scene(scene, at);  // reads two keyframes through the cache and interpolates them
  f.stage_s = seconds_since(t0);
  f.render_s = 1e30;
  for (int r = 0; r < 3; ++r) {
    t0 = Clock::now();
    f.image = render_sensor(scene, scene.sensors[0]);
    f.render_s = std::min(f.render_s, seconds_since(t0));
  }
  return f;
}

bool same_images(const SensorImage& a, const SensorImage& b) {
  if (a.bands.size() != b.bands.size()) return false;
  for (std::size_t i = 0; i < a.bands.size(); ++i)
    if (a.bands[i].radiance != b.bands[i].radiance ||
        a.bands[i].transmittance != b.bands[i].transmittance)
      return false;
  return true;
}

}  // namespace

int run(int argc, char** argv) {
  fs::path config_path = "examples/smoke-screen/prepare.json";
  fs::path scene_path = "examples/smoke-screen/scene.json";
  fs::path dir =
      fs::temp_directory_path() / ("obscura_species_bench_" + std::to_string(::getpid()));
  int wavelengths = 0, width = 120, height = 60;
  double at = 10.5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--config")
      config_path = argv[i + 1];
    else if (a == "--scene")
      scene_path = argv[i + 1];
    else if (a == "--wavelengths")
      wavelengths = std::atoi(argv[i + 1]);
    else if (a == "--width")
      width = std::atoi(argv[i + 1]);
    else if (a == "--height")
      height = std::atoi(argv[i + 1]);
    else if (a == "--at")
      at = std::atof(argv[i + 1]);
    else if (a == "--dir")
      dir = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  nlohmann::json config = nlohmann::json::parse(std::ifstream(config_path));
  // The config is rewritten into the scratch folder, where the frame paths
  // of a CFD config (relative to its own folder) would no longer resolve.
  if (config.contains("vtk") || config.contains("netcdf")) {
    std::fprintf(stderr, "bench_species_form: use a dispersion config\n");
    return 2;
  }
  if (wavelengths > 0) {
    // Spread over the windows phosphorus smoke has data for: 0.55–1.064,
    // 3–5 and 8–12 µm, a third each (the rest in the last).
    config["wavelengths_um"] = nlohmann::json::array();
    const double windows[3][2] = {{0.55, 1.064}, {3.0, 5.0}, {8.0, 12.0}};
    for (int w = 0; w < 3; ++w) {
      const int m = w < 2 ? wavelengths / 3 : wavelengths - 2 * (wavelengths / 3);
      for (int k = 0; k < m; ++k)
        config["wavelengths_um"].push_back(
            m == 1 ? windows[w][0]
                   : windows[w][0] + (windows[w][1] - windows[w][0]) * k / (m - 1.0));
    }
  }
  nlohmann::json scene_doc = nlohmann::json::parse(std::ifstream(scene_path));
  scene_doc.erase("regions");  // they name pixels of the full-size image
  scene_doc["sensors"][0]["width"] = width;
  scene_doc["sensors"][0]["height"] = height;
  scene_doc["render"]["method"] = "emission-absorption";

  fs::remove_all(dir);
  fs::create_directories(dir);
  const FormFigures spectral = run_form(config, "spectral", scene_doc, scene_path, dir, at);
  const FormFigures species = run_form(config, "species", scene_doc, scene_path, dir, at);
  fs::remove_all(dir);

  const PrepareReport& r = spectral.report;
  std::printf("species form benchmark: %s, %zu keyframes of %dx%dx%d voxels, %zu wavelengths\n",
              config_path.string().c_str(), r.keyframes.size(), r.dims.nx, r.dims.ny, r.dims.nz,
              r.wavelengths_um.size());
  std::printf("%-44s %14s %14s %8s\n", "", "spectral", "species", "ratio");
  const auto row = [](const char* what, double a, double b, const char* fmt) {
    char sa[32], sb[32];
    std::snprintf(sa, sizeof sa, fmt, a);
    std::snprintf(sb, sizeof sb, fmt, b);
    std::printf("%-44s %14s %14s %8.2f\n", what, sa, sb, a / b);
  };
  row("file per keyframe (KiB, mean)", spectral.mean_file_bytes / 1024.0,
      species.mean_file_bytes / 1024.0, "%.1f");
  row("prepare: writing keyframes (s)", spectral.report.seconds_keyframes,
      species.report.seconds_keyframes, "%.3f");
  row("in memory: expanded grid vs compact (MiB)", spectral.expanded_bytes / 1048576.0,
      species.compact_bytes / 1048576.0, "%.2f");
  row("read (+ expand) one keyframe (ms)", 1e3 * spectral.read_s, 1e3 * species.read_s, "%.1f");
  row("stage the scene at t (ms, cold cache)", 1e3 * spectral.stage_s, 1e3 * species.stage_s,
      "%.1f");
  row("render one frame (ms, best of 3)", 1e3 * spectral.render_s, 1e3 * species.render_s, "%.1f");
  std::printf("render: %dx%d pixels, %zu bands, emission-absorption, t = %g s; images %s\n", width,
              height, spectral.image.bands.size(), at,
              same_images(spectral.image, species.image) ? "bit-identical" : "DIFFER");
  std::printf("(the renderer holds the expanded grid in either form: %.2f MiB per keyframe)\n",
              species.expanded_bytes / 1048576.0);
  return 0;
}

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_species_form: %s\n", e.what());
    return 1;
  }
}
