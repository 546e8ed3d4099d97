#pragma once
// The render layer's view of a dense VoxelGrid: trilinear reconstruction
// between voxel centres, clamped to the edge values in the outer half voxel, so
// the medium fills exactly the grid's cells (n·Δ metres along each axis).
// Along a ray, each reconstruction cell gives one MediumSegment whose cubics
// are the exact restriction of the trilinear field to the ray; blocks whose
// majorant is zero are skipped.
#include <memory>

#include "obscura/medium/majorant_grid.h"
#include "obscura/medium/medium.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// A grid's channel arrays per spectral sample, looked up once (not through
// VoxelGrid's accessors per voxel: docs/performance.md).
struct GridChannels {
  GridChannels() = default;
  explicit GridChannels(const VoxelGrid& grid);

  std::vector<const float*> sigma_a, sigma_s, g;
  const float* temperature = nullptr;
};

class GridMedium final : public Medium {
 public:
  // Block size of the majorant grid, in cells: large enough that the block
  // walk is cheap, small enough to skip the empty space around a cloud.
  static constexpr int kDefaultBlockSize = 8;

  explicit GridMedium(std::shared_ptr<const VoxelGrid> grid, int block_size = kDefaultBlockSize);

  BBox3 bounds() const override { return bounds_; }
  const std::vector<double>& wavelengths_um() const override { return grid_->wavelengths_um(); }
  void coefficients_at(const Vec3& p, MediumPoint& out) const override;
  void coefficients_of_samples(const Vec3& p, int first, int second,
                               MediumPoint& out) const override;
  double extinction_at(const Vec3& p, const SpectralLerp& lambda,
                       MediumPoint& scratch) const override;
  void trace_segments(const Ray& ray, double t_min, double t_max,
                      const SegmentVisitor& visit) const override;
  void trace_majorants(const Ray& ray, double t_min, double t_max,
                       const MajorantVisitor& visit) const override;
  // Trilinear values at each cell's entry, middle and exit, straight from the
  // voxels (no cubics), the entry reused from the previous exit.
  void march_cells(const Ray& ray, double t_min, double t_max, const MarchOptions& options,
                   MarchVisitor& visit) const override;
  // By Simpson's rule on march_cells' three points per cell: exact, as
  // trilinear σt along a line is a cubic, and cheaper than building cubics.
  void add_optical_depth(const Ray& ray, double t_min, double t_max, double* tau) const override;
  std::optional<GridFrame> grid_frame() const override {
    return GridFrame{grid_->placement(), grid_->dims(), true, grid_.get()};
  }
  // From the majorant blocks the box's cells fall in.
  bool may_be_nonzero(const BBox3& world_box) const override;

  const VoxelGrid& grid() const { return *grid_; }
  const MajorantGrid& majorants() const { return majorants_; }

 private:
  std::shared_ptr<const VoxelGrid> grid_;
  MajorantGrid majorants_;
  BBox3 bounds_;
  GridChannels channels_;
};

}  // namespace obscura
