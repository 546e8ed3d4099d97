#include "obscura/gpu/cuda/cuda_check.h"
#include "obscura/gpu/cuda/cuda_devices.h"

namespace obscura {

int cuda_device_count(std::string& why) {
  int count = 0;
  const cudaError_t status = cudaGetDeviceCount(&count);
  if (status != cudaSuccess) {
    why = std::string(cudaGetErrorString(status)) + " (" + cudaGetErrorName(status) + ")";
    cudaGetLastError();  // clear it: the next call should not see this one
    return 0;
  }
  if (count == 0) why = "no CUDA device";
  return count;
}

CudaDeviceInfo cuda_device_info(int index) {
  cudaDeviceProp p{};
  OBSCURA_CUDA(cudaGetDeviceProperties(&p, index));
  CudaDeviceInfo info;
  info.index = index;
  info.name = p.name;
  info.compute_major = p.major;
  info.compute_minor = p.minor;
  info.multiprocessors = p.multiProcessorCount;
  info.memory_bytes = p.totalGlobalMem;
  info.l2_bytes = static_cast<std::uint64_t>(p.l2CacheSize);
  OBSCURA_CUDA(cudaDriverGetVersion(&info.driver_version));
  OBSCURA_CUDA(cudaRuntimeGetVersion(&info.runtime_version));
  return info;
}

}  // namespace obscura
