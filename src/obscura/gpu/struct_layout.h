#pragma once
// The sizes and field offsets of every struct that crosses to a CUDA device
// (docs/gpu.md), as the compiler that compiles this sees them: the host
// compiler's, and nvcc's device pass in a kernel (gpu/cuda/layout_probe.cu).
// The static_asserts beside each struct pin the host's; the GPU check
// (gpu/check) compares the device's with them on the device itself.
#include <array>
#include <cstddef>
#include <cstdint>

#include "obscura/core/host_device.h"
#include "obscura/gpu/march_job.h"
#include "obscura/gpu/sun_depth_job.h"

namespace obscura {

inline constexpr int kStructLayoutValues = 24;

// What each value of the layout is, for messages.
inline constexpr std::array<const char*, kStructLayoutValues> kStructLayoutNames = {
    "sizeof(Vec3)",
    "sizeof(Mat3)",
    "sizeof(BBox3)",
    "sizeof(LatticeView)",
    "offsetof(LatticeView, spacing_m)",
    "offsetof(LatticeView, dims)",
    "offsetof(LatticeView, block_index)",
    "offsetof(LatticeView, blocks)",
    "offsetof(LatticeView, occupied)",
    "offsetof(LatticeView, zero_slot)",
    "offsetof(LatticeView, domain)",
    "sizeof(PlanckTableView)",
    "offsetof(PlanckTableView, formula)",
    "sizeof(MarchRay)",
    "offsetof(MarchRay, t_end)",
    "sizeof(MarchJob)",
    "offsetof(MarchJob, records)",
    "offsetof(MarchJob, ray_count)",
    "offsetof(MarchJob, source)",
    "offsetof(MarchJob, to_sun)",
    "sizeof(SunDepthJob)",
    "offsetof(SunDepthJob, slot_count)",
    "offsetof(SunDepthJob, to_sun_lattice)",
    "sizeof(std::array<int, 3>)",
};

OBSCURA_HOST_DEVICE inline void struct_layout(std::uint64_t* out) {
  const std::uint64_t v[kStructLayoutValues] = {
      sizeof(Vec3),
      sizeof(Mat3),
      sizeof(BBox3),
      sizeof(LatticeView),
      offsetof(LatticeView, spacing_m),
      offsetof(LatticeView, dims),
      offsetof(LatticeView, block_index),
      offsetof(LatticeView, blocks),
      offsetof(LatticeView, occupied),
      offsetof(LatticeView, zero_slot),
      offsetof(LatticeView, domain),
      sizeof(PlanckTableView),
      offsetof(PlanckTableView, formula),
      sizeof(MarchRay),
      offsetof(MarchRay, t_end),
      sizeof(MarchJob),
      offsetof(MarchJob, records),
      offsetof(MarchJob, ray_count),
      offsetof(MarchJob, source),
      offsetof(MarchJob, to_sun),
      sizeof(SunDepthJob),
      offsetof(SunDepthJob, slot_count),
      offsetof(SunDepthJob, to_sun_lattice),
      sizeof(std::array<int, 3>),
  };
  for (int i = 0; i < kStructLayoutValues; ++i) out[i] = v[i];
}

}  // namespace obscura
