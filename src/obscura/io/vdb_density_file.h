#pragma once
// A smoke or explosion volume written by another tool (Houdini, Blender's
// Mantaflow, EmberGen, OpenVDB's own samples): an OpenVDB file holding a
// float density grid and perhaps a temperature grid among others (velocity,
// flame, heat, ...), in the tool's own units. Read as a scene's vdb-density
// cloud (docs/formats.md, "Clouds from other tools' VDB files"): the grids
// come back as dense arrays over the density grid's active bounding box
// only (or, read_vdb_density_parts, over boxes around its clusters of
// active voxels), so a small cloud far from the index origin costs its own
// size, not the index space around it. The file is walked whole (vdb_stream_check.h)
// before OpenVDB reads it.
#include <filesystem>
#include <string>
#include <vector>

#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// The grids' values as the tool stored them, x fastest.
struct VdbDensityVolume {
  GridDims dims;                 // the density grid's active bounding box
  GridPlacement placement;       // from the grids' transform, origin at the box's corner
  int index_min[3] = {0, 0, 0};  // OpenVDB index of voxel (0, 0, 0), for messages
  std::vector<float> density;
  std::vector<float> temperature;  // empty unless a temperature grid was asked for
  bool empty = false;              // the density grid has no active voxel (dims 1×1×1, value 0)
};

// Reads `density_grid` and, unless `temperature_grid` is empty, that grid
// over the same box. Both must be float grids (16-bit half floats included)
// with one linear transform of cubic voxels (rotation and translation
// allowed); the density's background must be 0 (the cloud ends where its
// active voxels do). A density grid without active voxels gives one empty
// voxel at index (0, 0, 0). Checks the dense arrays' memory against the
// limit (core/memory_limit.h) before allocating them. Throws InputError
// naming the file and the grid.
VdbDensityVolume read_vdb_density(const std::filesystem::path& path,
                                  const std::string& density_grid,
                                  const std::string& temperature_grid);

// The same grids in parts where the active voxels lie in clusters far
// apart: the active 8³ leaves (and active tiles) grouped by adjacency, a box
// around each group's active voxels widened by one voxel of background (so
// that the trilinear reconstruction at its rim is the whole grid's), boxes
// that then overlap merged. Returned only when the parts together hold
// under half the voxels of the active bounding box (and are at most
// kMaxVdbDensityParts); otherwise the one box of read_vdb_density. Parts in
// order of their lowest index (z, then y, then x). The memory of all parts
// is checked before any is allocated.
inline constexpr int kMaxVdbDensityParts = 64;
std::vector<VdbDensityVolume> read_vdb_density_parts(const std::filesystem::path& path,
                                                     const std::string& density_grid,
                                                     const std::string& temperature_grid);

}  // namespace obscura
