#include "obscura/render/radiance_cache/radiance_cache.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/core/parallel.h"
#include "obscura/core/shared_ranges.h"
#include "obscura/render/lattice/parallel_depths.h"
#include "obscura/render/photon_map/photon_tracing.h"
#include "obscura/render/radiance_cache/estimates_at_nodes.h"
#include "obscura/render/radiance_cache/flight_splat.h"
#include "obscura/render/radiance_cache/kernel_sums.h"

namespace obscura {
namespace {

// Lattices up to this many nodes are laid out (only occupied blocks are stored).
constexpr double kMaxLatticeNodes = 4e9;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// ∫ (tent(t/r)/r) tᵐ tent(t − k) dt over t in [lo, hi], m = `moment` (0 or
// 1): the splatting kernel against the lattice's linear interpolation, one
// axis, at node offset k (|k| ≤ r), the medium present only on [lo, hi]
// (node units, relative to the kernel's node); with m = 1 the kernel's first
// moment, whose ratio to m = 0 is where the estimate sits (estimates_at_nodes.h).
// Simpson's rule between the integrand's breakpoints, where it is at most a
// cubic: exact.
double kernel_overlap(int r, int k, double lo, double hi, int moment) {
  const double a = std::max<double>(-r, lo), b = std::min<double>(r, hi);
  if (!(b > a)) return 0.0;
  auto f = [&](double t) {
    return std::max(0.0, 1.0 - std::abs(t) / r) / r * std::max(0.0, 1.0 - std::abs(t - k)) *
           (moment == 1 ? t : 1.0);
  };
  std::vector<double> breaks = {
      a, b, 0.0, static_cast<double>(k - 1), static_cast<double>(k), static_cast<double>(k + 1)};
  std::sort(breaks.begin(), breaks.end());
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double x0 = std::max(a, breaks[i]), x1 = std::min(b, breaks[i + 1]);
    if (x1 > x0) sum += (x1 - x0) / 6.0 * (f(x0) + 4.0 * f(0.5 * (x0 + x1)) + f(x1));
  }
  return sum;
}

// Per node index along one axis of `nodes` nodes, the 2r + 1 overlaps of
// kernel_overlap with the medium on [lo, hi] (node units).
std::vector<double> axis_overlaps(int r, int nodes, double lo, double hi, int moment) {
  std::vector<double> out(static_cast<std::size_t>(nodes) * (2 * r + 1));
  for (int i = 0; i < nodes; ++i)
    for (int k = -r; k <= r; ++k)
      out[static_cast<std::size_t>(i) * (2 * r + 1) + (k + r)] =
          kernel_overlap(r, k, lo - i, hi - i, moment);
  return out;
}

}  // namespace

namespace {

// Shares a per-block loop among processes: body(block) runs for the blocks
// b ≡ rank (mod N), in parallel on this process's threads, and every
// process then receives every block's `per_block` values of `data`, so each
// holds the same bits as if it had run every block itself.
void for_blocks_shared(const ProcessGroup& processes, std::size_t blocks, int threads,
                       std::vector<float>& data, std::size_t per_block,
                       const std::function<void(std::size_t)>& body) {
  const auto rank = static_cast<std::size_t>(processes.rank()),
             ranks = static_cast<std::size_t>(processes.size());
  const std::size_t own = blocks / ranks + (rank < blocks % ranks ? 1 : 0);
  parallel_for(own, threads, [&](std::size_t i) { body(i * ranks + rank); });
  share_ranges(processes, data, [&](int r) {
    IndexRanges ranges;
    for (std::size_t block = static_cast<std::size_t>(r); block < blocks; block += ranks)
      ranges.emplace_back(block * per_block, (block + 1) * per_block);
    return ranges;
  });
}

}  // namespace

namespace {

std::vector<SpectralLerp> lerps_of(const std::vector<SpectralNode>& nodes) {
  std::vector<SpectralLerp> lerps;
  for (const SpectralNode& nd : nodes) lerps.push_back(nd.lerp());
  return lerps;
}

}  // namespace

