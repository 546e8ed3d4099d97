#pragma once
// One cloud keyframe — a VoxelGrid of σa, σs, g per spectral sample plus
// temperature, at one time — stored as one OpenVDB file (docs/formats.md), in
// one of two forms: the full spectral grids, or the compact species form
// (concentration per particle species plus temperature, and the species'
// optics table), which the reader expands to the same VoxelGrid. The
// conventions (grid names, transform, metadata) are in docs/formats.md,
// "Cloud keyframe (OpenVDB)"; this file and the io/vdb_* files behind it are
// their only implementation.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "obscura/core/bbox.h"
#include "obscura/medium/grid_placement.h"
#include "obscura/medium/species_optics.h"
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

// Writes `cloud` at `time_s` in the compact species form: one concentration
// grid per species (g/m³) and the temperature, with the species' optics as
// file metadata. Atomic, like write_cloud_keyframe, with the same rules for
// `extra_metadata`. Validates the cloud first (validate_species_cloud).
// Throws InputError on bad input, Error on I/O failure.
void write_species_keyframe(const std::filesystem::path& path, const SpeciesCloud& cloud,
                            double time_s,
                            const std::map<std::string, std::string>& extra_metadata = {});

// Reads and validates a keyframe of either form written by
// write_cloud_keyframe or write_species_keyframe (or by any tool that follows
// the same conventions); a species-form file is returned expanded
// (expand_species), so callers never see which form a file holds. Throws
// InputError naming the file and the grid or metadata field on any problem.
CloudKeyframe read_cloud_keyframe(const std::filesystem::path& path);

// Range of one channel over every voxel of the dense grid (zeros included).
struct ChannelSummary {
  std::string name;   // e.g. "sigma_a_000", "temperature"
  std::string units;  // "1/m", "1" or "K"
  float min = 0.0f;
  float max = 0.0f;
  std::size_t nonzero_voxels = 0;  // voxels whose value is not 0 (active in a file)
};

// One species of a species-form keyframe.
struct SpeciesSummary {
  SpeciesOptics optics;          // mass coefficients at the file's wavelengths
  ChannelSummary concentration;  // "concentration_000", "g/m3"
};

// What `obscura info` prints about a keyframe file.
struct KeyframeInfo {
  std::filesystem::path file;
  std::uintmax_t file_bytes = 0;
  std::string form = "spectral";        // "spectral" or "species" (obscura_form)
  std::vector<SpeciesSummary> species;  // species form only, in file order
  GridDims dims;
  std::vector<double> wavelengths_um;
  GridPlacement placement;
  BBox3 world_bounds_m;
  double time_s = 0.0;
  std::vector<ChannelSummary> channels;  // in VoxelGrid channel order (expanded)
  std::size_t memory_bytes = 0;          // dense in-memory size once loaded (expanded)
  std::size_t compact_bytes = 0;         // species form: concentrations + temperature
  // Every file-level metadata entry, formatted as text (OpenVDB's str()).
  std::map<std::string, std::string> metadata;
};

// Reads `path` (validating it exactly as read_cloud_keyframe does) and
// summarises it; the voxel data is released before returning.
KeyframeInfo inspect_cloud_keyframe(const std::filesystem::path& path);

}  // namespace obscura
