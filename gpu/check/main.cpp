// obscura_gpu_check: the GPU path checked against the CPU on procedural clouds
// (docs/gpu.md, "The GPU check"). Builds from obscura's shared headers, the
// kernels and the standard library alone, for a bare GPU machine.
//   obscura_gpu_check [--case NAME|all] [--threads N] [--repeats N]
// Exit status: 0 when every case passes, 1 when one does not agree, 2 for a
// usage error or no usable CUDA device.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <thread>

#include "check_cases.h"
#include "obscura/gpu/cuda/cuda_devices.h"
#include "obscura/gpu/cuda/cuda_executor.h"
#include "obscura/gpu/cuda/layout_probe.h"

using namespace obscura;

int main(int argc, char** argv) {
  std::string which = "all";
  gpu_check::CheckOptions options;
  options.cpu_threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  options.device = [] { return std::make_unique<CudaExecutor>(0); };
  options.device_layout = device_struct_layout;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 < argc && a == "--case") {
      which = argv[++i];
    } else if (i + 1 < argc && a == "--threads") {
      options.cpu_threads = std::max(1, std::atoi(argv[++i]));
    } else if (i + 1 < argc && a == "--repeats") {
      options.repeats = std::max(1, std::atoi(argv[++i]));
    } else {
      std::fprintf(stderr,
                   "usage: obscura_gpu_check [--case NAME|all] [--threads N] [--repeats N]\n"
                   "cases:");
      for (const std::string& c : gpu_check::case_names()) std::fprintf(stderr, " %s", c.c_str());
      std::fprintf(stderr, "\n");
      return 2;
    }
  }
  std::string why;
  if (cuda_device_count(why) == 0) {
    std::fprintf(stderr, "obscura_gpu_check: no usable CUDA device: %s\n", why.c_str());
    return 2;
  }
  try {
    const CudaDeviceInfo d = cuda_device_info(0);
    std::printf(
        "device 0: %s, compute %d.%d, %d multiprocessors, %.1f GiB, L2 %.0f MiB, "
        "driver %d.%d, runtime %d.%d\n",
        d.name.c_str(), d.compute_major, d.compute_minor, d.multiprocessors,
        static_cast<double>(d.memory_bytes) / (1 << 30),
        static_cast<double>(d.l2_bytes) / (1 << 20), d.driver_version / 1000,
        d.driver_version % 1000 / 10, d.runtime_version / 1000, d.runtime_version % 1000 / 10);
    std::printf("CPU reference: %d threads\n", options.cpu_threads);
    bool all = true;
    for (const std::string& c : gpu_check::case_names())
      if (which == "all" || which == c) all = gpu_check::run_case(c, options) && all;
    if (which != "all") {
      bool known = false;
      for (const std::string& c : gpu_check::case_names()) known = known || c == which;
      if (!known) {
        std::fprintf(stderr, "obscura_gpu_check: no case '%s'\n", which.c_str());
        return 2;
      }
    }
    std::printf("%s\n", all ? "PASS" : "FAIL");
    return all ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "obscura_gpu_check: %s\n", e.what());
    return 1;
  }
}
