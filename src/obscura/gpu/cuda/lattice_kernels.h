#pragma once
// The kernels over a frame's lattice (docs/gpu.md): one device thread per
// item of a MarchJob (march_job.h) or a SunDepthJob (sun_depth_job.h), each
// running the item function the CPU's reference runs (host_executor.h), in a
// grid-stride loop of launch_geometry(items) (launch_geometry.h). For .cu
// files only (cuda_runtime.h).
#include <cuda_runtime.h>

#include "obscura/gpu/march_job.h"
#include "obscura/gpu/sun_depth_job.h"

namespace obscura {

// Launches the march of `job` (its pointers into device memory) on `stream`;
// returns at once. Throws CudaError when the launch fails.
void launch_march(const MarchJob& job, cudaStream_t stream);

// The same for the sun's optical depths.
void launch_sun_depths(const SunDepthJob& job, cudaStream_t stream);

}  // namespace obscura
