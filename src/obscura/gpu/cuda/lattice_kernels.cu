#include "obscura/gpu/cuda/cuda_check.h"
#include "obscura/gpu/cuda/lattice_kernels.h"
#include "obscura/gpu/launch_geometry.h"

namespace obscura {
namespace {

// Runs item(i) for every i < items, each thread taking i = its index,
// index + the grid's threads, … (launch_geometry.h).
template <class Item>
__device__ void for_grid_items(std::uint64_t items, const Item& item) {
  const std::uint64_t step = static_cast<std::uint64_t>(gridDim.x) * blockDim.x;
  for (std::uint64_t i = static_cast<std::uint64_t>(blockIdx.x) * blockDim.x + threadIdx.x;
       i < items; i += step)
    item(i);
}

// The job is a __grid_constant__ parameter: read in place from the
// parameter space by every thread, not copied to each thread's stack.
template <int Stride, MarchSource Kind>
__global__ void __launch_bounds__(kThreadsPerBlock)
    march_kernel(const __grid_constant__ MarchJob job) {
  for_grid_items(job.items(), [&](std::uint64_t i) { march_item<Stride, Kind>(job, i); });
}

template <int Stride>
__global__ void __launch_bounds__(kThreadsPerBlock)
    sun_depth_kernel(const __grid_constant__ SunDepthJob job) {
  for_grid_items(job.items(), [&](std::uint64_t i) { sun_depth_item<Stride>(job, i); });
}

}  // namespace

void launch_march(const MarchJob& job, cudaStream_t stream) {
  const LaunchGeometry g = launch_geometry(job.items());
  if (g.blocks == 0) return;
  dispatch_march(job, [&](auto stride, auto kind) {
    march_kernel<decltype(stride)::value, decltype(kind)::value>
        <<<g.blocks, g.threads, 0, stream>>>(job);
  });
  OBSCURA_CUDA(cudaGetLastError());
}

void launch_sun_depths(const SunDepthJob& job, cudaStream_t stream) {
  const LaunchGeometry g = launch_geometry(job.items());
  if (g.blocks == 0) return;
  dispatch_sun_depths(job, [&](auto stride) {
    sun_depth_kernel<decltype(stride)::value><<<g.blocks, g.threads, 0, stream>>>(job);
  });
  OBSCURA_CUDA(cudaGetLastError());
}

}  // namespace obscura
