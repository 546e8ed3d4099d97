#pragma once
// The lattice work on the CPU's threads (lattice_executor.h): the reference
// the GPU is checked against (gpu/check, tests/gpu), running the same item
// functions as the kernels over its own copy of the frame. Standard threads
// only, so that the bare GPU check builds it; items are independent, so
// results do not depend on the thread count.
#include <array>
#include <cstdint>
#include <vector>

#include "obscura/gpu/lattice_executor.h"

namespace obscura {

class HostExecutor final : public LatticeExecutor {
 public:
  // `threads` ≥ 1 (std::thread::hardware_concurrency() is the caller's to choose).
  explicit HostExecutor(int threads);

  std::string name() const override;
  void load(const FrameLattice& frame) override;
  void sun_depths(const Vec3& to_sun) override;
  void march(const MarchRequest& request, std::span<const MarchRay> rays,
             MarchResult& result) override;
  std::vector<float> records(int node) const override;
  ExecutorTimes last_times() const override { return times_; }

 private:
  // The view over this executor's copies.
  LatticeView view() const;

  int threads_;
  FrameLattice frame_;  // its pointers into the copies below
  std::vector<std::int32_t> block_index_;
  std::vector<std::array<int, 3>> blocks_;
  std::vector<std::uint8_t> occupied_;
  std::vector<std::vector<float>> records_;
  std::vector<std::vector<double>> planck_cubic_;
  ExecutorTimes times_;
};

}  // namespace obscura
