#pragma once
// The GPU check's cases (docs/gpu.md, "The GPU check"): each makes its cloud
// and rays, runs the same work on the CUDA device and on the CPU's threads
// (obscura/gpu/host_executor.h), prints how far apart the results are and
// what the device took, and says whether they agree (mean ≤ 1e-4, worst
// pixel ≤ 1e-3 relative).
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "obscura/gpu/lattice_executor.h"
#include "obscura/gpu/struct_layout.h"

namespace obscura::gpu_check {

struct CheckOptions {
  int cpu_threads = 1;  // the reference's threads
  int repeats = 3;      // timed device runs (the best is printed)
  // The side under test: a CUDA device's executor and the struct layout its
  // code sees (main.cpp; gpu/cuda/cuda_executor.h, layout_probe.h).
  std::function<std::unique_ptr<LatticeExecutor>()> device;
  std::function<std::array<std::uint64_t, kStructLayoutValues>()> device_layout;
};

// The case names, in the order "all" runs them.
const std::vector<std::string>& case_names();

// Runs case `name`; true when it passes. Throws std::invalid_argument for an
// unknown name.
bool run_case(const std::string& name, const CheckOptions& options);

}  // namespace obscura::gpu_check
