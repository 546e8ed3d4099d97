// Emission–absorption throughput: 1024×1024 rays through a 256³ grid (issue #2).
// Prints rays/s and voxel steps (medium segments) per second per core. Usage:
//   bench_emission_absorption [--resolution 256] [--pixels 1024] [--threads N] [--nodes 1]
// Figures go to docs/performance.md; nothing here is asserted.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "obscura/core/parallel.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/renderer.h"

using namespace obscura;

int main(int argc, char** argv) {
  int resolution = 256, pixels = 1024, threads = 0, nodes = 1;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const int v = std::atoi(argv[i + 1]);
    if (a == "--resolution")
      resolution = v;
    else if (a == "--pixels")
      pixels = v;
    else if (a == "--threads")
      threads = v;
    else if (a == "--nodes")
      nodes = v;
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  // A non-isothermal, scattering puff that fills the grid: every cell is
  // non-zero, so every cell the rays cross is a real voxel step.
  GaussianPuffSpec spec;
  spec.center_m = {0, 0, 0};
  spec.radius_m = 10.0;
  spec.extent_radii = 1.5;
  spec.resolution = resolution;
  spec.wavelengths_um = {10.0};
  spec.peak_sigma_a = {0.05};
  spec.peak_sigma_s = {0.02};
  spec.g = {0.5};
  spec.ambient_temperature_k = 290;
  spec.temperature_excess_k = 30;
  auto t0 = std::chrono::steady_clock::now();
  Scene scene;
  scene.medium =
      std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
  const double build_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Sensor sensor;
  sensor.name = "bench";
  // Looking at the grid face-on from outside, the field of view just covering it.
  sensor.camera = PinholeCamera({0, -60, 0}, {0, 0, 0}, {0, 0, 1}, 28.0, pixels, pixels);
  sensor.bands = {Band::flat("lwir", 8.0, 12.0)};
  scene.sensors.push_back(sensor);
  scene.settings.spectral_nodes_per_band = nodes;
  scene.settings.threads = threads;
  const SensorImage img = render_sensor(scene, sensor);
  const int cores = resolve_thread_count(threads);
  const double s = img.stats.seconds;
  std::printf("emission-absorption benchmark\n");
  std::printf(
      "  grid %d^3 (%.1f MB, built in %.2f s), image %dx%d, %d spectral node(s), %d thread(s)\n",
      resolution,
      scene.medium ? static_cast<const GridMedium&>(*scene.medium).grid().memory_bytes() / 1e6
                   : 0.0,
      build_s, pixels, pixels, nodes, cores);
  std::printf("  wall time            %.3f s\n", s);
  std::printf("  rays                 %llu (%.3g rays/s, %.3g rays/s/core)\n",
              static_cast<unsigned long long>(img.stats.rays), img.stats.rays / s,
              img.stats.rays / s / cores);
  std::printf("  voxel steps          %llu (%.1f per ray)\n",
              static_cast<unsigned long long>(img.stats.segments),
              static_cast<double>(img.stats.segments) / img.stats.rays);
  std::printf("  voxel steps/s/core   %.3g\n", img.stats.segments / s / cores);
  // The wall time above includes the frame's preparation: the lattice's
  // records (σa, σs, T, σs g per node, laid out once per frame before any
  // ray; render/lattice/). The march alone is the rest.
  const double prepared_s = img.stats.photon_seconds;
  std::printf("  preparation          %.3f s (the lattice's records, once per frame)\n",
              prepared_s);
  if (s > prepared_s)
    std::printf("  march only           %.3f s, %.3g voxel steps/s/core\n", s - prepared_s,
                img.stats.segments / (s - prepared_s) / cores);
  // Only the adaptive (validation) quadrature counts its integrand
  // evaluations; the cell quadrature evaluates each cell's three points.
  if (img.stats.integrand_evals > 0)
    std::printf("  integrand evals/step %.2f\n",
                static_cast<double>(img.stats.integrand_evals) /
                    std::max<unsigned long long>(1, img.stats.segments));
  else
    std::printf("  quadrature           cell (entry, middle and exit of each voxel step)\n");
  return 0;
}
