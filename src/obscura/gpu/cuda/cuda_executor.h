#pragma once
// The lattice work on a CUDA device (lattice_executor.h): the frame's records,
// block tables and Planck tables copied to device memory once per frame, the
// sun's optical depths written there in place, and each march's rays copied
// in and results copied out (docs/gpu.md). Standard headers only (the device
// state is behind a pointer), so host code compiled without nvcc uses it.
#include <memory>

#include "obscura/gpu/lattice_executor.h"

namespace obscura {

class CudaExecutor final : public LatticeExecutor {
 public:
  // Uses device `device` (< cuda_device_count). Throws CudaError.
  explicit CudaExecutor(int device = 0);
  ~CudaExecutor() override;

  std::string name() const override;
  void load(const FrameLattice& frame) override;
  void sun_depths(const Vec3& to_sun) override;
  void march(const MarchRequest& request, std::span<const MarchRay> rays,
             MarchResult& result) override;
  std::vector<float> records(int node) const override;
  ExecutorTimes last_times() const override;

 private:
  struct Device;
  std::unique_ptr<Device> device_;
};

}  // namespace obscura
