// Cost of staging a cloud at a new time: per-voxel interpolation of two 256³
// keyframes (same layout) and, for comparison, with resampling onto the union
// of two different extents. Prints milliseconds per frame; nothing asserted.
//   bench_staging [--resolution 256] [--samples 2]
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_timer.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/keyframe_interpolation.h"

using namespace obscura;
using bench::seconds_since;

int main(int argc, char** argv) {
  int resolution = 256, samples = 2;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--resolution")
      resolution = std::atoi(argv[i + 1]);
    else if (a == "--samples")
      samples = std::atoi(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  GaussianPuffSpec spec;
  spec.resolution = resolution;
  spec.radius_m = 5.0;
  spec.extent_radii = 3.0;
  spec.wavelengths_um.clear();
  spec.peak_sigma_a.clear();
  spec.peak_sigma_s.clear();
  spec.g.clear();
  for (int s = 0; s < samples; ++s) {
    spec.wavelengths_um.push_back(3.0 + s);
    spec.peak_sigma_a.push_back(0.2);
    spec.peak_sigma_s.push_back(0.1);
    spec.g.push_back(0.5);
  }
  spec.temperature_excess_k = 20;
  const VoxelGrid a = make_gaussian_puff(spec);
  spec.peak_sigma_a.assign(samples, 0.35);  // same grid, other values
  spec.temperature_excess_k = 10;
  const VoxelGrid b = make_gaussian_puff(spec);
  spec.resolution = resolution / 2;
  spec.center_m = {3.0, 0.0, 0.0};
  const VoxelGrid c = make_gaussian_puff(spec);  // coarser and shifted: needs resampling

  const int repeats = 3;
  auto t0 = std::chrono::steady_clock::now();
  double checksum = 0;
  for (int r = 0; r < repeats; ++r) checksum += interpolate_keyframes(a, b, 0.37).sigma_a(0)[12345];
  const double same = seconds_since(t0) / repeats;
  t0 = std::chrono::steady_clock::now();
  const VoxelGrid u = interpolate_keyframes(a, c, 0.37);
  const double resampled = seconds_since(t0);
  std::printf("staging benchmark (%d spectral samples, %d channels per voxel)\n", samples,
              a.channel_count());
  std::printf("  same layout   %d^3: %.1f ms per frame (%.1f M voxels/s)\n", resolution, 1e3 * same,
              a.dims().count() / same / 1e6);
  std::printf("  resampled     %d^3 + %d^3 -> %dx%dx%d: %.1f ms per frame\n", resolution,
              resolution / 2, u.dims().nx, u.dims().ny, u.dims().nz, 1e3 * resampled);
  std::printf("  (checksum %g)\n", checksum);
  return 0;
}
