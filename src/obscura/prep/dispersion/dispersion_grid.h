#pragma once
// Concentration keyframes of the built-in dispersion model on a regular grid
// (docs/dispersion.md, "Keyframes on a grid").
//
// All frames share ONE grid: the union over the requested times of ±k σ boxes
// around every released puff (k = coverage_sigmas), snapped outwards to whole
// voxels in x and y and starting at the ground (z = 0) in z. One layout makes
// interpolation between keyframes a per-voxel blend, without resampling
// (keyframe_interpolation.h), at the cost of storing early, small clouds in the
// final cloud's box.
//
// Each voxel holds the voxel-AVERAGE concentration, the exact integral of the
// puffs over the voxel's cube divided by its volume: a Gaussian integrates
// over a box as a product of erf differences per axis (the image puff adds its
// own z factor), so Σ value × volume is the released mass even for puffs
// smaller than a voxel (up to the mass beyond the grid, at most ~2·10⁻⁴ of a
// puff at the default 4σ coverage).
#include <vector>

#include "obscura/medium/concentration_series.h"
#include "obscura/prep/dispersion/dispersion_model.h"

namespace obscura {

struct DispersionGridOptions {
  double voxel_size_m = 1.0;     // edge of the cubic voxels (> 0), m
  double coverage_sigmas = 4.0;  // the grid covers ±this many σ around each puff, in [1, 10]
  int threads = 0;               // 0: all cores; results do not depend on it
};

struct DispersionGridLayout {
  GridDims dims;
  GridPlacement placement;  // identity rotation; origin_m.z = 0 (the ground)
};

// The grid that covers the cloud at every time in `times_s` (finite and
// strictly increasing). Throws InputError (field "times_s") if no puff has
// been released by the last time, or naming "voxel_size_m" if the voxel count
// along an axis does not fit an int.
DispersionGridLayout dispersion_grid_layout(const DispersionModel& model,
                                            const std::vector<double>& times_s,
                                            const DispersionGridOptions& options);

// Bytes the series would take: frames × voxels × 2 channels (concentration and
// temperature) × sizeof(float), plus `scratch_bytes` of working memory; throws
// InputError naming `source` and "voxel_size_m" if that overflows or exceeds
// the memory available on this machine (available_memory_bytes, voxel_grid.h).
std::size_t dispersion_series_checked_bytes(const DispersionGridLayout& layout,
                                            std::size_t frame_count, const std::string& source,
                                            std::size_t scratch_bytes = 0);

// One frame per time: voxel-average concentration (g/m³) and temperature (K,
// DispersionModel::temperature_k's mixing rule applied to the voxel averages;
// ambient where no smoke is). The temperature grid is always written, since
// the model knows its ambient. Series source: the configuration's source.
ConcentrationSeries dispersion_series(const DispersionModel& model,
                                      const std::vector<double>& times_s,
                                      const DispersionGridOptions& options);

// Shorthand: builds the model from `config` (validating it) with default
// options at the given voxel size.
ConcentrationSeries dispersion_series(const DispersionConfig& config,
                                      const std::vector<double>& times_s, double voxel_size_m,
                                      int threads = 0);

}  // namespace obscura
