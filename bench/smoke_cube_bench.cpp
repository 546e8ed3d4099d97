// Time to 2 % error on the homogeneous smoke cube of the radiance-cache issue
// (docs/performance.md, "The smoke cube"): a cube of 2 m side, σa 0.2 and
// σs 1.8 /m, g 0.5, lit by a sun of 1° angular diameter 40° from the zenith
// under a black sky, seen from 6 m (1 m above its centre, looking at it) by a
// 45° pinhole camera at 256², in one narrow visible band (0.549–0.551 µm).
//
// The error: the image averaged over 8×8-pixel blocks, the blocks where the
// reference is above 1 % of its largest block kept, the RMS of the relative
// difference. The reference is a path-traced image at --reference-spp (its
// own error is printed: the block mean's standard error, RMS over the kept
// blocks); each method is then run at growing effort (spp for the path
// tracer, photons for the photon map and the radiance cache) until the error
// is below --target, printing time and error at each step. Usage:
//   bench_smoke_cube [--reference-spp 4096] [--target 0.02] [--threads N]
//                    [--size 256] [--methods path-tracer,photonmap,radiance-cache]
//                    [--reference-file F] [--sh-degree D] [--kernel R] [--voxel M]
//                    [--photons N] [--steps 12] [--error-map F] [--cache-spp 4]
//                    [--medium grid|box] [--grid 32] [--seed 1]
// --reference-file keeps the reference's block means in F (read back when F
// exists, which must then have been made at the same size and spp); --sh-degree, --kernel and
// --voxel set the radiance cache's settings, --photons its first effort
// (photons per node, doubled at each of at most --steps steps). --error-map
// writes each step's blocks (reference mean and relative difference) to F as
// CSV. --seed: the methods' seed (1; the reference's is fixed). --cache-spp: the radiance cache's
// samples per pixel (stratified: one sample at a pixel's centre is not the pixel's mean where an
// edge crosses it, and the reference's is). The radiance cache's defaults here, 4 spp and SH degree
// 3, are what reached 2 % (docs/performance.md). --medium: the cube as a grid of --grid³ voxels
// (default 32³) or a box (the same medium). The radiance cache's lattice lies on the grid's
// voxels, so --grid also sets its spacing: at 16 (12.5 cm) it reaches 2 % soonest
// (docs/performance.md). Nothing here is asserted.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "bench_timer.h"
#include "obscura/core/parallel.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/renderer.h"

using namespace obscura;

