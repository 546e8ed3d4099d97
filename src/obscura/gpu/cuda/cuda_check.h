#pragma once
// OBSCURA_CUDA(call): a CUDA runtime call whose failure throws CudaError
// naming the call and CUDA's message. For .cu files only (cuda_runtime.h).
#include <cuda_runtime.h>

#include <string>

#include "obscura/gpu/cuda/cuda_error.h"

namespace obscura {

[[noreturn]] inline void throw_cuda_error(cudaError_t status, const char* call) {
  throw CudaError(std::string("CUDA: ") + call + ": " + cudaGetErrorString(status) + " (" +
                  cudaGetErrorName(status) + ")");
}

}  // namespace obscura

#define OBSCURA_CUDA(call)                                     \
  do {                                                         \
    const cudaError_t obscura_cuda_status = (call);            \
    if (obscura_cuda_status != cudaSuccess)                    \
      ::obscura::throw_cuda_error(obscura_cuda_status, #call); \
  } while (false)
