#include "obscura/gpu/cuda/cuda_check.h"
#include "obscura/gpu/cuda/device_buffer.h"
#include "obscura/gpu/cuda/layout_probe.h"

namespace obscura {
namespace {

__global__ void layout_kernel(std::uint64_t* out) { struct_layout(out); }

}  // namespace

std::array<std::uint64_t, kStructLayoutValues> device_struct_layout() {
  DeviceBuffer<std::uint64_t> values(kStructLayoutValues);
  layout_kernel<<<1, 1>>>(values.data());
  OBSCURA_CUDA(cudaGetLastError());
  std::array<std::uint64_t, kStructLayoutValues> out{};
  values.download(out.data(), out.size());
  OBSCURA_CUDA(cudaDeviceSynchronize());
  return out;
}

}  // namespace obscura
