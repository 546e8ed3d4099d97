#pragma once
// One cloud keyframe — a VoxelGrid of σa, σs, g per spectral sample plus
// temperature, at one time — stored as one OpenVDB file (DESIGN.md §4). The
// conventions (grid names, transform, metadata) are in docs/formats.md,
// "Cloud keyframe (OpenVDB)"; this file is their only implementation.
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

// Version written into "obscura_format_version"; readers refuse newer files.
inline constexpr int kCloudKeyframeFormatVersion = 1;

struct CloudKeyframe {
  std::shared_ptr<VoxelGrid> grid;
  double time_s = 0.0;  // seconds after the cloud's activation
};

// Writes `grid` at `time_s` (s after activation, finite and >= 0) to `path`,
// atomically: the file appears complete or not at all, never half-written.
// `extra_metadata` is stored as string file metadata; its keys must not be
// one of the reserved obscura_* / format keys. Validates the grid first (an
// invalid grid would be an unreadable file). Throws InputError on bad input,
// Error on I/O failure.
void write_cloud_keyframe(const std::filesystem::path& path, const VoxelGrid& grid, double time_s,
                          const std::map<std::string, std::string>& extra_metadata = {});

// Reads and validates a keyframe written by write_cloud_keyframe (or by any
// tool that follows the same conventions). Throws InputError naming the file
// and the grid or metadata field on any problem.
CloudKeyframe read_cloud_keyframe(const std::filesystem::path& path);

// Range of one channel over every voxel of the dense grid (zeros included).
struct ChannelSummary {
  std::string name;   // e.g. "sigma_a_000", "temperature"
  std::string units;  // "1/m", "1" or "K"
  float min = 0.0f;
  float max = 0.0f;
  std::size_t nonzero_voxels = 0;  // voxels stored as active in the file
};

// What `obscura info` prints about a keyframe file.
struct KeyframeInfo {
  std::filesystem::path file;
  std::uintmax_t file_bytes = 0;
  GridDims dims;
  std::vector<double> wavelengths_um;
  GridPlacement placement;
  BBox3 world_bounds_m;
  double time_s = 0.0;
  std::vector<ChannelSummary> channels;  // in VoxelGrid channel order
  std::size_t memory_bytes = 0;          // dense in-memory size once loaded
  // Every file-level metadata entry, formatted as text (OpenVDB's str()).
  std::map<std::string, std::string> metadata;
};

// Reads `path` (validating it exactly as read_cloud_keyframe does) and
// summarises it; the voxel data is released before returning.
KeyframeInfo inspect_cloud_keyframe(const std::filesystem::path& path);

}  // namespace obscura
