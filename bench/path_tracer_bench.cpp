// Path-tracer throughput and the cost of a reference image (issue #3): the
// example scene of `make demo` (examples/puff-over-target, the puff of
// scripts/puff-example) rendered with "method": "path-tracer". Prints paths per second
// (one path per pixel sample, spectral node and band), the mean relative
// standard error over pixels, and the wall time of a render whose mean relative
// standard error is 1 % (sample count predicted from a pilot render, since the
// error falls as 1/√spp). Usage:
//   bench_path_tracer [--width 160] [--height 120] [--pilot-spp 16] [--target 0.01] [--threads N]
// Figures go to docs/performance.md; nothing here is asserted.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "obscura/core/parallel.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/renderer.h"

using namespace obscura;

namespace {

struct Run {
  double seconds = 0, mean_relative_stderr = 0;
  long long paths = 0;
};

Run render(Scene& scene, int spp, int threads) {
  scene.settings.samples_per_pixel = spp;
  scene.settings.threads = threads;
  const auto t0 = std::chrono::steady_clock::now();
  const SensorImage img = render_sensor(scene, scene.sensors[0]);
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double sum = 0;
  long long n = 0;
  for (const auto& band : img.bands)
    for (std::size_t i = 0; i < band.radiance.size(); ++i, ++n)
      sum += band.radiance_stderr[i] / band.radiance[i];
  r.mean_relative_stderr = sum / n;
  r.paths = static_cast<long long>(n) * spp * scene.settings.spectral_nodes_per_band;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 160, height = 120, pilot = 16, threads = 0;
  double target = 0.01;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--width")
      width = std::atoi(argv[i + 1]);
    else if (a == "--height")
      height = std::atoi(argv[i + 1]);
    else if (a == "--pilot-spp")
      pilot = std::atoi(argv[i + 1]);
    else if (a == "--target")
      target = std::atof(argv[i + 1]);
    else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  // The puff of scripts/puff-example: `make-puff --center -2,-12,3 --radius 2.5
  // --extent 3.5 --resolution 96 --wavelengths 4,10 --sigma-a 0.25,0.30
  // --sigma-s 0.15,0.05 --g 0.6,0.4 --ambient 288 --excess 12`.
  GaussianPuffSpec spec;
  spec.center_m = {-2, -12, 3};
  spec.radius_m = 2.5;
  spec.extent_radii = 3.5;
  spec.resolution = 96;
  spec.wavelengths_um = {4.0, 10.0};
  spec.peak_sigma_a = {0.25, 0.30};
  spec.peak_sigma_s = {0.15, 0.05};
  spec.g = {0.6, 0.4};
  spec.ambient_temperature_k = 288;
  spec.temperature_excess_k = 12;
  Scene scene;
  scene.medium =
      std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{288, 0.95}, 0.0));
  scene.surfaces.push_back(std::make_unique<BoxSurface>("target", SurfaceMaterial{330, 0.9},
                                                        BBox3({-3, 0, 0}, {3, 6, 2.5})));
  scene.sky = Sky::blackbody(250, true);
  Sensor sensor;
  sensor.name = "ir";
  sensor.camera = PinholeCamera({0, -60, 4}, {0, 0, 2.5}, {0, 0, 1}, 24.0, width, height);
  sensor.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.settings.method = RenderMethod::kPathTracer;
  scene.settings.spectral_nodes_per_band = 8;

  const int cores = resolve_thread_count(threads);
  std::printf(
      "example scene (puff over target), %dx%d px, mwir + lwir, 8 spectral nodes per band, "
      "%d threads\n",
      width, height, cores);
  const Run p = render(scene, pilot, threads);
  std::printf("pilot   %5d spp: %8.2f s, %.3g paths/s (%.3g per core), mean relative stderr %.4f\n",
              pilot, p.seconds, p.paths / p.seconds, p.paths / p.seconds / cores,
              p.mean_relative_stderr);
  // The standard error falls as 1/√spp; the pilot's estimate of it is itself
  // noisy, so re-predict until the target is met (the last render is reported).
  int spp = pilot;
  Run r = p;
  for (int round = 0; round < 4 && r.mean_relative_stderr > target; ++round) {
    spp = static_cast<int>(std::ceil(spp * 1.05 * std::pow(r.mean_relative_stderr / target, 2.0)));
    r = render(scene, spp, threads);
    std::printf("render  %5d spp: %8.2f s, %.3g paths/s, mean relative stderr %.4f\n", spp,
                r.seconds, r.paths / r.seconds, r.mean_relative_stderr);
  }
  std::printf("reference image at mean relative stderr <= %.3g: %d spp, %.2f s wall\n", target, spp,
              r.seconds);
  return 0;
}