RadianceCache::RadianceCache(const Scene& scene, const std::vector<SpectralNode>& nodes,
                             const ProcessGroup& processes, SunDepths sun_depths,
                             const std::vector<std::vector<int>>& node_sensors,
                             const std::vector<long long>& node_photons,
                             const PreparationProgress& progress)
    : lattice_(*scene.medium, scene.settings.radiance_cache.voxel_m,
               scene.settings.radiance_cache.lateral_period_m,
               static_cast<std::size_t>(kMaxLatticeNodes)),
      processes_(&processes),
      sh_degree_(scene.settings.radiance_cache.sh_degree),
      sh_count_(sh_coefficient_count(sh_degree_)),
      spectral_count_(static_cast<int>(scene.medium->wavelengths_um().size())),
      has_sun_(scene.sun.enabled),
      sun_depths_(sun_depths),
      volume_(lattice_, lerps_of(nodes), record::light_stride(sh_count_),
              LatticeVolume::aligned_grid(*scene.medium, lattice_), scene.settings.threads,
              "render/radiance_cache/voxel_m") {
  const auto start = std::chrono::steady_clock::now();
  // What building it takes besides the records: the kernels' σs integrals
  // and moments, the sun's depths per sample, one node's splat sums, their
  // normalised values and centroids.
  const std::size_t slots = lattice_.slot_count();
  const double bytes =
      static_cast<double>(slots) *
      (sizeof(float) * ((kKernelMoments + 1) * spectral_count_ + 1) +
       sizeof(double) * 2 * (sh_count_ + kMaxPeakViews) + sizeof(double) * kKernelMoments);
  check_memory(static_cast<std::uint64_t>(bytes), "", "render/radiance_cache/voxel_m",
               fmt::format("building the radiance cache ({} nodes at {:.4g} m)", slots,
                           lattice_.spacing_m()));
  ground_.resize(nodes.size());
  node_photons_ = node_photons;
  if (node_photons_.empty())
    node_photons_.assign(nodes.size(), scene.settings.radiance_cache.photons_per_node);
  OBSCURA_CHECK(node_photons_.size() == nodes.size());
  choose_peak_views(scene);
  choose_light_cells(scene, nodes.size(), node_sensors);
  const std::vector<float> kernel_moments = kernel_scattering(scene);
  const auto sun_start = std::chrono::steady_clock::now();
  compute_sun(scene, nodes);
  sun_seconds = seconds_since(sun_start);
  long long photons_total = 0;
  for (const long long n : node_photons_) photons_total += n;
  PhotonTracingProgress tracing_progress(progress, photons_total);
  for (std::size_t u = 0; u < nodes.size(); ++u)
    splat(scene, nodes[u], static_cast<int>(u), kernel_moments, tracing_progress);
  seconds = seconds_since(start);
}

std::vector<long long> photons_of_nodes(const Scene& scene, const DistinctNodes& distinct) {
  const RadianceCacheSettings& settings = scene.settings.radiance_cache;
  std::vector<long long> photons(distinct.nodes.size(), 0);
  for (std::size_t s = 0; s < distinct.index.size(); ++s)
    for (std::size_t b = 0; b < distinct.index[s].size(); ++b) {
      // Spectra that are not the scene's sensors' (a validation case's one
      // band, with no sensor) take photons_per_node.
      const bool of_sensor = s < scene.sensors.size() && b < scene.sensors[s].bands.size();
      const long long count =
          of_sensor ? settings.photons(scene.sensors[s].bands[b]) : settings.photons_per_node;
      for (const int u : distinct.index[s][b])
        photons[static_cast<std::size_t>(u)] =
            std::max(photons[static_cast<std::size_t>(u)], count);
    }
  return photons;
}

std::size_t RadianceCache::memory_bytes() const { return volume_.memory_bytes(); }

void RadianceCache::choose_peak_views(const Scene& scene) {
  sensor_peak_.assign(scene.sensors.size(), -1);
  const RadianceCacheSettings& settings = scene.settings.radiance_cache;
  if (!settings.sensor_peaks || !splats_flights(settings)) return;
  // The light record's padding after the harmonics holds the peaks.
  const int room = std::min(kMaxPeakViews, volume_.stride() - record::kSh - sh_count_);
  const double deg = std::numbers::pi / 180.0;
  const double cos_narrow = std::cos(kMaxPeakHalfAngleDeg * deg), cos_same = std::cos(1.0 * deg);
  for (std::size_t s = 0; s < scene.sensors.size(); ++s) {
    const PinholeCamera& camera = scene.sensors[s].camera;
    const Vec3 axis = camera.generate_ray(0.5 * camera.width(), 0.5 * camera.height()).direction;
    if (dot(axis, camera.generate_ray(0.0, 0.0).direction) < cos_narrow) continue;
    const Vec3 out = -axis;  // the light leaves towards the sensor
    std::size_t v = 0;
    while (v < peak_views_.size() && dot(peak_views_[v], out) < cos_same) ++v;
    if (v == peak_views_.size()) {
      if (static_cast<int>(v) == room) continue;
      peak_views_.push_back(out);
    }
    sensor_peak_[s] = record::kSh - record::kTauSun + sh_count_ + static_cast<int>(v);
  }
}

