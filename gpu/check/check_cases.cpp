#include "check_cases.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <stdexcept>

#include "camera_rays.h"
#include "image_difference.h"
#include "obscura/gpu/host_executor.h"
#include "procedural_cloud.h"

namespace obscura::gpu_check {
namespace {

// The H200's measured memory bandwidth (the figure), bytes/s.
constexpr double kH200Bandwidth = 4.3e12;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

Mat3 rotation_z_deg(double deg) {
  const double c = std::cos(deg * std::numbers::pi / 180.0),
               s = std::sin(deg * std::numbers::pi / 180.0);
  return Mat3::from_rows({c, -s, 0}, {s, c, 0}, {0, 0, 1});
}

Mat3 tilted() {
  const double a = 0.35, b = -0.6;  // about x, then y, radians
  const Mat3 rx =
      Mat3::from_rows({1, 0, 0}, {0, std::cos(a), -std::sin(a)}, {0, std::sin(a), std::cos(a)});
  const Mat3 ry =
      Mat3::from_rows({std::cos(b), 0, std::sin(b)}, {0, 1, 0}, {-std::sin(b), 0, std::cos(b)});
  return rotation_z_deg(40.0) * ry * rx;
}

// One march on both sides: the device's best of `repeats` timed runs after
// a first untimed one, the CPU once.
struct BothMarches {
  MarchResult gpu, cpu;
  double kernel_s = 0, transfer_s = 0, cpu_s = 0;
  std::uint64_t cells = 0;         // the device's, summed over items
  std::uint64_t cells_differ = 0;  // items whose cell counts differ
};

BothMarches march_both(LatticeExecutor& gpu, LatticeExecutor& cpu, const MarchRequest& request,
                       const std::vector<MarchRay>& rays, int repeats) {
  BothMarches m;
  gpu.march(request, rays, m.gpu);  // the first launch loads the kernel
  m.kernel_s = m.transfer_s = 1e300;
  for (int r = 0; r < repeats; ++r) {
    gpu.march(request, rays, m.gpu);
    m.kernel_s = std::min(m.kernel_s, gpu.last_times().kernel_seconds);
    m.transfer_s = std::min(m.transfer_s, gpu.last_times().transfer_seconds);
  }
  const auto start = std::chrono::steady_clock::now();
  cpu.march(request, rays, m.cpu);
  m.cpu_s = seconds_since(start);
  for (std::size_t i = 0; i < m.gpu.cells.size(); ++i) {
    m.cells += m.gpu.cells[i];
    m.cells_differ += m.gpu.cells[i] != m.cpu.cells[i];
  }
  return m;
}

std::vector<double> slice(const std::vector<double>& v, std::size_t k, std::size_t count) {
  return {v.begin() + static_cast<std::ptrdiff_t>(k * count),
          v.begin() + static_cast<std::ptrdiff_t>((k + 1) * count)};
}

// Prints output k's radiance and transmittance differences (and the
// attenuation's, what the background is seen through: the transmittance, or
// more with the radiance cache's delta-M), the means over the rays the
// medium dims; true when they agree.
bool compare_output(const char* label, const BothMarches& m, std::size_t k, std::size_t count) {
  const std::vector<double> cpu_t = slice(m.cpu.transmittance, k, count);
  std::vector<bool> dimmed(count);
  double mean_l = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    dimmed[i] = cpu_t[i] < 1.0;
    mean_l += m.cpu.radiance[k * count + i] / static_cast<double>(count);
  }
  const ImageDifference l =
      image_difference(slice(m.gpu.radiance, k, count), slice(m.cpu.radiance, k, count), dimmed);
  const ImageDifference t = image_difference(slice(m.gpu.transmittance, k, count), cpu_t, dimmed);
  const ImageDifference a = image_difference(slice(m.gpu.attenuation, k, count),
                                             slice(m.cpu.attenuation, k, count), dimmed);
  const bool ok = agrees(l) && agrees(t) && agrees(a);
  // What the images hold (a comparison of empty images would prove nothing):
  // the CPU's mean radiance and the share of rays the medium dims.
  std::printf(
      "  %-18s L %.3e, %3.0f%% dimmed   radiance %.2e / %.2e   transmittance %.2e / %.2e   "
      "attenuation %.2e / %.2e   %s\n",
      label, mean_l, 100.0 * static_cast<double>(l.pixels) / static_cast<double>(count), l.mean,
      l.worst, t.mean, t.worst, a.mean, a.worst, ok ? "ok" : "DISAGREE");
  if (!ok)
    std::printf("    worst radiance at ray %zu: gpu %.9g cpu %.9g\n", l.worst_pixel,
                m.gpu.radiance[k * count + l.worst_pixel],
                m.cpu.radiance[k * count + l.worst_pixel]);
  return ok;
}

void print_header() {
  std::printf("  %-18s %-26s relative difference GPU - CPU: mean / worst pixel\n", "image (node)",
              "CPU mean radiance");
}

// τ_sun of every slot inside the lattice, both sides, compared.
bool compare_sun_depths(const ProceduralCloud& cloud, LatticeExecutor& gpu, LatticeExecutor& cpu) {
  const FrameLattice f = cloud.frame();
  bool ok = true;
  for (int u = 0; u < f.nodes(); ++u) {
    const std::vector<float> g = gpu.records(u), c = cpu.records(u);
    std::vector<double> tg, tc;
    std::vector<bool> deep;  // the mean over slots the sun reaches through medium
    for (std::uint64_t slot = 0; slot < f.slot_count(); ++slot) {
      tg.push_back(g[slot * f.stride + record::kTauSun]);
      tc.push_back(c[slot * f.stride + record::kTauSun]);
      deep.push_back(tc.back() > 0.0);
    }
    const ImageDifference d = image_difference(tg, tc, deep);
    const bool node_ok = agrees(d);
    ok = ok && node_ok;
    double mean = 0.0;
    for (const double t : tc) mean += t / static_cast<double>(tc.size());
    char label[48];
    std::snprintf(label, sizeof label, "tau_sun %.3g um", cloud.spec().wavelengths_um[u]);
    std::printf("  %-18s mean %.3e, %zu of %zu slots > 0   %.2e / %.2e   %s\n", label, mean,
                d.pixels, tc.size(), d.mean, d.worst, node_ok ? "ok" : "DISAGREE");
  }
  return ok;
}

bool case_layout(const CheckOptions& o) {
  std::printf("== layout: sizes and offsets of the structs that cross to the device\n");
  std::uint64_t host[kStructLayoutValues];
  struct_layout(host);
  const auto device = o.device_layout();
  int differ = 0;
  for (int i = 0; i < kStructLayoutValues; ++i)
    if (host[i] != device[i]) {
      ++differ;
      std::printf("  %s: host %llu, device %llu\n", kStructLayoutNames[i],
                  static_cast<unsigned long long>(host[i]),
                  static_cast<unsigned long long>(device[i]));
    }
  std::printf("  %d values, %d differ   %s\n", kStructLayoutValues, differ, differ ? "FAIL" : "ok");
  return differ == 0;
}

// Emission–absorption on a rotated, sparse two-lobe grid at three
// wavelengths: one camera outside, one inside the cloud, rays ending on a
// ground through the cloud.
bool case_ea(const CheckOptions& o) {
  CloudSpec spec;
  spec.voxels = {48, 40, 56};
  spec.voxel_m = 0.25;
  spec.origin_m = {-6, -5, -2};
  spec.rotation = tilted();
  spec.lobes = {{{-1.0, 0.5, 2.0}, 2.0, 1.0}, {{2.0, -1.0, 4.0}, 1.2, 0.7}};
  spec.cutoff = 1e-3;
  spec.wavelengths_um = {3.5, 4.0, 4.6};
  spec.peak_sigma_a = {0.8, 0.5, 1.1};
  spec.peak_sigma_s = {0.4, 0.6, 0.2};
  spec.ambient_k = 285.0;
  spec.excess_k = 120.0;
  const ProceduralCloud cloud(spec);
  std::printf(
      "== ea: emission-absorption, %dx%dx%d rotated sparse grid (%zu of %d blocks), "
      "3 nodes, 2 cameras 256x192, ground\n",
      spec.voxels[0], spec.voxels[1], spec.voxels[2],
      static_cast<std::size_t>(cloud.slots() / LatticeView::kBlockNodes),
      cloud.frame().view.block_dims[0] * cloud.frame().view.block_dims[1] *
          cloud.frame().view.block_dims[2]);
  const std::unique_ptr<LatticeExecutor> device = o.device();
  LatticeExecutor& gpu = *device;
  HostExecutor cpu(o.cpu_threads);
  gpu.load(cloud.frame());
  cpu.load(cloud.frame());
  MarchRequest request;
  request.source = MarchSource::kEmission;
  request.output_node = {0, 1, 2};
  bool ok = true;
  print_header();
  const Vec3 centre = cloud.centre_m();
  for (const bool inside : {false, true}) {
    Camera cam;
    cam.position_m = inside ? centre + Vec3(0.3, -0.2, 0.1) : centre + Vec3(2, -25, 6);
    cam.look_at_m = inside ? centre + Vec3(5, 3, -1) : centre;
    cam.horizontal_fov_deg = inside ? 90.0 : 40.0;
    cam.width = 256;
    cam.height = 192;
    cam.ground = true;
    cam.ground_m = centre.z - 1.5;
    const std::vector<MarchRay> rays = camera_rays(cam);
    const BothMarches m = march_both(gpu, cpu, request, rays, 1);
    for (std::size_t k = 0; k < 3; ++k) {
      char label[48];
      std::snprintf(label, sizeof label, "%s %.2g um", inside ? "inside" : "outside",
                    spec.wavelengths_um[k]);
      ok = compare_output(label, m, k, rays.size()) && ok;
    }
    std::printf("  %-18s %llu of %zu rays cross a different number of cells\n", "",
                static_cast<unsigned long long>(m.cells_differ), m.gpu.cells.size());
  }
  return ok;
}

// The radiance cache at every spherical-harmonic degree: the sun's optical
// depths from both sides, then the march with the sun's single scattering,
// a shadow over the lower part of the cloud and the synthetic harmonics.
bool case_cache(const CheckOptions& o) {
  std::printf(
      "== cache: radiance cache, 40x32x24 rotated sparse grid, 2 nodes, sun, degrees 0-3, "
      "camera 192x128\n");
  bool ok = true;
  for (int degree = 0; degree <= 3; ++degree) {
    CloudSpec spec;
    spec.voxels = {40, 32, 24};
    spec.voxel_m = 0.5;
    spec.origin_m = {-10, -8, 0};
    spec.rotation = rotation_z_deg(25.0);
    spec.lobes = {{{-2, 0, 5}, 3.0, 1.0}, {{4, 2, 6}, 2.0, 0.8}};
    spec.cutoff = 1e-3;
    spec.wavelengths_um = {0.55, 1.064};
    spec.peak_sigma_a = {0.05, 0.04};
    spec.peak_sigma_s = {1.5, 1.2};
    spec.g = 0.6;
    spec.sh_degree = degree;
    spec.shadow_below_m = 3.0;
    const ProceduralCloud cloud(spec);
    const std::unique_ptr<LatticeExecutor> device = o.device();
    LatticeExecutor& gpu = *device;
    HostExecutor cpu(o.cpu_threads);
    gpu.load(cloud.frame());
    cpu.load(cloud.frame());
    const Vec3 to_sun = normalize(Vec3(-0.5, -0.6, 0.62));
    gpu.sun_depths(to_sun);
    cpu.sun_depths(to_sun);
    std::printf(" degree %d (records of %d floats)\n", degree, cloud.stride());
    ok = compare_sun_depths(cloud, gpu, cpu) && ok;
    MarchRequest request;
    request.source = MarchSource::kCache;
    request.sh_degree = degree;
    request.sun = true;
    request.to_sun = to_sun;
    request.output_node = {0, 1};
    Camera cam;
    cam.position_m = cloud.centre_m() + Vec3(-6, -30, 4);
    cam.look_at_m = cloud.centre_m();
    cam.horizontal_fov_deg = 45.0;
    cam.width = 192;
    cam.height = 128;
    cam.ground = true;
    const std::vector<MarchRay> rays = camera_rays(cam);
    const BothMarches m = march_both(gpu, cpu, request, rays, 1);
    for (std::size_t k = 0; k < 2; ++k) {
      char label[48];
      std::snprintf(label, sizeof label, "march %.3g um", spec.wavelengths_um[k]);
      ok = compare_output(label, m, k, rays.size()) && ok;
    }
  }
  return ok;
}

// The benchmark: 1024x1024 rays through a 256³ grid that a puff
// fills (every cell holds medium, as bench/emission_absorption_bench.cpp),
// one LWIR node.
bool case_ea256(const CheckOptions& o) {
  CloudSpec spec;
  spec.voxels = {256, 256, 256};
  spec.voxel_m = 30.0 / 256;
  spec.origin_m = {-15, -15, -15};
  spec.lobes = {{{0, 0, 0}, 10.0, 1.0}};  // the bench's puff: σ = 10 m, grid ±1.5 σ
  spec.wavelengths_um = {10.0};
  spec.peak_sigma_a = {0.05};
  spec.peak_sigma_s = {0.02};
  spec.ambient_k = 290.0;
  spec.excess_k = 30.0;
  const auto build_start = std::chrono::steady_clock::now();
  const ProceduralCloud cloud(spec);
  std::printf(
      "== ea256: emission-absorption benchmark, 256^3 grid filled (%.0f MB of records, "
      "made in %.1f s), 1024x1024 rays, 1 node\n",
      cloud.record_bytes() / 1e6, seconds_since(build_start));
  const std::unique_ptr<LatticeExecutor> device = o.device();
  LatticeExecutor& gpu = *device;
  HostExecutor cpu(o.cpu_threads);
  gpu.load(cloud.frame());
  std::printf("  upload            %8.1f ms\n", 1e3 * gpu.last_times().transfer_seconds);
  cpu.load(cloud.frame());
  Camera cam;
  cam.position_m = {0, -60, 0};
  cam.look_at_m = {0, 0, 0};
  cam.horizontal_fov_deg = 28.0;
  cam.width = cam.height = 1024;
  const std::vector<MarchRay> rays = camera_rays(cam);
  MarchRequest request;
  request.output_node = {0};
  const BothMarches m = march_both(gpu, cpu, request, rays, o.repeats);
  const double steps_per_s = static_cast<double>(m.cells) / m.kernel_s;
  // Two interpolated points per cell (the entry is the previous exit), 8
  // corner records of 4 floats each: what the march asks of memory, cache
  // hits included.
  const double demand = static_cast<double>(m.cells) * 2 * 8 * record::kMediumStride * 4;
  std::printf("  kernel            %8.2f ms (best of %d), transfers %.2f ms\n", 1e3 * m.kernel_s,
              o.repeats, 1e3 * m.transfer_s);
  std::printf("  voxel steps       %llu (%.1f per ray), %.3g per second\n",
              static_cast<unsigned long long>(m.cells), static_cast<double>(m.cells) / rays.size(),
              steps_per_s);
  std::printf("  record reads      %.3g GB/s = %.3g of 4.3 TB/s (demand, cache hits included)\n",
              demand / m.kernel_s / 1e9, demand / m.kernel_s / kH200Bandwidth);
  std::printf("  records once      %.3g GB/s = %.3g of 4.3 TB/s (each record read once)\n",
              cloud.record_bytes() / m.kernel_s / 1e9,
              cloud.record_bytes() / m.kernel_s / kH200Bandwidth);
  std::printf("  CPU reference     %8.2f s on %d threads (%.3g voxel steps/s): GPU %.3gx\n",
              m.cpu_s, o.cpu_threads, static_cast<double>(m.cells) / m.cpu_s, m.cpu_s / m.kernel_s);
  print_header();
  const bool ok = compare_output("lwir 10 um", m, 0, rays.size());
  std::printf("  %-18s %llu of %zu rays cross a different number of cells\n", "",
              static_cast<unsigned long long>(m.cells_differ), m.gpu.cells.size());
  return ok;
}

// The demo's frame as the GPU would render it: four sensors at 1024x512, one
// band of two nodes each (visible, laser, MWIR, LWIR: 8 distinct nodes), the
// radiance cache at degree 2 over a 128x96x48 grid of eight puffs at 1 m,
// the sun, a ground. Per frame: the records' upload, the sun kernel and the
// four marches.
bool case_demo(const CheckOptions& o) {
  CloudSpec spec;
  spec.voxels = {128, 96, 48};
  spec.voxel_m = 1.0;
  spec.origin_m = {-60, -30, 0};
  spec.rotation = rotation_z_deg(10.0);
  for (int i = 0; i < 8; ++i) {
    const double a = (-60.0 + 120.0 * i / 7.0) * std::numbers::pi / 180.0;
    spec.lobes.push_back(
        {{30.0 * std::sin(a), 30.0 * std::cos(a) - 5.0, 8.0 + 1.5 * i}, 6.0 + 0.5 * i, 1.0});
  }
  spec.cutoff = 1e-3;
  spec.wavelengths_um = {0.5, 0.6, 1.06, 1.07, 3.8, 4.6, 8.5, 11.0};
  spec.peak_sigma_a = {0.02, 0.02, 0.02, 0.02, 0.05, 0.05, 0.08, 0.08};
  spec.peak_sigma_s = {0.6, 0.55, 0.45, 0.45, 0.1, 0.08, 0.03, 0.02};
  spec.g = 0.7;
  spec.ambient_k = 288.0;
  spec.excess_k = 60.0;
  spec.sh_degree = 2;
  spec.shadow_below_m = 2.0;
  const ProceduralCloud cloud(spec);
  std::printf(
      "== demo: 4 sensors 1024x512, 8 nodes (2 per sensor), radiance cache degree 2, "
      "128x96x48 grid, %zu blocks, %.0f MB of records\n",
      static_cast<std::size_t>(cloud.slots() / LatticeView::kBlockNodes),
      cloud.record_bytes() / 1e6);
  const std::unique_ptr<LatticeExecutor> device = o.device();
  LatticeExecutor& gpu = *device;
  HostExecutor cpu(o.cpu_threads);
  gpu.load(cloud.frame());
  const double upload_s = gpu.last_times().transfer_seconds;
  cpu.load(cloud.frame());
  const Vec3 to_sun = normalize(Vec3(-0.58, -0.58, 0.57));
  gpu.sun_depths(to_sun);  // the first launch loads the kernel
  double sun_s = 1e300;
  for (int r = 0; r < o.repeats; ++r) {
    gpu.sun_depths(to_sun);
    sun_s = std::min(sun_s, gpu.last_times().kernel_seconds);
  }
  const auto cpu_sun_start = std::chrono::steady_clock::now();
  cpu.sun_depths(to_sun);
  const double cpu_sun_s = seconds_since(cpu_sun_start);
  std::printf("  upload            %8.2f ms\n", 1e3 * upload_s);
  std::printf("  sun kernel        %8.2f ms (CPU %.2f s)\n", 1e3 * sun_s, cpu_sun_s);
  bool ok = compare_sun_depths(cloud, gpu, cpu);
  const char* names[4] = {"tv", "laser", "mwir", "lwir"};
  double frame_kernel = sun_s, frame_transfer = upload_s, frame_cpu = cpu_sun_s;
  print_header();
  for (int s = 0; s < 4; ++s) {
    MarchRequest request;
    request.source = MarchSource::kCache;
    request.sh_degree = 2;
    request.sun = true;
    request.to_sun = to_sun;
    request.output_node = {2 * s, 2 * s + 1};
    Camera cam;
    cam.position_m = {0, -1000, 8};
    cam.look_at_m = {0, 0, 10};
    cam.horizontal_fov_deg = 7.0;
    cam.width = 1024;
    cam.height = 512;
    cam.ground = true;
    const std::vector<MarchRay> rays = camera_rays(cam);
    const BothMarches m = march_both(gpu, cpu, request, rays, o.repeats);
    frame_kernel += m.kernel_s;
    frame_transfer += m.transfer_s;
    frame_cpu += m.cpu_s;
    std::printf("  %-6s march       %8.2f ms, transfers %.2f ms, %.3g voxel steps/s, CPU %.2f s\n",
                names[s], 1e3 * m.kernel_s, 1e3 * m.transfer_s,
                static_cast<double>(m.cells) / m.kernel_s, m.cpu_s);
    for (std::size_t k = 0; k < 2; ++k) {
      char label[48];
      std::snprintf(label, sizeof label, "%s %.3g um", names[s],
                    spec.wavelengths_um[request.output_node[k]]);
      ok = compare_output(label, m, k, rays.size()) && ok;
    }
  }
  std::printf(
      "  frame on the GPU  %8.2f ms in kernels, %.2f ms with the copies (target < 100 "
      "ms, without the CPU's photons and camera rays); CPU reference %.2f s\n",
      1e3 * frame_kernel, 1e3 * (frame_kernel + frame_transfer), frame_cpu);
  return ok;
}

}  // namespace

const std::vector<std::string>& case_names() {
  static const std::vector<std::string> names = {"layout", "ea", "cache", "ea256", "demo"};
  return names;
}

bool run_case(const std::string& name, const CheckOptions& options) {
  if (name == "layout") return case_layout(options);
  if (name == "ea") return case_ea(options);
  if (name == "cache") return case_cache(options);
  if (name == "ea256") return case_ea256(options);
  if (name == "demo") return case_demo(options);
  throw std::invalid_argument("no case " + name);
}

}  // namespace obscura::gpu_check
