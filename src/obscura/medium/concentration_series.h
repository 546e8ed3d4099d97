#pragma once
// Particle mass concentration over time on a regular grid: what the preparation
// phase turns into radiative properties (docs/preparation.md). Produced by the
// built-in dispersion model (prep/dispersion) or read from CFD output
// (io/vtk_structured_points, io/netcdf_cf).
//
// Grid convention is GridPlacement's (medium/grid_placement.h): value (i, j, k)
// belongs to the cube of side voxel_size_m whose centre is at
//   origin_m + voxel_size_m · (i + ½, j + ½, k + ½),
// i.e. origin_m is the outer corner of voxel (0, 0, 0). Axes are the world's
// (x east, y north, z up), values x fastest.
#include <optional>
#include <string>
#include <vector>

#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// One scalar per voxel, x fastest.
struct ScalarGrid {
  GridDims dims;
  GridPlacement placement;  // rotation stays identity for concentration grids
  std::vector<float> values;

  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.nx) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims.ny) * k);
  }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  double voxel_volume_m3() const {
    const double h = placement.voxel_size_m;
    return h * h * h;
  }
};

struct ConcentrationFrame {
  double time_s = 0;
  ScalarGrid concentration_g_m3;            // agent mass per volume, g/m³
  std::optional<ScalarGrid> temperature_k;  // same grid; absent → ambient
};

struct ConcentrationSeries {
  std::string source;                      // file or model the series came from, for messages
  std::vector<ConcentrationFrame> frames;  // strictly increasing time_s
};

}  // namespace obscura
