#pragma once
// The radiance cache's optical depth towards the sun, τ_sun, at every node of
// its lattice and every spectral node (render/radiance_cache/radiance_cache.h),
// by marching σt = σa + σs of the frame's own records from the node towards
// the sun: the work of the GPU's sun kernel (gpu/cuda/sun_depth_kernel.cu) and
// of its reference on the CPU's threads (host_executor.h), which run the same
// sun_depth_item (docs/gpu.md). An item is one slot at one spectral node
// (items u·slots … (u + 1)·slots − 1 are node u's); it writes the slot's
// record::kTauSun channel and reads only the medium channels, which no item
// writes. Slots past the lattice's last node keep what they hold. A rim node
// outside the medium's box holds 2 τ(face) − τ(inner neighbour), as the CPU's
// (lattice_view.h, rim_face).
//
// The CPU's cache sums the same records' cells over one walk shared by all
// nodes (RadianceCache::compute_sun, render/lattice/parallel_depths.h); this
// marches each node's ray over the same cells with the same Simpson rule:
// equal up to rounding (tests/gpu/sun_depth_job_test.cpp measures it).
#include <array>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "obscura/core/host_device.h"
#include "obscura/core/ray.h"
#include "obscura/core/vec3.h"
#include "obscura/gpu/march_job.h"
#include "obscura/render/lattice/lattice_view.h"
#include "obscura/render/lattice/lattice_view_march.h"

namespace obscura {

struct SunDepthJob {
  LatticeView lattice;
  float* const* records = nullptr;  // per distinct node u: its records (τ_sun written)
  std::uint64_t slot_count = 0;     // slots of the lattice's held blocks
  std::int32_t nodes = 0;           // distinct spectral nodes
  std::int32_t stride = 0;          // floats per record
  Vec3 to_sun_lattice;              // towards the sun, lattice units per metre

  OBSCURA_HOST_DEVICE std::uint64_t items() const {
    return slot_count * static_cast<std::uint64_t>(nodes);
  }
};

static_assert(std::is_trivially_copyable_v<SunDepthJob> && std::is_standard_layout_v<SunDepthJob>);
static_assert(offsetof(SunDepthJob, slot_count) == sizeof(LatticeView) + 8 &&
              offsetof(SunDepthJob, to_sun_lattice) == sizeof(LatticeView) + 24 &&
              sizeof(SunDepthJob) == sizeof(LatticeView) + 48);

// The lattice node (i, j, k) slot `slot` holds.
OBSCURA_HOST_DEVICE inline std::array<int, 3> slot_node(const LatticeView& lattice,
                                                        std::uint64_t slot) {
  constexpr int b = LatticeView::kBlock;
  const std::array<int, 3>& block = lattice.blocks[slot / LatticeView::kBlockNodes];
  const auto local = static_cast<int>(slot % LatticeView::kBlockNodes);
  return {block[0] * b + local % b, block[1] * b + (local / b) % b, block[2] * b + local / (b * b)};
}

template <int Stride>
OBSCURA_HOST_DEVICE void sun_depth_item(const SunDepthJob& job, std::uint64_t item) {
  const std::uint64_t slot = item % job.slot_count;
  const auto u = static_cast<std::int32_t>(item / job.slot_count);
  const std::array<int, 3> node = slot_node(job.lattice, slot);
  for (int a = 0; a < 3; ++a)
    if (node[a] >= job.lattice.dims[a]) return;
  float* const records = job.records[u];
  const auto depth = [&](const Vec3& from) {
    return lattice_optical_depth<Stride>(job.lattice, records, Ray{from, job.to_sun_lattice},
                                         std::numeric_limits<double>::infinity());
  };
  const Vec3 at(node[0], node[1], node[2]);
  Vec3 face;
  const double tau = rim_face(job.lattice.domain, at, face)
                         ? 2.0 * depth(face) - depth(face * 2.0 - at)
                         : depth(at);
  records[slot * Stride + record::kTauSun] = static_cast<float>(tau);
}

// Calls f(std::integral_constant<int, Stride>{}) for the job's stride, which
// must be a light stride (sh_degree_of_stride ≥ 0).
template <class F>
void dispatch_sun_depths(const SunDepthJob& job, F&& f) {
  dispatch_light_stride(job.stride, f);
}

}  // namespace obscura
