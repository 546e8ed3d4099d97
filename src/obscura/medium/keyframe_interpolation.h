#pragma once
// Per-voxel interpolation of a cloud between the two keyframes that bracket a
// time (docs/physics.md, "Clouds in time"; the source paper's §3.1):
// state = (1 − w)·A + w·B with
//   σa, σs  linear;
//   g       weighted by σs, so a voxel's phase function is that of its scatterers;
//   T       linear, except where one keyframe has no extinction at the voxel
//           (nothing there to have a temperature): there the other keyframe's T.
// Linear T rather than linear emission σa B(T) keeps a physical state (one
// temperature per voxel, used by every integrator); docs/physics.md gives the
// measured difference between the two.
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// Keyframes with the same dims and placement are interpolated voxel by voxel;
// otherwise both are resampled (trilinear, zero outside) onto a grid covering
// the union of their bounds with the finer voxel size. They must share their
// wavelengths and rotation; throws InputError naming `source` otherwise.
// weight 0 returns A exactly and weight 1 returns B exactly.
VoxelGrid interpolate_keyframes(const VoxelGrid& a, const VoxelGrid& b, double weight,
                                const std::string& source = "");

// `grid` resampled onto `dims` voxels placed at `placement` (same rotation),
// by the trilinear reconstruction of GridMedium; zero (and 0 K) outside it.
VoxelGrid resample_grid(const VoxelGrid& grid, GridDims dims, const GridPlacement& placement);

}  // namespace obscura
