#pragma once
// The CUDA devices this process can use, and what they are. Standard headers
// only: host code compiled without nvcc calls it (gpu/gpu_device.cpp).
#include <cstdint>
#include <string>

namespace obscura {

struct CudaDeviceInfo {
  int index = 0;
  std::string name;
  int compute_major = 0, compute_minor = 0;  // compute capability (Hopper: 9.0)
  int multiprocessors = 0;
  std::uint64_t memory_bytes = 0;  // global memory
  std::uint64_t l2_bytes = 0;
  int driver_version = 0, runtime_version = 0;  // e.g. 13000 for 13.0
};

// How many CUDA devices there are; 0 with `why` saying CUDA's reason when
// there are none (no driver, no device, a driver too old for this runtime).
int cuda_device_count(std::string& why);

// Device `index` (< cuda_device_count). Throws CudaError.
CudaDeviceInfo cuda_device_info(int index);

}  // namespace obscura
