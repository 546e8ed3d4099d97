#include "obscura/io/vtk_grid_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace obscura::vtk_legacy {
namespace {

// Cubic voxels: spacings that differ by more than this (relative) are refused.
constexpr double kIsotropyTolerance = 1e-6;

}  // namespace

const char* section_keyword(Section s) {
  return s == Section::kPoints  ? "POINT_DATA"
         : s == Section::kCells ? "CELL_DATA"
                                : "dataset FIELD";
}

void GridGeometry::read_dimensions(const Token& kw) {
  GridDims d;
  d.nx = tokens_.expect_integer<int>("DIMENSIONS nx", 1, std::numeric_limits<int>::max());
  d.ny = tokens_.expect_integer<int>("DIMENSIONS ny", 1, std::numeric_limits<int>::max());
  d.nz = tokens_.expect_integer<int>("DIMENSIONS nz", 1, std::numeric_limits<int>::max());
  dims_ = d;
  dims_at_ = kw;
}

void GridGeometry::read_origin() {
  Vec3 o;
  for (int a = 0; a < 3; ++a) o[a] = tokens_.expect_double("an ORIGIN component");
  origin_ = o;
}

void GridGeometry::read_spacing(const Token& kw) {
  Vec3 s;
  for (int a = 0; a < 3; ++a) s[a] = tokens_.expect_double(fmt::format("{} component", kw.text));
  spacing_ = s;
  spacing_at_ = kw;
}

// The voxel size, once DIMENSIONS and SPACING are both known. ScalarGrid
// voxels are cubes (one voxel_size_m): an anisotropic grid would have to be
// resampled, which is the CFD post-processor's job. The spacing of an axis
// with a single point places nothing (writers of 2-D slices put 0 or 1
// there), so it is ignored; the slice is one voxel thick.
double GridGeometry::voxel_size() const {
  const Vec3& s = *spacing_;
  const int n[3] = {dims_->nx, dims_->ny, dims_->nz};
  const std::string text = fmt::format("{} {} {} {}", spacing_at_.text, s.x, s.y, s.z);
  double h = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (n[a] == 1 && !(n[0] == 1 && n[1] == 1 && n[2] == 1)) continue;
    if (!(s[a] > 0.0)) tokens_.fail(spacing_at_, text + ": the spacing must be > 0 m");
    if (h == 0.0) {
      h = s[a];
    } else if (std::abs(s[a] - h) > kIsotropyTolerance * h) {
      tokens_.fail(spacing_at_,
                   fmt::format("{}: obscura grids have cubic voxels, so the spacing must "
                               "be the same along x, y and z (to a relative {}); resample "
                               "the data onto an isotropic grid",
                               text, kIsotropyTolerance));
    }
  }
  return h;
}

std::uint64_t GridGeometry::read_section_count(const Token& kw, Section s) {
  if (!dims_) tokens_.fail(kw, fmt::format("{} before DIMENSIONS", kw.text));
  if (!spacing_)
    tokens_.fail(kw, fmt::format("{} before SPACING: the grid spacing is required", kw.text));
  voxel_size_ = voxel_size();
  if (!origin_)
    tokens_.fail(kw, fmt::format("{} before ORIGIN: the grid origin is required", kw.text));
  const std::uint64_t n = tokens_.expect_integer<std::uint64_t>(
      fmt::format("the {} count", kw.text), 0, std::numeric_limits<std::int64_t>::max());
  // Points: nx·ny·nz. Cells: VTK drops axes with a single point
  // (vtkStructuredData), so a 2-D image of 10×10×1 points has 9×9 cells.
  const std::uint64_t expected = s == Section::kPoints
                                     ? dims_->count()
                                     : static_cast<std::uint64_t>(std::max(dims_->nx - 1, 1)) *
                                           static_cast<std::uint64_t>(std::max(dims_->ny - 1, 1)) *
                                           static_cast<std::uint64_t>(std::max(dims_->nz - 1, 1));
  if (n != expected)
    tokens_.fail(
        kw, fmt::format("{} {} does not match DIMENSIONS {} {} {} ({}): {} {} expected", kw.text, n,
                        dims_->nx, dims_->ny, dims_->nz, Lexer::where(dims_at_), expected,
                        s == Section::kPoints ? "points" : "cells"));
  return n;
}

ScalarGrid GridGeometry::make_grid(Section s, const Token& at, std::vector<float> values,
                                   const std::string& role) const {
  ScalarGrid g;
  const double h = voxel_size_;
  if (s == Section::kPoints) {
    g.dims = *dims_;
    g.placement.origin_m = *origin_ - Vec3(h, h, h) * 0.5;
  } else {
    if (dims_->nx < 2 || dims_->ny < 2 || dims_->nz < 2)
      tokens_.fail(at, fmt::format("{} is CELL_DATA on DIMENSIONS {} {} {}: a grid with a single "
                                   "point along an axis has flat cells, which are not voxels",
                                   role, dims_->nx, dims_->ny, dims_->nz));
    g.dims = GridDims{dims_->nx - 1, dims_->ny - 1, dims_->nz - 1};
    g.placement.origin_m = *origin_;
  }
  g.placement.voxel_size_m = h;
  g.values = std::move(values);
  return g;
}

}  // namespace obscura::vtk_legacy
