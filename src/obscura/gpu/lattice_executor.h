#pragma once
// Where a frame's lattice work runs (docs/gpu.md): the sun's optical depths
// into the radiance cache's records (sun_depth_job.h) and the camera march of
// batches of rays (march_job.h), on a CUDA device (cuda/cuda_executor.h) or on
// the CPU's threads (host_executor.h: the reference the device is checked
// against, and what the host-side tests run). Both run the same item
// functions over their own copy of the frame, so they give the same numbers
// up to the device's floating-point contractions.
//
// Standard headers and obscura's shared headers only: the bare GPU check
// (gpu/check) builds it.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "obscura/core/planck_table.h"
#include "obscura/core/vec3.h"
#include "obscura/gpu/march_job.h"
#include "obscura/render/lattice/lattice_view.h"

namespace obscura {

// A frame's lattice on the host: what an executor copies. The view's arrays
// and the records must live until load() returns.
struct FrameLattice {
  LatticeView view;                             // host pointers: block_index, blocks, occupied
  std::int32_t stride = record::kMediumStride;  // floats per record
  // Per distinct spectral node: its (view.zero_slot + 1) · stride floats of
  // records, its Planck table (the coefficients in host memory) and the sun's
  // irradiance there (W m⁻² µm⁻¹; the radiance cache's, else 0).
  std::vector<const float*> records;
  std::vector<PlanckTableView> planck;
  std::vector<double> sun_irradiance;

  std::uint64_t slot_count() const { return view.zero_slot; }
  std::uint64_t block_count() const { return view.zero_slot / LatticeView::kBlockNodes; }
  std::uint64_t block_grid_size() const {
    return static_cast<std::uint64_t>(view.block_dims[0]) * view.block_dims[1] * view.block_dims[2];
  }
  int nodes() const { return static_cast<int>(records.size()); }
  // Bytes an executor's copy of the frame takes.
  std::uint64_t bytes() const;
};

// What a march computes besides the rays: the source, and per output k the
// distinct node it is at (a sensor's bands' nodes in order).
struct MarchRequest {
  MarchSource source = MarchSource::kEmission;
  int sh_degree = 0;      // kCache
  bool sun = false;       // kCache
  Vec3 to_sun;            // kCache, unit, world
  int peak_channel = -1;  // kCache: the sensor's forward peak (RadianceCache::peak_channel)
  std::vector<std::int32_t> output_node;
};

// Per item (output k, ray i) at [k · rays + i]: MarchJob's outputs.
struct MarchResult {
  std::vector<double> radiance, transmittance, attenuation;
  std::vector<std::uint32_t> cells;
};

// What the last call took: copies between host and device, and the work
// itself (a device's kernel time, the CPU's wall time).
struct ExecutorTimes {
  double transfer_seconds = 0.0;
  double kernel_seconds = 0.0;
};

class LatticeExecutor {
 public:
  virtual ~LatticeExecutor() = default;
  // "cpu (N threads)", or the device's name and number.
  virtual std::string name() const = 0;
  // Copies `frame` (replacing an earlier one). Throws Error-like
  // std::runtime_error when the device lacks the memory.
  virtual void load(const FrameLattice& frame) = 0;
  // τ_sun of every slot and node into the loaded records (record::kTauSun),
  // towards the unit world direction `to_sun`. Light records only.
  virtual void sun_depths(const Vec3& to_sun) = 0;
  // Marches `rays` over the loaded records for `request` into `result`.
  virtual void march(const MarchRequest& request, std::span<const MarchRay> rays,
                     MarchResult& result) = 0;
  // The loaded records of distinct node u, as they are now.
  virtual std::vector<float> records(int node) const = 0;
  virtual ExecutorTimes last_times() const = 0;
};

// The job of `request` over `frame`'s view and the given arrays (host or
// device pointers alike), for `ray_count` rays. Checks what the kernels
// support (march_supported) and that every output node exists; throws
// std::invalid_argument otherwise.
MarchJob make_march_job(const LatticeView& view, std::int32_t stride, int nodes,
                        const MarchRequest& request, std::uint64_t ray_count);

}  // namespace obscura
