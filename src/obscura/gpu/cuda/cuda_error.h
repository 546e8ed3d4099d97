#pragma once
// A CUDA runtime call that failed (no device, out of device memory, a kernel
// that faulted), with the call and CUDA's own words. Standard headers only, so
// that host code compiled without nvcc can catch it (gpu/gpu_integrator.cpp
// turns it into an obscura Error for the user).
#include <stdexcept>
#include <string>

namespace obscura {

class CudaError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace obscura