void RadianceCache::choose_light_cells(const Scene& scene, std::size_t nodes,
                                       const std::vector<std::vector<int>>& node_sensors) {
  light_cells_.assign(nodes, all_cells(lattice_));
  sun_cells_ = all_cells(lattice_);
  // Only the track-length splat walks a box; a periodic lattice's rays wrap.
  if (node_sensors.empty() || !splats_flights(scene.settings.radiance_cache) || lattice_.periodic())
    return;
  OBSCURA_CHECK(node_sensors.size() == nodes);
  light_in_view_ = true;
  // A node's light reads the cells within the kernel's r of it (the splat's
  // hats widened, widen_splat) and of its neighbours (move_to_nodes), and a
  // camera ray reads the nodes of the cells it crosses: r + 1 cells around
  // those; one more against off-by-one (docs/physics.md, "Only where the
  // sensors look").
  const int margin = scene.settings.radiance_cache.kernel_radius_nodes + 2;
  sun_cells_ = CellBox{};
  for (std::size_t u = 0; u < nodes; ++u) {
    std::vector<const PinholeCamera*> cameras;
    for (const int s : node_sensors[u])
      cameras.push_back(&scene.sensors[static_cast<std::size_t>(s)].camera);
    light_cells_[u] = cells_in_view(lattice_, cameras, margin);
    sun_cells_.add(light_cells_[u]);
  }
}

