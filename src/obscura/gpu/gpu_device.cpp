#include "obscura/gpu/gpu_device.h"

#include <fmt/format.h>

#include "obscura/core/check.h"
#include "obscura/core/error.h"

#if OBSCURA_WITH_CUDA
#include "obscura/gpu/cuda/cuda_devices.h"
#include "obscura/gpu/cuda/cuda_error.h"
#include "obscura/gpu/cuda/cuda_executor.h"
#endif

namespace obscura {
namespace {

Error unavailable(const std::string& why) {
  return Error(fmt::format(
      "\"device\": \"gpu\" cannot run: {}; render with \"device\": \"cpu\" (docs/gpu.md)", why));
}

}  // namespace

#if OBSCURA_WITH_CUDA

bool built_with_cuda() { return true; }

int gpu_device_count(std::string& why) {
  const int count = cuda_device_count(why);
  if (count == 0) why = "no usable CUDA device: " + why;
  return count;
}

std::unique_ptr<LatticeExecutor> make_gpu_executor() {
  require_gpu();
  try {
    return std::make_unique<CudaExecutor>(0);
  } catch (const CudaError& e) {
    throw unavailable(e.what());
  }
}

#else

bool built_with_cuda() { return false; }

int gpu_device_count(std::string& why) {
  why =
      "this obscura was built without CUDA (configure with -DOBSCURA_CUDA=ON where the CUDA "
      "toolkit's nvcc is installed)";
  return 0;
}

std::unique_ptr<LatticeExecutor> make_gpu_executor() {
  require_gpu();
  throw InternalError("require_gpu passed in a build without CUDA");
}

#endif

void require_gpu() {
  std::string why;
  if (gpu_device_count(why) == 0) throw unavailable(why);
}

}  // namespace obscura