namespace {

// The cube as a box, or as an n³ grid of the same constant values (a grid's
// clamped reconstruction is constant up to its faces, so the medium is the
// same), which the radiance cache marches over its lattice records.
Scene smoke_cube(int size, bool as_grid, int n) {
  Scene scene;
  const std::vector<double> wavelengths{0.5, 0.6};
  if (as_grid) {
    GridPlacement placement;
    placement.origin_m = {-1, -1, -1};
    placement.voxel_size_m = 2.0 / n;
    auto grid = std::make_shared<VoxelGrid>(GridDims{n, n, n}, placement, wavelengths);
    for (int s = 0; s < 2; ++s) {
      std::fill_n(grid->sigma_a(s), grid->dims().count(), 0.2f);
      std::fill_n(grid->sigma_s(s), grid->dims().count(), 1.8f);
      std::fill_n(grid->g(s), grid->dims().count(), 0.5f);
    }
    scene.medium = std::make_shared<GridMedium>(grid);
  } else {
    scene.medium = std::make_shared<HomogeneousMedium>(
        BBox3({-1, -1, -1}, {1, 1, 1}), wavelengths, std::vector<double>{0.2, 0.2},
        std::vector<double>{1.8, 1.8}, std::vector<double>{0.5, 0.5}, 0.0);
  }
  scene.sky = Sky::blackbody(0.0, false);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 50.0;  // 40° from the zenith
  scene.sun.azimuth_deg = 30.0;
  scene.sun.angular_diameter_deg = 1.0;
  Sensor sensor;
  sensor.name = "vis";
  sensor.camera = PinholeCamera({0, -6, 1}, {0, 0, 0}, {0, 0, 1}, 45.0, size, size);
  sensor.bands = {Band::flat("narrow", 0.549, 0.551)};
  scene.sensors.push_back(sensor);
  scene.settings.spectral_nodes_per_band = 1;
  scene.settings.camera_sees_sun = false;
  return scene;
}

struct Blocks {
  std::vector<double> mean, stderr_mean;
};

Blocks block_means(const SensorImage& img, int size) {
  const int nb = size / 8;
  Blocks b;
  b.mean.assign(nb * nb, 0.0);
  b.stderr_mean.assign(nb * nb, 0.0);
  const auto& band = img.bands[0];
  for (int y = 0; y < nb * 8; ++y)
    for (int x = 0; x < nb * 8; ++x) {
      const std::size_t p = static_cast<std::size_t>(y) * size + x, k = (y / 8) * nb + x / 8;
      b.mean[k] += band.radiance[p] / 64.0;
      if (!band.radiance_stderr.empty())  // deterministic methods have none
        b.stderr_mean[k] += band.radiance_stderr[p] * band.radiance_stderr[p] / (64.0 * 64.0);
    }
  for (double& s : b.stderr_mean) s = std::sqrt(s);
  return b;
}

// RMS relative difference over blocks above 1 % of the reference's largest.
double block_error(const Blocks& ref, const Blocks& b,
                   const std::vector<double>* stderr_of = nullptr) {
  double largest = 0;
  for (const double m : ref.mean) largest = std::max(largest, m);
  double sum = 0;
  int n = 0;
  for (std::size_t k = 0; k < ref.mean.size(); ++k) {
    if (!(ref.mean[k] > 0.01 * largest)) continue;
    const double d = stderr_of ? (*stderr_of)[k] / ref.mean[k] : b.mean[k] / ref.mean[k] - 1.0;
    sum += d * d;
    ++n;
  }
  return std::sqrt(sum / n);
}

// The reference's block means, kept between runs (plain text: size, spp,
// block count, then the means and their standard errors).
// Reads a reference kept by write_reference: false if `path` does not
// exist; exits with a message if it holds another size or spp (rather than
// rendering and overwriting it).
bool read_reference(const std::string& path, int size, int spp, Blocks& out) {
  std::ifstream in(path);
  if (!in) return false;
  int file_size = 0, file_spp = 0;
  std::size_t count = 0;
  if (!(in >> file_size >> file_spp >> count)) {
    std::fprintf(stderr,
                 "bench_smoke_cube: %s: not a reference file (size spp count, then blocks)\n",
                 path.c_str());
    std::exit(2);
  }
  if (file_size != size || file_spp != spp) {
    std::fprintf(stderr,
                 "bench_smoke_cube: %s holds a reference of %d² px at %d spp; give --size %d "
                 "--reference-spp %d, or another file\n",
                 path.c_str(), file_size, file_spp, file_size, file_spp);
    std::exit(2);
  }
  out.mean.resize(count);
  out.stderr_mean.resize(count);
  for (std::size_t k = 0; k < count; ++k)
    if (!(in >> out.mean[k] >> out.stderr_mean[k])) {
      std::fprintf(stderr, "bench_smoke_cube: %s: block %zu of %zu is missing\n", path.c_str(), k,
                   count);
      std::exit(2);
    }
  return true;
}

void write_reference(const std::string& path, int size, int spp, const Blocks& b) {
  std::ofstream out(path);
  out.precision(17);
  out << size << ' ' << spp << ' ' << b.mean.size() << '\n';
  for (std::size_t k = 0; k < b.mean.size(); ++k)
    out << b.mean[k] << ' ' << b.stderr_mean[k] << '\n';
}

struct Timed {
  double seconds;
  Blocks blocks;
  RenderStats stats;
};

Timed render_timed(Scene& scene) {
  const auto t0 = bench::Clock::now();
  const SensorImage img = render_sensor(scene, scene.sensors[0]);
  return {bench::seconds_since(t0), block_means(img, scene.sensors[0].camera.width()), img.stats};
}

constexpr const char* kUsage =
    "usage: bench_smoke_cube [--reference-spp 4096] [--target 0.02] [--threads N] [--size 256]\n"
    "         [--methods path-tracer,photonmap,radiance-cache] [--reference-file F]\n"
    "         [--sh-degree 3] [--kernel R] [--voxel M] [--photons 25000] [--steps 12]\n"
    "         [--error-map F] [--cache-spp 4] [--medium grid|box] [--grid 32] [--seed 1]\n";

}  // namespace

