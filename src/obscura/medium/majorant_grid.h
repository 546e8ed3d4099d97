#pragma once
// Coarse grid of upper bounds on the extinction σt = σa + σs (1/m) of a
// VoxelGrid, one value per block of block_size³ reconstruction cells and per
// spectral sample. Trilinear interpolation never exceeds the largest of its
// corner values, so the maximum over the voxels that influence a block bounds
// σt everywhere inside it. Used to skip empty space and, later, as the
// majorant for delta and ratio tracking (pbrt-v4 MajorantGrid); the least
// value over the same voxels bounds it from below (the control of residual
// ratio tracking, medium/tracking.h).
//
// Blocks tile "cell space": reconstruction cell c ∈ [−1, n−1] along an axis
// spans index coordinates [c, c+1] (clipped to the grid's [−½, n−½]); it is
// stored as c + 1 ∈ [0, n], so block b holds cells [b·B, b·B + B − 1].
#include <array>
#include <vector>

#include "obscura/medium/voxel_grid.h"

namespace obscura {

class MajorantGrid {
 public:
  MajorantGrid(const VoxelGrid& grid, int block_size);

  int block_size() const { return block_size_; }
  const std::array<int, 3>& block_dims() const { return block_dims_; }
  // Bound on σt in the block for one spectral sample, 1/m.
  double majorant(int bx, int by, int bz, int sample) const {
    return values_[(block_linear(bx, by, bz)) * spectral_count_ + sample];
  }
  // Bound over all spectral samples.
  float max_majorant(int bx, int by, int bz) const { return max_[block_linear(bx, by, bz)]; }
  // Lower bound on σt in the block for one spectral sample, 1/m (the least
  // of the same voxels, as trilinear interpolation never goes below it).
  double minorant(int bx, int by, int bz, int sample) const {
    return minorants_[(block_linear(bx, by, bz)) * spectral_count_ + sample];
  }

 private:
  std::size_t block_linear(int bx, int by, int bz) const {
    return static_cast<std::size_t>(bx) +
           static_cast<std::size_t>(block_dims_[0]) *
               (static_cast<std::size_t>(by) + static_cast<std::size_t>(block_dims_[1]) * bz);
  }
  int block_size_;
  int spectral_count_;
  std::array<int, 3> block_dims_{};
  std::vector<double> values_, minorants_;
  std::vector<float> max_;
};

}  // namespace obscura
