#pragma once
// Random voxel grids shared by the medium and render tests.
#include <memory>

#include "obscura/core/rng.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::testing {

// A grid of random non-negative coefficients (some voxels exactly zero),
// rotated and offset, with `samples` spectral samples.
inline std::shared_ptr<VoxelGrid> random_grid(GridDims dims, int samples, std::uint64_t seed,
                                              const Mat3& rotation = Mat3::identity()) {
  GridPlacement p;
  p.origin_m = {-1.3, 0.4, 2.0};
  p.voxel_size_m = 0.37;
  p.rotation = rotation;
  std::vector<double> wl;
  for (int s = 0; s < samples; ++s) wl.push_back(3.0 + s);
  auto grid = std::make_shared<VoxelGrid>(dims, p, wl);
  Rng rng(seed, 0);
  for (std::size_t v = 0; v < dims.count(); ++v) {
    const bool empty = rng.uniform() < 0.3;
    for (int s = 0; s < samples; ++s) {
      grid->sigma_a(s)[v] = empty ? 0.0f : static_cast<float>(2.0 * rng.uniform());
      grid->sigma_s(s)[v] = empty ? 0.0f : static_cast<float>(rng.uniform());
      grid->g(s)[v] = static_cast<float>(1.8 * rng.uniform() - 0.9);
    }
    grid->temperature()[v] = static_cast<float>(250.0 + 100.0 * rng.uniform());
  }
  return grid;
}

}  // namespace obscura::testing