int main(int argc, char** argv) {
  int reference_spp = 4096, threads = 0, size = 256, sh_degree = 3, kernel = -1;
  double target = 0.02, voxel_m = -1;
  long long cache_photons = 25000;
  int max_steps = 12, cache_spp = 4, grid_voxels = 32;
  std::uint64_t seed = 1;
  std::string medium_form = "grid";
  std::string methods = "path-tracer,photonmap,radiance-cache", reference_file, error_map;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      std::printf("%s", kUsage);
      return 0;
    }
    if (i + 1 == argc) {
      std::fprintf(stderr, "option %s needs a value\n%s", a.c_str(), kUsage);
      return 2;
    }
    if (a == "--reference-spp")
      reference_spp = std::atoi(argv[i + 1]);
    else if (a == "--target")
      target = std::atof(argv[i + 1]);
    else if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--size")
      size = std::atoi(argv[i + 1]);
    else if (a == "--methods")
      methods = argv[i + 1];
    else if (a == "--reference-file")
      reference_file = argv[i + 1];
    else if (a == "--sh-degree")
      sh_degree = std::atoi(argv[i + 1]);
    else if (a == "--kernel")
      kernel = std::atoi(argv[i + 1]);
    else if (a == "--voxel")
      voxel_m = std::atof(argv[i + 1]);
    else if (a == "--error-map")
      error_map = argv[i + 1];
    else if (a == "--medium")
      medium_form = argv[i + 1];
    else if (a == "--grid")
      grid_voxels = std::atoi(argv[i + 1]);
    else if (a == "--cache-spp")
      cache_spp = std::atoi(argv[i + 1]);
    else if (a == "--steps")
      max_steps = std::atoi(argv[i + 1]);
    else if (a == "--seed")
      seed = std::strtoull(argv[i + 1], nullptr, 10);
    else if (a == "--photons")
      cache_photons = std::atoll(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n%s", a.c_str(), kUsage);
      return 2;
    }
  }
  const int cores = resolve_thread_count(threads);
  std::printf("smoke cube, %d² px, %d threads; reference: path tracer at %d spp\n", size, cores,
              reference_spp);
  if (grid_voxels < 1 || grid_voxels > 512) {
    std::fprintf(stderr, "--grid: voxels per side must lie in [1, 512]\n");
    return 2;
  }
  Scene scene = smoke_cube(size, medium_form == "grid", grid_voxels);
  scene.settings.threads = threads;
  scene.settings.method = RenderMethod::kPathTracer;
  scene.settings.samples_per_pixel = reference_spp;
  scene.settings.seed = 12345;
  if (sh_degree >= 0) scene.settings.radiance_cache.sh_degree = sh_degree;
  if (kernel >= 0) scene.settings.radiance_cache.kernel_radius_nodes = kernel;
  if (voxel_m >= 0) scene.settings.radiance_cache.voxel_m = voxel_m;
  Timed ref{0.0, {}, {}};
  if (reference_file.empty() || !read_reference(reference_file, size, reference_spp, ref.blocks)) {
    ref = render_timed(scene);
    if (!reference_file.empty()) write_reference(reference_file, size, reference_spp, ref.blocks);
  }
  const double ref_error = block_error(ref.blocks, ref.blocks, &ref.blocks.stderr_mean);
  std::printf("reference: %.1f s, its own block error (stderr, RMS relative) %.4f\n", ref.seconds,
              ref_error);

  std::stringstream list(methods);
  std::string name;
  while (std::getline(list, name, ',')) {
    const auto method = parse_render_method(name);
    if (!method) {
      std::fprintf(stderr, "unknown method %s\n", name.c_str());
      return 2;
    }
    scene.settings.method = *method;
    scene.settings.seed = seed;
    double first_under = -1;
    for (int step = 0; step < max_steps; ++step) {
      const long long effort = 1ll << step;
      std::string what;
      if (*method == RenderMethod::kPathTracer) {
        scene.settings.samples_per_pixel = static_cast<int>(16 * effort);
        what = std::to_string(scene.settings.samples_per_pixel) + " spp";
      } else if (*method == RenderMethod::kPhotonMap) {
        scene.settings.samples_per_pixel = 4;
        scene.settings.photon_map.photons_per_node = 50000 * effort;
        what = std::to_string(scene.settings.photon_map.photons_per_node) + " photons, 4 spp";
      } else {
        scene.settings.samples_per_pixel = cache_spp;
        scene.settings.radiance_cache.photons_per_node = cache_photons * effort;
        what = std::to_string(scene.settings.radiance_cache.photons_per_node) + " photons";
      }
      const Timed t = render_timed(scene);
      const double error = block_error(ref.blocks, t.blocks);
      if (!error_map.empty()) {
        std::ofstream map(error_map);
        map << "block_x,block_y,reference,relative_difference\n";
        const int nb = size / 8;
        for (int k = 0; k < nb * nb; ++k)
          map << k % nb << ',' << k / nb << ',' << ref.blocks.mean[k] << ','
              << t.blocks.mean[k] / ref.blocks.mean[k] - 1.0 << '\n';
      }
      std::printf("%-15s %-28s %8.2f s  error %.4f", name.c_str(), what.c_str(), t.seconds, error);
      // Where the photon methods' time goes: tracing pass 1, building (the
      // kd-tree, or the cache's splat and sun depths), the camera rays.
      if (t.stats.photon_seconds > 0.0)
        std::printf("  (tracing %.2f s, building %.2f s, rays %.2f s)",
                    t.stats.photon_trace_seconds, t.stats.photon_build_seconds,
                    t.seconds - t.stats.photon_seconds);
      std::printf("\n");
      std::fflush(stdout);
      if (error <= target) {
        first_under = t.seconds;
        break;
      }
      if (t.seconds > 120.0) break;
    }
    if (first_under >= 0)
      std::printf("%-15s time to %.3g: %.2f s\n", name.c_str(), target, first_under);
    else
      std::printf("%-15s did not reach %.3g\n", name.c_str(), target);
  }
  return 0;
}
