#pragma once
// The GPU a render asks for with "device": "gpu" or --device gpu
// (docs/gpu.md): the first CUDA device, in a build with CUDA (OBSCURA_CUDA).
// Asking for it where there is none is an Error saying why, never a silent
// render on the CPU.
#include <memory>
#include <string>

#include "obscura/gpu/lattice_executor.h"

namespace obscura {

// Whether this obscura was built with CUDA.
bool built_with_cuda();

// The CUDA devices usable here; 0 with `why` saying why not (a build
// without CUDA, or CUDA's own reason: no driver, no device).
int gpu_device_count(std::string& why);

// Throws Error when "device": "gpu" cannot run here: a build without CUDA,
// or no usable CUDA device (no driver, no device: CUDA's own reason).
void require_gpu();

// The executor of "device": "gpu" on the first CUDA device; throws as
// require_gpu does.
std::unique_ptr<LatticeExecutor> make_gpu_executor();

}  // namespace obscura