void RadianceCache::compute_sun(const Scene& scene, const std::vector<SpectralNode>& nodes) {
  if (!has_sun_) return;
  // Where the records hold the grid's own medium (the lattice at the
  // cloud's voxel size), τ_sun is marched over them per spectral node, the
  // nodes inside the medium's box sharing one walk (parallel_depths.h): the
  // same trilinear σt and Simpson's rule as the medium's own march
  // (GridMedium::add_optical_depth), up to the records' float rounding, at
  // a fraction of its cost (docs/performance.md, "The sun's depths").
  // Otherwise the medium is marched per medium sample from each node and τ
  // interpolated in wavelength; so too where the lattice holds less than a
  // quarter of its box's nodes (ParallelDepths::fits).
  const LatticeView view = volume_.view();
  const bool by_records =
      sun_depths_ == SunDepths::kHere && volume_.has_medium() && ParallelDepths::fits(view);
  OBSCURA_CHECK(!by_records || volume_.node_count() == static_cast<int>(nodes.size()));
  const std::size_t depths = by_records ? nodes.size() : static_cast<std::size_t>(spectral_count_);
  const std::size_t per_slot = depths + 1;
  // τ_sun per medium sample (or spectral node), then the visibility, per slot.
  std::vector<float> sun(lattice_.slot_count() * per_slot, 0.0f);
  const Vec3 to_sun = scene.sun.direction();
  const Vec3 to_sun_lattice = lattice_.to_lattice_direction(to_sun);
  // Nodes of the cells in sun_cells_ (a node serves the cells on both sides).
  const auto in_sun_cells = [&](std::size_t slot) {
    const std::array<int, 3> n = lattice_.slot_node(slot);
    for (int a = 0; a < 3; ++a)
      if (n[a] < sun_cells_.lo[a] || n[a] > sun_cells_.hi[a] + 1) return false;
    return true;
  };
  // A surface within one node diagonal does not shade a node: the node is
  // then on or just under it (the ground beneath a cloud's lowest nodes),
  // and its values serve the cells above.
  const double near_m = std::sqrt(3.0) * lattice_.spacing_m();
  // τ_sun from lattice point `at`, added to `tau`, through the medium.
  const auto add_depth_from = [&](const Vec3& at, double* tau) {
    const Ray from{lattice_.origin() + lattice_.rotation() * (at * lattice_.spacing_m()), to_sun};
    scene.medium->add_optical_depth(from, 0.0, std::numeric_limits<double>::infinity(), tau);
  };
  std::vector<const float*> records(nodes.size());
  for (std::size_t u = 0; u < nodes.size(); ++u) records[u] = volume_.records(static_cast<int>(u));
  // Every node inside the medium's box, and a rim node's two points, share
  // one walk (parallel_depths.h).
  std::optional<ParallelDepths> parallel;
  if (by_records)
    parallel.emplace(view, records.data(), static_cast<int>(nodes.size()), volume_.stride(),
                     to_sun_lattice);
  // τ_sun at the node of `slot` (world position `at`) into `tau`, `inner`
  // a scratch of its size.
  const auto depth_at = [&](std::size_t slot, const Vec3& at, std::vector<double>& tau,
                            std::vector<double>& inner) {
    const std::array<int, 3> index = lattice_.slot_node(slot);
    const Vec3 node = by_records ? Vec3(index[0], index[1], index[2]) : lattice_.to_lattice(at);
    Vec3 face;
    if (!volume_.has_medium() || !rim_face(volume_.domain(), node, face)) {
      if (by_records)
        parallel->add(index, 0, tau.data());
      else
        scene.medium->add_optical_depth(Ray{at, to_sun}, 0.0,
                                        std::numeric_limits<double>::infinity(), tau.data());
      return;
    }
    // A rim node: 2 τ(face) − τ(inner neighbour) (lattice_view.h).
    std::fill(inner.begin(), inner.end(), 0.0);
    const Vec3 in = face * 2.0 - node;
    if (by_records) {
      // The face lies ½ from a node along the axes the rim node is beyond
      // the box on; the inner neighbour is a node.
      int half = 0;
      std::array<int, 3> below, inner_node;
      for (int a = 0; a < 3; ++a) {
        if (face[a] != node[a]) half |= 1 << a;
        below[a] = static_cast<int>(std::floor(face[a]));
        inner_node[a] = static_cast<int>(std::lround(in[a]));
        OBSCURA_CHECK(face[a] - below[a] == ((half >> a & 1) ? 0.5 : 0.0) &&
                      in[a] == inner_node[a]);
      }
      parallel->add(below, half, tau.data());
      parallel->add(inner_node, 0, inner.data());
    } else {
      add_depth_from(face, tau.data());
      add_depth_from(in, inner.data());
    }
    for (std::size_t k = 0; k < tau.size(); ++k) tau[k] = 2.0 * tau[k] - inner[k];
  };
  for_blocks_shared(*processes_, lattice_.block_count(), scene.settings.threads, sun,
                    per_slot * NodeLattice::kBlockNodes, [&](std::size_t block) {
                      std::vector<double> tau(depths), inner(depths);
                      for (std::size_t slot = block * NodeLattice::kBlockNodes;
                           slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
                        if (!lattice_.slot_inside(slot) || !in_sun_cells(slot)) continue;
                        const Ray ray{lattice_.slot_position(slot), to_sun};
                        SurfaceHit hit;
                        const bool shaded =
                            intersect_surfaces(scene.surfaces, ray, near_m,
                                               std::numeric_limits<double>::infinity(), hit);
                        std::fill(tau.begin(), tau.end(), 0.0);
                        if (sun_depths_ == SunDepths::kHere) depth_at(slot, ray.origin, tau, inner);
                        float* out = sun.data() + slot * per_slot;
                        for (std::size_t k = 0; k < depths; ++k)
                          out[k] = static_cast<float>(tau[k]);
                        out[depths] = shaded ? 0.0f : 1.0f;
                      }
                    });
  // Into every spectral node's records, τ_sun at its wavelength.
  parallel_for(lattice_.block_count(), scene.settings.threads, [&](std::size_t block) {
    std::vector<double> tau(depths);
    for (std::size_t slot = block * NodeLattice::kBlockNodes;
         slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
      const float* in = sun.data() + slot * per_slot;
      for (std::size_t k = 0; k < depths; ++k) tau[k] = in[k];
      for (std::size_t u = 0; u < nodes.size(); ++u) {
        float* r = volume_.record(static_cast<int>(u), slot);
        r[record::kTauSun] = by_records ? in[u] : static_cast<float>(nodes[u].lerp()(tau.data()));
        r[record::kSunVisibility] = in[depths];
      }
    }
  });
}

