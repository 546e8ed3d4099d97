// Streaming a long keyframe sequence: a synthetic cloud of 200 keyframes is
// written to disk, then staged at 400 times across its life. Prints the peak
// resident memory against the size of one keyframe and of the whole sequence,
// and the staging time per frame; nothing asserted.
//   bench_keyframe_sequence [--keyframes 200] [--resolution 64] [--dir /tmp/obscura_sequence]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "obscura/io/cloud_manifest.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/scene/animated_cloud.h"

using namespace obscura;

namespace {
double current_rss_mib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * 4096.0 / 1048576.0;
}
double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;  // ru_maxrss is in KiB on Linux
}
}  // namespace

int main(int argc, char** argv) {
  int keyframes = 200, resolution = 64;
  std::filesystem::path dir = std::filesystem::temp_directory_path() / "obscura_sequence_bench";
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--keyframes")
      keyframes = std::atoi(argv[i + 1]);
    else if (a == "--resolution")
      resolution = std::atoi(argv[i + 1]);
    else if (a == "--dir")
      dir = argv[i + 1];
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  if (keyframes < 3) {
    std::fprintf(stderr, "--keyframes must be >= 3\n");
    return 2;
  }
  std::filesystem::create_directories(dir);
  const double rss_start = peak_rss_mib();
  auto t0 = std::chrono::steady_clock::now();
  nlohmann::json frames = nlohmann::json::array();
  std::size_t keyframe_bytes = 0;
  for (int k = 0; k < keyframes; ++k) {
    GaussianPuffSpec spec;
    spec.resolution = resolution;
    spec.radius_m = 2.0 + 0.02 * k;  // a puff that grows and drifts
    spec.center_m = {0.05 * k, 0, 3};
    spec.wavelengths_um = {4, 10};
    spec.peak_sigma_a = {0.3, 0.4};
    spec.peak_sigma_s = {0.1, 0.05};
    spec.g = {0.5, 0.3};
    spec.temperature_excess_k = 15.0;
    const VoxelGrid grid = make_gaussian_puff(spec);
    keyframe_bytes = grid.memory_bytes();
    const std::string name = "k" + std::to_string(k) + ".vdb";
    write_cloud_keyframe(dir / name, grid, 0.5 * k);
    frames.push_back({{"file", name}, {"time", 0.5 * k}});
  }
  const double write_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const nlohmann::json manifest = {
      {"keyframes", frames},
      {"lifecycle",
       // Initialisation plays almost every keyframe once; a short loop at the end.
       {{"init_end", keyframes - 3},
        {"loop_start", keyframes - 3},
        {"loop_end", keyframes - 2},
        {"loop_wrap", 0.5},
        {"extinction_start", keyframes - 1}}}};
  std::ofstream(dir / "cloud.json") << manifest.dump();
  const double rss_after_write = peak_rss_mib();

  AnimatedCloud cloud("bench", read_cloud_manifest(dir / "cloud.json"), 0.0, std::nullopt, 3);
  const double duration = 0.5 * (keyframes - 1);
  const int frames_staged = 2 * keyframes;
  t0 = std::chrono::steady_clock::now();
  std::size_t voxels = 0;
  for (int f = 0; f < frames_staged; ++f) {
    auto grid = cloud.stage_grid(duration * f / frames_staged);
    if (grid) voxels += grid->dims().count();
  }
  const double stage_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("keyframe sequence benchmark\n");
  std::printf(
      "  %d keyframes of %d^3 voxels, 2 spectral samples: %.1f MiB each in memory, %.1f MiB "
      "for the whole sequence (written in %.1f s)\n",
      keyframes, resolution, keyframe_bytes / 1048576.0, keyframes * keyframe_bytes / 1048576.0,
      write_s);
  std::printf(
      "  staged %d frames across the sequence: %.1f ms per frame, %zu keyframe loads, %zu "
      "cache hits (cache of %zu)\n",
      frames_staged, 1e3 * stage_s / frames_staged, cloud.cache().loads(), cloud.cache().hits(),
      cloud.cache().capacity());
  std::printf(
      "  peak RSS: %.1f MiB at start, %.1f MiB after writing, %.1f MiB after staging "
      "(resident now %.1f MiB)\n",
      rss_start, rss_after_write, peak_rss_mib(), current_rss_mib());
  std::printf("  (%zu voxels staged)\n", voxels);
  std::filesystem::remove_all(dir);
  return 0;
}
