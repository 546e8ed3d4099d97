// The photon-map study of issue #4: relative RMSE against a converged
// path-traced reference versus wall time, photon map against path tracer, on
// the two study scenes (scene/example_scenes.h: the demo puff in sunlight at
// 0.55 µm, multiple scattering dominating; and at 10 µm, emission dominating),
// the photon map's error versus photon count and k, and the radiance cache's
// versus photon count. Usage:
//   bench_photon_map_study [--width 64] [--height 48] [--reference-spp 1024]
//                          [--scene visible|lwir|both] [--threads N] [--csv FILE] [--plot FILE.png]
//                          [--methods path-tracer,photon-map,radiance-cache]
//                          [--cache-photons 25000,100000,400000,1600000] [--cache-spp 1,4]
// Prints one row per render; --csv writes them, --plot draws relative RMSE
// against wall time (docs/images/photon_map_study.png). Nothing is asserted.
// The RMSE against the reference contains the reference's own noise in
// quadrature; the column "less ref." takes it out, sqrt(RMSE² − noise²),
// the method's own error where the reference's noise is smaller.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// "a,b,c" as numbers; exits with a message on anything else.
std::vector<long long> number_list(const std::string& option, const std::string& text) {
  std::vector<long long> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    char* end = nullptr;
    const long long v = std::strtoll(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || v <= 0) {
      std::fprintf(stderr, "%s: expected positive integers separated by commas, got '%s'\n",
                   option.c_str(), text.c_str());
      std::exit(2);
    }
    out.push_back(v);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 64, height = 48, reference_spp = 1024, threads = 0;
  std::string which = "both", csv, plot_path, methods = "path-tracer,photon-map,radiance-cache";
  std::vector<long long> cache_photons = {25000, 100000, 400000, 1600000}, cache_spp = {1, 4};
  LinePlot plot;
  plot.title =
      "Photon map and radiance cache vs path tracer: error against a converged path-traced image";
  plot.x = {"wall time (s)", true, std::nullopt, std::nullopt};
  plot.y = {"relative RMSE", true, std::nullopt, std::nullopt};
  constexpr const char* kUsage =
      "usage: bench_photon_map_study [--width 64] [--height 48] [--reference-spp 1024]\n"
      "         [--scene visible|lwir|both] [--threads N] [--csv FILE] [--plot FILE.png]\n"
      "         [--methods path-tracer,photon-map,radiance-cache]\n"
      "         [--cache-photons 25000,100000,400000,1600000] [--cache-spp 1,4]\n";
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("%s", kUsage);
      return 0;
    }
    if (i + 1 >= argc) {
      std::fprintf(stderr, "option %s needs a value\n%s", a.c_str(), kUsage);
      return 2;
    }
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
    else if (a == "--methods")
      methods = argv[i + 1];
    else if (a == "--cache-photons")
      cache_photons = number_list(a, argv[i + 1]);
    else if (a == "--cache-spp")
      cache_spp = number_list(a, argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  // The methods named, each one known.
  std::vector<std::string> wanted_methods;
  {
    std::stringstream in(methods);
    std::string m;
    while (std::getline(in, m, ',')) {
      if (m != "path-tracer" && m != "photon-map" && m != "radiance-cache") {
        std::fprintf(stderr,
                     "--methods: expected path-tracer, photon-map or radiance-cache, got '%s'\n",
                     m.c_str());
        return 2;
      }
      wanted_methods.push_back(m);
    }
  }
  auto wanted = [&](const std::string& method) {
    return std::find(wanted_methods.begin(), wanted_methods.end(), method) != wanted_methods.end();
  };
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
    const double ref_noise = relative_noise(ref.stderr_l, ref.radiance);
    std::printf("%s, %dx%d px: path-traced reference %d spp in %.1f s, its relative noise %.4f\n",
                name.c_str(), width, height, reference_spp, ref.seconds, ref_noise);
    std::printf("  %-14s %4s %9s %5s %9s %10s %10s %10s\n", "method", "spp", "photons", "k",
                "seconds", "rel. RMSE", "less ref.", "mean bias");
    auto row = [&](const char* method, int spp, long long photons, int k, const Result& r) {
      const double e = relative_rmse(r.radiance, ref.radiance);
      double sx = 0, sr = 0;
      for (std::size_t i = 0; i < r.radiance.size(); ++i) {
        sx += r.radiance[i];
        sr += ref.radiance[i];
      }
      // The method's own error: the reference's noise taken out in
      // quadrature (independent seeds), nan where the RMSE is below it.
      const double own = e > ref_noise ? std::sqrt(e * e - ref_noise * ref_noise) : std::nan("");
      std::printf("  %-14s %4d %9lld %5d %9.3f %10.4f %10.4f %+10.4f", method, spp, photons, k,
                  r.seconds, e, own, sx / sr - 1);
      if (photons > 0)
        std::printf("   (pass 1 %.3f s, %llu photons stored, %.1f MB)", r.photon_seconds,
                    static_cast<unsigned long long>(r.photons), r.photon_bytes / 1e6);
      std::printf("\n");
      if (out)
        out << name << "," << method << "," << spp << "," << photons << "," << k << "," << r.seconds
            << "," << e << "\n";
    };
    if (wanted("path-tracer")) {
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
    }
    if (wanted("photon-map")) {
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
    }
    if (!wanted("radiance-cache")) continue;
    // The radiance cache (its own default settings), by photons per node.
    Scene rc = make_study_scene(s, width, height, RenderMethod::kRadianceCache);
    for (const long long spp : cache_spp) {
      PlotSeries rc_series{name + ": radiance cache, " + std::to_string(cache_photons.front()) +
                               "–" + std::to_string(cache_photons.back()) + " photons, " +
                               std::to_string(spp) + " spp",
                           {},
                           {},
                           PlotSeries::Style::kLineAndMarkers};
      for (const long long photons : cache_photons) {
        rc.settings.samples_per_pixel = static_cast<int>(spp);
        rc.settings.radiance_cache.photons_per_node = photons;
        const Result r = render(rc, threads, 7);
        row("radiance-cache", static_cast<int>(spp), photons, 0, r);
        rc_series.x.push_back(r.seconds);
        rc_series.y.push_back(relative_rmse(r.radiance, ref.radiance));
      }
      plot.series.push_back(rc_series);
    }
  }
  if (!plot_path.empty()) write_line_plot_png(plot_path, plot);
  return 0;
}
