// The photon-map study of issue #4: relative RMSE against a converged
// path-traced reference versus wall time, photon map against path tracer, on
// the two study scenes (scene/example_scenes.h: the demo puff in sunlight at
// 0.55 µm, multiple scattering dominating; and at 10 µm, emission dominating),
// the photon map's error versus photon count and k, and the radiance cache's
// versus photon count. Usage:
//   bench_photon_map_study [--width 64] [--height 48] [--reference-spp 1024]
//                          [--scene visible|lwir|both] [--threads N] [--csv FILE] [--plot FILE.png]
// Prints one row per render; --csv writes them, --plot draws relative RMSE
// against wall time (docs/images/photon_map_study.png). Nothing is asserted.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "obscura/render/renderer.h"
#include "obscura/report/line_plot.h"
#include "obscura/scene/example_scenes.h"

using namespace obscura;

namespace {

struct Result {
  double seconds = 0;
  std::vector<float> radiance, stderr_l;
  double photon_seconds = 0;
  std::uint64_t photons = 0, photon_bytes = 0;
};

Result render(Scene& scene, int threads, std::uint64_t seed) {
  scene.settings.threads = threads;
  scene.settings.seed = seed;
  const auto t0 = std::chrono::steady_clock::now();
  const SensorImage img = render_sensor(scene, scene.sensors[0]);
  Result r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.radiance = img.bands[0].radiance;
  r.stderr_l = img.bands[0].radiance_stderr;
  r.photon_seconds = img.stats.photon_seconds;
  r.photons = img.stats.photons;
  r.photon_bytes = img.stats.photon_bytes;
  return r;
}

// Relative RMSE of `x` against `ref`: sqrt(mean (x − ref)²) / mean ref.
double relative_rmse(const std::vector<float>& x, const std::vector<float>& ref) {
  double se = 0, mean = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    se += (x[i] - ref[i]) * double(x[i] - ref[i]);
    mean += ref[i];
  }
  mean /= x.size();
  return std::sqrt(se / x.size()) / mean;
}

double relative_noise(const std::vector<float>& stderr_l, const std::vector<float>& ref) {
  double v = 0, mean = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    v += stderr_l[i] * double(stderr_l[i]);
    mean += ref[i];
  }
  return std::sqrt(v / ref.size()) / (mean / ref.size());
}

}  // namespace

int main(int argc, char** argv) {
  int width = 64, height = 48, reference_spp = 1024, threads = 0;
  std::string which = "both", csv, plot_path;
  LinePlot plot;
  plot.title =
      "Photon map and radiance cache vs path tracer: error against a converged path-traced image";
  plot.x = {"wall time (s)", true, std::nullopt, std::nullopt};
  plot.y = {"relative RMSE", true, std::nullopt, std::nullopt};
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--width")
      width = std::atoi(argv[i + 1]);
    else if (a == "--height")
      height = std::atoi(argv[i + 1]);
    else if (a == "--reference-spp")
      reference_spp = std::atoi(argv[i + 1]);
    else if (a == "--scene")
      which = argv[i + 1];
    else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--csv")
      csv = argv[i + 1];
    else if (a == "--plot")
      plot_path = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  std::ofstream out;
  if (!csv.empty()) {
    out.open(csv);
    out << "scene,method,spp,photons,k,seconds,relative_rmse\n";
  }
  for (const StudyScene s : {StudyScene::kVisible, StudyScene::kLwir}) {
    const std::string name = s == StudyScene::kVisible ? "visible" : "lwir";
    if (which != "both" && which != name) continue;
    Scene pt = make_study_scene(s, width, height, RenderMethod::kPathTracer);
    pt.settings.samples_per_pixel = reference_spp;
    const Result ref = render(pt, threads, 1000);
    std::printf("%s, %dx%d px: path-traced reference %d spp in %.1f s, its relative noise %.4f\n",
                name.c_str(), width, height, reference_spp, ref.seconds,
                relative_noise(ref.stderr_l, ref.radiance));
    std::printf("  %-12s %6s %9s %5s %9s %12s %10s\n", "method", "spp", "photons", "k", "seconds",
                "rel. RMSE", "mean bias");
    auto row = [&](const char* method, int spp, long long photons, int k, const Result& r) {
      const double e = relative_rmse(r.radiance, ref.radiance);
      double sx = 0, sr = 0;
      for (std::size_t i = 0; i < r.radiance.size(); ++i) {
        sx += r.radiance[i];
        sr += ref.radiance[i];
      }
      std::printf("  %-12s %6d %9lld %5d %9.3f %12.4f %+10.4f", method, spp, photons, k, r.seconds,
                  e, sx / sr - 1);
      if (photons > 0)
        std::printf("   (pass 1 %.3f s, %llu photons stored, %.1f MB)", r.photon_seconds,
                    static_cast<unsigned long long>(r.photons), r.photon_bytes / 1e6);
      std::printf("\n");
      if (out)
        out << name << "," << method << "," << spp << "," << photons << "," << k << "," << r.seconds
            << "," << e << "\n";
    };
    PlotSeries pt_series{
        name + ": path tracer, 1–64 spp", {}, {}, PlotSeries::Style::kLineAndMarkers};
    for (int spp : {1, 2, 4, 8, 16, 32, 64}) {
      pt.settings.samples_per_pixel = spp;
      const Result r = render(pt, threads, 7);
      row("path-tracer", spp, 0, 0, r);
      pt_series.x.push_back(r.seconds);
      pt_series.y.push_back(relative_rmse(r.radiance, ref.radiance));
    }
    plot.series.push_back(pt_series);
    Scene pm = make_study_scene(s, width, height, RenderMethod::kPhotonMap);
    for (int spp : {1, 4}) {
      PlotSeries pm_series{
          name + ": photon map, k 50, 2e4–5e5 photons, " + std::to_string(spp) + " spp",
          {},
          {},
          PlotSeries::Style::kLineAndMarkers};
      for (long long photons : {20000LL, 100000LL, 500000LL})
        for (int k : {20, 50, 100}) {
          pm.settings.samples_per_pixel = spp;
          pm.settings.photon_map.photons_per_node = photons;
          pm.settings.photon_map.k = k;
          const Result r = render(pm, threads, 7);
          row("photonmap", spp, photons, k, r);
          if (k == 50) {
            pm_series.x.push_back(r.seconds);
            pm_series.y.push_back(relative_rmse(r.radiance, ref.radiance));
          }
        }
      plot.series.push_back(pm_series);
    }
    // The radiance cache (its own default settings), by photons per node.
    Scene rc = make_study_scene(s, width, height, RenderMethod::kRadianceCache);
    for (int spp : {1, 4}) {
      PlotSeries rc_series{
          name + ": radiance cache, 2.5e4–1.6e6 photons, " + std::to_string(spp) + " spp",
          {},
          {},
          PlotSeries::Style::kLineAndMarkers};
      for (long long photons : {25000LL, 100000LL, 400000LL, 1600000LL}) {
        rc.settings.samples_per_pixel = spp;
        rc.settings.radiance_cache.photons_per_node = photons;
        const Result r = render(rc, threads, 7);
        row("radiance-cache", spp, photons, 0, r);
        rc_series.x.push_back(r.seconds);
        rc_series.y.push_back(relative_rmse(r.radiance, ref.radiance));
      }
      plot.series.push_back(rc_series);
    }
  }
  if (!plot_path.empty()) write_line_plot_png(plot_path, plot);
  return 0;
}