std::vector<float> RadianceCache::kernel_scattering(const Scene& scene) const {
  const Medium& medium = *scene.medium;
  const std::size_t slots = lattice_.slot_count();
  const int ns = spectral_count_;
  const int r = scene.settings.radiance_cache.kernel_radius_nodes;
  std::vector<float> out(slots * static_cast<std::size_t>(ns) * kKernelMoments, 0.0f);
  // The medium is trilinear between the lattice's nodes when they are its
  // own voxel centres: then ∫ K σs dV = Σ_m σs(x_m) W(m − n) exactly.
  const std::optional<GridFrame> frame = medium.grid_frame();
  const bool aligned = frame && frame->trilinear && !lattice_.periodic() &&
                       std::abs(frame->placement.voxel_size_m - lattice_.spacing_m()) <=
                           1e-12 * lattice_.spacing_m();
  // Inside the grid's box the medium is the trilinear interpolation of the
  // nodes' values, a rim node repeating its edge voxel (the grid's clamped
  // reconstruction), and zero outside it: the overlaps are clipped to the
  // box, [½, n + ½] in node units.
  std::vector<float> at_nodes;
  std::array<std::vector<double>, 3> overlap, overlap_moment;
  if (aligned) {
    at_nodes.assign(slots * static_cast<std::size_t>(ns), 0.0f);
    const GridDims& d = frame->dims;
    parallel_for(lattice_.block_count(), scene.settings.threads, [&](std::size_t block) {
      MediumPoint point;
      for (std::size_t slot = block * NodeLattice::kBlockNodes;
           slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
        if (!lattice_.slot_inside(slot)) continue;
        const std::array<int, 3> n = lattice_.slot_node(slot);
        const int vx = std::clamp(n[0] - 1, 0, d.nx - 1), vy = std::clamp(n[1] - 1, 0, d.ny - 1),
                  vz = std::clamp(n[2] - 1, 0, d.nz - 1);
        if (frame->voxels) {  // the voxel itself, as the lattice's records copy it
          const std::size_t v = frame->voxels->index(vx, vy, vz);
          for (int k = 0; k < ns; ++k) at_nodes[slot * ns + k] = frame->voxels->sigma_s(k)[v];
          continue;
        }
        medium.coefficients_at(frame->placement.index_to_world(Vec3(vx, vy, vz)), point);
        for (int k = 0; k < ns; ++k) at_nodes[slot * ns + k] = static_cast<float>(point.sigma_s[k]);
      }
    });
    const std::array<int, 3> cells = {d.nx, d.ny, d.nz};
    for (int a = 0; a < 3; ++a) {
      overlap[a] = axis_overlaps(r, lattice_.dims()[a], 0.5, cells[a] + 0.5, 0);
      overlap_moment[a] = axis_overlaps(r, lattice_.dims()[a], 0.5, cells[a] + 0.5, 1);
    }
    // The weights are products of one factor per axis: three 1-D passes
    // (kernel_sums.h), on every process alike, where their arrays over the
    // lattice's box fit.
    if (kernel_sums_fit(lattice_)) {
      std::array<AxisOverlaps, 3> axes;
      for (int a = 0; a < 3; ++a) axes[a] = {overlap[a], overlap_moment[a]};
      kernel_sums(lattice_, r, axes, at_nodes, ns, scene.settings.threads, out);
      return out;
    }
  }
  // Otherwise (boxes, clouds on other grids) by two-point Gauss–Legendre per
  // lattice interval and axis over the kernel's support, each interval
  // clipped to the medium's box (σs steps to zero at its faces, which need
  // not lie on nodes: a box 1 m tall at a spacing of 0.3125 m put both points
  // of its top interval above the face, and J read 8.5 % high in that box;
  // docs/physics.md): exact for σs trilinear within each clipped interval
  // (the tent is linear there), and converging as the spacing shrinks where
  // it is not. Per node and axis: the points' offsets from the node (node
  // units) and weights.
  const BBox3& support = lattice_.medium_support();
  auto axis_points = [&](int axis, int node, std::vector<double>& u, std::vector<double>& w) {
    u.clear();
    w.clear();
    for (int i = -r; i < r; ++i) {
      const double u0 = std::max<double>(i, support.lo[axis] - node),
                   u1 = std::min<double>(i + 1, support.hi[axis] - node);
      if (!(u1 > u0)) continue;
      for (const double x : {-1.0 / std::sqrt(3.0), 1.0 / std::sqrt(3.0)}) {
        const double at = 0.5 * (u0 + u1) + 0.5 * (u1 - u0) * x;
        u.push_back(at);
        w.push_back(0.5 * (u1 - u0) * std::max(0.0, 1.0 - std::abs(at) / r) / r);
      }
    }
  };
  const std::size_t per_slot = static_cast<std::size_t>(ns) * kKernelMoments;
  for_blocks_shared(
      *processes_, lattice_.block_count(), scene.settings.threads, out,
      per_slot * NodeLattice::kBlockNodes, [&](std::size_t block) {
        MediumPoint point;
        // Per sample: ∫ K σs dV and its first moments along the lattice's axes.
        std::vector<double> sum(per_slot);
        std::array<std::vector<double>, 3> gauss_u, gauss_w;
        for (std::size_t slot = block * NodeLattice::kBlockNodes;
             slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
          if (!lattice_.slot_inside(slot)) continue;
          const Vec3 node = lattice_.to_lattice(lattice_.slot_position(slot));
          const int ni = static_cast<int>(std::lround(node.x)),
                    nj = static_cast<int>(std::lround(node.y)),
                    nk = static_cast<int>(std::lround(node.z));
          std::fill(sum.begin(), sum.end(), 0.0);
          auto add = [&](double w, const std::array<double, 3>& moment, auto&& sigma_s) {
            for (int k = 0; k < ns; ++k) {
              double* s = sum.data() + static_cast<std::size_t>(k) * kKernelMoments;
              const double ws = sigma_s(k);
              s[0] += w * ws;
              for (int a = 0; a < 3; ++a) s[1 + a] += moment[a] * ws;
            }
          };
          if (aligned) {
            const std::size_t span = 2 * r + 1;
            for (int dk = -r; dk <= r; ++dk)
              for (int dj = -r; dj <= r; ++dj)
                for (int di = -r; di <= r; ++di) {
                  const std::size_t m = lattice_.slot_of(ni + di, nj + dj, nk + dk);
                  if (m == NodeLattice::kNoSlot) continue;
                  const std::size_t ix = ni * span + (di + r), iy = nj * span + (dj + r),
                                    iz = nk * span + (dk + r);
                  const double ox = overlap[0][ix], oy = overlap[1][iy], oz = overlap[2][iz];
                  add(ox * oy * oz,
                      {overlap_moment[0][ix] * oy * oz, ox * overlap_moment[1][iy] * oz,
                       ox * oy * overlap_moment[2][iz]},
                      [&](int k) { return at_nodes[m * ns + k]; });
                }
          } else {
            const Vec3 p0 = lattice_.slot_position(slot);
            const double h = lattice_.spacing_m();
            const int n[3] = {ni, nj, nk};
            for (int axis = 0; axis < 3; ++axis)
              axis_points(axis, n[axis], gauss_u[axis], gauss_w[axis]);
            const auto& [ux, uy, uz] = gauss_u;
            const auto& [wx, wy, wz] = gauss_w;
            for (std::size_t c = 0; c < uz.size(); ++c)
              for (std::size_t b = 0; b < uy.size(); ++b)
                for (std::size_t a = 0; a < ux.size(); ++a) {
                  const Vec3 offset(ux[a] * h, uy[b] * h, uz[c] * h);
                  medium.coefficients_at(p0 + lattice_.rotation() * offset, point);
                  const double w = wx[a] * wy[b] * wz[c];
                  add(w, {w * ux[a], w * uy[b], w * uz[c]},
                      [&](int k) { return point.sigma_s[k]; });
                }
          }
          for (std::size_t q = 0; q < per_slot; ++q)
            out[slot * per_slot + q] = static_cast<float>(sum[q]);
        }
      });
  return out;
}

