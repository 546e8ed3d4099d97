#include "obscura/medium/majorant_grid.h"

#include <algorithm>
#include <limits>

#include "obscura/core/error.h"

namespace obscura {

MajorantGrid::MajorantGrid(const VoxelGrid& grid, int block_size)
    : block_size_(block_size), spectral_count_(grid.spectral_count()) {
  if (block_size < 1) throw Error("MajorantGrid: block size must be >= 1");
  const std::array<int, 3> n = {grid.dims().nx, grid.dims().ny, grid.dims().nz};
  for (int a = 0; a < 3; ++a) block_dims_[a] = (n[a] + 1 + block_size - 1) / block_size;
  const std::size_t blocks =
      static_cast<std::size_t>(block_dims_[0]) * block_dims_[1] * block_dims_[2];
  values_.assign(blocks * spectral_count_, 0.0);
  minorants_.assign(blocks * spectral_count_, 0.0);
  max_.assign(blocks, 0.0f);
  // Voxels influencing block b along an axis: cells [bB, bB+B−1] have corners
  // (cell − 1) and cell, i.e. voxels [bB − 1, bB + B − 1], clamped to the grid.
  auto range = [&](int b, int axis, int& lo, int& hi) {
    lo = std::clamp(b * block_size - 1, 0, n[axis] - 1);
    hi = std::clamp(b * block_size + block_size - 1, 0, n[axis] - 1);
  };
  for (int bz = 0; bz < block_dims_[2]; ++bz)
    for (int by = 0; by < block_dims_[1]; ++by)
      for (int bx = 0; bx < block_dims_[0]; ++bx) {
        int x0, x1, y0, y1, z0, z1;
        range(bx, 0, x0, x1);
        range(by, 1, y0, y1);
        range(bz, 2, z0, z1);
        const std::size_t b = block_linear(bx, by, bz);
        for (int s = 0; s < spectral_count_; ++s) {
          const float* sa = grid.sigma_a(s);
          const float* ss = grid.sigma_s(s);
          // In double, as the field is evaluated (coefficients_at).
          double m = 0.0, least = std::numeric_limits<double>::infinity();
          for (int k = z0; k <= z1; ++k)
            for (int j = y0; j <= y1; ++j)
              for (int i = x0; i <= x1; ++i) {
                const std::size_t v = grid.index(i, j, k);
                const double sigma_t = static_cast<double>(sa[v]) + ss[v];
                m = std::max(m, sigma_t);
                least = std::min(least, sigma_t);
              }
          // Widen slightly so that the bounds hold for the trilinear field with
          // its rounding. A block of one value is left as it is: its field is
          // that value to rounding, and equal bounds make residual ratio
          // tracking exact there.
          if (least < m) {
            m *= 1.0 + 1e-9;
            least *= 1.0 - 1e-9;
          }
          values_[b * spectral_count_ + s] = m;
          minorants_[b * spectral_count_ + s] = least;
          max_[b] = std::max(max_[b], static_cast<float>(m * (1.0 + 1e-6)));
        }
      }
}

}  // namespace obscura
