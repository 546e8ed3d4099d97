// Cost of preparing the paper's scenario with the built-in dispersion model
// (issue #6 target: under one minute on 2 cores at 1 m voxels): 8 smoke
// grenades on an arc in front of a main battle tank, wind from the tank's left,
// keyframes every second for 30 s. Prints wall time, grid size, throughput,
// memory and the grid's mass balance; nothing asserted.
//   bench_dispersion [--threads 2] [--voxel-m 1] [--radius-m 30] [--burn-s 60]
//                    [--puffs-per-second 10] [--frames 30] [--stability D]
//                    [--sigma-set ccps-puff]
//
// The scenario (docs/dispersion.md, "Benchmark"): the tank is at the origin
// facing north (+y), so its left is west and the wind blows from 270° at
// 3 m/s (10 m reference), class D (overcast, docs/domain.md §3.5). Each grenade is a
// burning 360 g terephthalic-acid fill (M83-like, docs/domain.md §2.6; yield 1)
// emitting for ~1 min (burning grenades, docs/domain.md §2.6), lying on the ground
// (release height 0.3 m) on a 30 m arc from −52.5° to +52.5° either side of the
// bow, launched as a salvo 0.05 s apart. σ0 = 1.5 m, 30 K excess at the
// source decaying in 10 s: illustrative, not measured values.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <string>

#include "bench_timer.h"
#include "obscura/core/parallel.h"
#include "obscura/prep/dispersion/dispersion_grid.h"

using namespace obscura;
using bench::seconds_since;

int main(int argc, char** argv) {
  int threads = 2, frames = 30;
  double voxel_m = 1.0, radius_m = 30.0, burn_s = 60.0, puffs_per_second = 10.0;
  StabilityClass stability = StabilityClass::kD;
  SigmaSet sigma_set = SigmaSet::kCcpsPuff;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--threads")
      threads = std::atoi(argv[i + 1]);
    else if (a == "--voxel-m")
      voxel_m = std::atof(argv[i + 1]);
    else if (a == "--radius-m")
      radius_m = std::atof(argv[i + 1]);
    else if (a == "--burn-s")
      burn_s = std::atof(argv[i + 1]);
    else if (a == "--puffs-per-second")
      puffs_per_second = std::atof(argv[i + 1]);
    else if (a == "--frames")
      frames = std::atoi(argv[i + 1]);
    else if (a == "--stability" && parse_stability_class(argv[i + 1]))
      stability = *parse_stability_class(argv[i + 1]);
    else if (a == "--sigma-set" && parse_sigma_set(argv[i + 1]))
      sigma_set = *parse_sigma_set(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }

  DispersionConfig config;
  config.source = "bench_dispersion";
  config.stability = stability;
  config.sigma_set = sigma_set;
  config.wind.speed_m_s = 3.0;
  config.wind.from_deg = 270.0;  // from the tank's left (west)
  config.wind.power_law_exponent = default_wind_profile_exponent(config.stability);
  for (int k = 0; k < 8; ++k) {
    const double bearing = (-52.5 + 15.0 * k) * std::numbers::pi / 180.0;
    SmokeDevice d;
    d.name = "grenade " + std::to_string(k);
    d.x_m = radius_m * std::sin(bearing);
    d.y_m = radius_m * std::cos(bearing);
    d.release_height_m = 0.3;
    d.start_s = 0.05 * k;
    d.burn_time_s = burn_s;
    d.agent_mass_g = 360.0;
    d.yield_factor = 1.0;
    d.initial_sigma_m = 1.5;
    d.source_temperature_excess_k = 30.0;
    d.temperature_decay_time_s = 10.0;
    d.puffs_per_second = puffs_per_second;
    config.devices.push_back(d);
  }
  std::vector<double> times;
  for (int f = 1; f <= frames; ++f) times.push_back(static_cast<double>(f));

  const auto t0 = std::chrono::steady_clock::now();
  const DispersionModel model(config);
  DispersionGridOptions options;
  options.voxel_size_m = voxel_m;
  options.threads = threads;
  const ConcentrationSeries series = dispersion_series(model, times, options);
  const double wall = seconds_since(t0);

  const ScalarGrid& last = series.frames.back().concentration_g_m3;
  const std::size_t voxels = last.dims.count();
  double grid_mass = 0, peak = 0;
  for (float v : last.values) {
    grid_mass += v;
    peak = std::max(peak, static_cast<double>(v));
  }
  grid_mass *= last.voxel_volume_m3();
  const double released = model.released_mass_g(times.back());
  std::size_t live_puffs = 0;
  for (double t : times) live_puffs += model.puffs_at(t).size();
  const double bytes = 2.0 * sizeof(float) * static_cast<double>(voxels) * frames;

  std::printf(
      "dispersion benchmark: 8 devices, %g m arc, %g s burn, %g puffs/s, class %s, "
      "%s, 3 m/s from 270 deg\n",
      radius_m, burn_s, puffs_per_second, to_string(stability).c_str(),
      to_string(sigma_set).c_str());
  std::printf("  threads            %d (of %d cores)\n", resolve_thread_count(threads),
              resolve_thread_count(0));
  std::printf("  frames             %d (t = 1 .. %d s)\n", frames, frames);
  std::printf("  grid               %dx%dx%d at %g m (%zu voxels, origin %.1f %.1f %.1f m)\n",
              last.dims.nx, last.dims.ny, last.dims.nz, voxel_m, voxels, last.placement.origin_m.x,
              last.placement.origin_m.y, last.placement.origin_m.z);
  std::printf("  puffs              %zu in all, %zu puff-frames\n", model.puffs().size(),
              live_puffs);
  std::printf("  wall time          %.3f s (%.1f ms per frame)\n", wall, 1e3 * wall / frames);
  std::printf("  throughput         %.1f M voxels/s written\n",
              static_cast<double>(voxels) * frames / wall / 1e6);
  std::printf("  memory             %.1f MiB (concentration + temperature)\n", bytes / 1048576.0);
  std::printf(
      "  last frame         released %.1f g, on grid %.1f g (rel. error %.2e), peak %.3g "
      "g/m3\n",
      released, grid_mass, grid_mass / released - 1.0, peak);
  return 0;
}