void RadianceCache::splat(const Scene& scene, const SpectralNode& node, int index,
                          const std::vector<float>& kernel_moments,
                          PhotonTracingProgress& progress) {
  const RadianceCacheSettings& settings = scene.settings.radiance_cache;
  auto t0 = std::chrono::steady_clock::now();
  PhotonTracingSettings tracing;
  tracing.photons = node_photons_[static_cast<std::size_t>(index)];
  tracing.store_first_environment_scatter = true;  // only the sun's single scattering is apart
  tracing.seed = scene.settings.seed;
  tracing.threads = scene.settings.threads;
  tracing.processes = processes_;
  tracing.memory_field = "render/radiance_cache/photons";
  tracing.lateral_period_m = lattice_.periodic() ? settings.lateral_period_m : 0.0;
  // The flights' tracks where the records hold the medium and the kernel is
  // the lattice's own hat (flight_splat.h), else the collisions.
  tracing.flights = splats_flights(settings);
  tracing.absorb_by_weight = true;
  // The cloud's light on the ground (ground_light.h).
  tracing.surface_deposits = GroundLight::has_ground(scene) && !lattice_.periodic();
  tracing.on_traced = progress.on_traced();
  // Where the medium does not scatter at this node (an absorbing smoke in
  // the infrared), σs J is zero whatever J: the photons' flights would be
  // splatted for nothing, and the light channels stay zero. The photons
  // still carry the cloud's light on the ground (its emission, its shadow on
  // the sky's light) in their deposits, which neither the sun's photons
  // nor the environment's from surfaces ever make (they cannot scatter), so
  // the sky's and the emission's take their share; without ground the
  // photons carry nothing the images read.
  const bool scatters = node_scatters(index);
  if (!scatters) {
    if (!tracing.surface_deposits) return progress.node_done(tracing.photons);
    tracing.flights = false;
    tracing.sun_photons = false;
    tracing.surface_photons = false;
  }
  // One block of 2^40 photon streams per spectral node, above the pixels'.
  const std::uint64_t base = (static_cast<std::uint64_t>(index) + 1) << 40;
  TracedPhotons traced = trace_photons(scene, node, base, tracing);
  progress.node_done(tracing.photons);
  photons_stored_ += tracing.flights ? traced.flights.size() : traced.photons.size();
  walks_ += traced.walks;
  if (tracing.surface_deposits) {
    const BoundingSphere sphere = photon_bounding_sphere(scene);
    ground_[static_cast<std::size_t>(index)] =
        GroundLight(scene, traced.deposits, sphere.center, 2.0 * sphere.radius_m);
  }
  photon_seconds += seconds_since(t0);
  if (!scatters) return;

  t0 = std::chrono::steady_clock::now();
  const std::size_t slots = lattice_.slot_count();
  // Per slot the harmonics' sums, then (flights only) the sensors' peaks.
  const int peaks = tracing.flights ? static_cast<int>(peak_views_.size()) : 0;
  const std::size_t per_slot = static_cast<std::size_t>(sh_count_ + peaks);
  std::vector<double> sum(slots * per_slot, 0.0);
  const int r = settings.kernel_radius_nodes;
  if (tracing.flights) {
    const CellBox* cells =
        light_in_view_ ? &light_cells_[static_cast<std::size_t>(index)] : nullptr;
    splat_flights(volume_, index, traced.flights, sh_degree_, scene.settings.threads, sum,
                  *processes_, peak_views_, cells);
    widen_splat(lattice_, r, per_slot, scene.settings.threads, sum);
  }
  const double h = lattice_.spacing_m();
  const double volume = std::pow(r * h, 3);  // the kernel's normalisation (r h)³
  std::array<double, kMaxShCoefficients> y;
  // Photons in their stored order: the sums do not depend on the thread count.
  for (const Photon& p : traced.photons) {
    const Vec3 u = lattice_.to_lattice(p.position());
    spherical_harmonics(p.dir(), y, sh_degree_);
    const int i0 = static_cast<int>(std::floor(u.x)) - r + 1,
              j0 = static_cast<int>(std::floor(u.y)) - r + 1,
              k0 = static_cast<int>(std::floor(u.z)) - r + 1;
    for (int k = k0; k < k0 + 2 * r; ++k) {
      const double wz = std::max(0.0, 1.0 - std::abs(u.z - k) / r);
      for (int j = j0; j < j0 + 2 * r; ++j) {
        const double wyz = wz * std::max(0.0, 1.0 - std::abs(u.y - j) / r);
        for (int i = i0; i < i0 + 2 * r; ++i) {
          const double w = wyz * std::max(0.0, 1.0 - std::abs(u.x - i) / r);
          const std::size_t slot = lattice_.slot_of(i, j, k);
          if (w == 0.0 || slot == NodeLattice::kNoSlot) continue;
          double* s = sum.data() + slot * per_slot;
          const double weight = w * p.power / volume;
          for (int c = 0; c < sh_count_; ++c) s[c] += weight * y[c];
        }
      }
    }
  }
  normalise(index, node.lerp(), kernel_moments, sum, per_slot, r, scene.settings.threads);
  splat_seconds += seconds_since(t0);
}

bool RadianceCache::node_scatters(int index) const {
  // Where the records do not hold the medium, the collisions' splat finds no
  // photon in a medium that does not scatter (each is absorbed at its first
  // collision) and costs nothing.
  if (!volume_.has_medium()) return true;
  const std::size_t slots = lattice_.slot_count();
  const std::size_t stride = static_cast<std::size_t>(volume_.stride());
  const float* records = volume_.records(index);
  for (std::size_t slot = 0; slot < slots; ++slot)
    if (records[slot * stride + record::kSigmaS] != 0.0f) return true;
  return false;
}

void RadianceCache::normalise(int index, const SpectralLerp& lerp,
                              const std::vector<float>& kernel_moments,
                              const std::vector<double>& sum, std::size_t per_slot,
                              int kernel_radius, int threads) {
  const std::size_t slots = lattice_.slot_count();
  const std::size_t ns = static_cast<std::size_t>(spectral_count_);
  // Per slot the estimate Σ/∫ K σs dV of every channel, and where it sits:
  // the σs-weighted centroid of the node's kernel.
  KernelEstimates estimates;
  estimates.channels = per_slot;
  estimates.value.assign(slots * per_slot, 0.0);
  estimates.shift.assign(slots, {0.0, 0.0, 0.0});
  estimates.held.assign(slots, 0);
  parallel_for(lattice_.block_count(), threads, [&](std::size_t block) {
    std::array<std::vector<double>, kKernelMoments> samples;
    for (auto& m : samples) m.resize(ns);
    for (std::size_t slot = block * NodeLattice::kBlockNodes;
         slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
      for (std::size_t k = 0; k < ns; ++k)
        for (int q = 0; q < kKernelMoments; ++q)
          samples[q][k] = kernel_moments[(slot * ns + k) * kKernelMoments + q];
      const double norm = lerp(samples[0].data());
      if (!(norm > 0.0)) continue;
      estimates.held[slot] = 1;
      for (std::size_t c = 0; c < per_slot; ++c)
        estimates.value[slot * per_slot + c] = sum[slot * per_slot + c] / norm;
      for (int a = 0; a < 3; ++a)
        estimates.shift[slot][a] = std::clamp(lerp(samples[1 + a].data()) / norm,
                                              -1.0 * kernel_radius, 1.0 * kernel_radius);
    }
  });
  const std::vector<double> moved = move_to_nodes(lattice_, estimates, threads);
  parallel_for(lattice_.block_count(), threads, [&](std::size_t block) {
    for (std::size_t slot = block * NodeLattice::kBlockNodes;
         slot < (block + 1) * NodeLattice::kBlockNodes; ++slot) {
      if (!estimates.held[slot]) continue;
      float* out = volume_.record(index, slot) + record::kSh;
      for (std::size_t c = 0; c < per_slot; ++c)
        out[c] = static_cast<float>(moved[slot * per_slot + c]);
    }
  });
}

void add_ground_light(const Scene& scene, const RadianceCache& cache, const CameraRay& camera,
                      const SpectralNodes& nodes, const int* record, double* behind) {
  if (!camera.on_surface || !cache.ground(0).covers(camera.hit.surface)) return;
  const SurfaceMaterial& m = scene.surfaces[camera.hit.surface]->material();
  const Vec3 p = camera.ray.at(camera.hit.t);
  // Per horizontal area on the map; a sloped facet spreads it over 1/n_z more.
  const double n_z = std::abs(camera.hit.normal.z);
  for (std::size_t j = 0; j < nodes.size(); ++j)
    behind[j] += m.reflectance_at(nodes.nodes()[j].wavelength_um) * std::numbers::inv_pi * n_z *
                 cache.ground(record[j]).irradiance(p);
}

}  // namespace obscura
