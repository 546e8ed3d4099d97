#pragma once
// A scene cloud from another tool's VDB files (docs/formats.md, "Clouds from
// other tools' VDB files"): {"type": "vdb-density", "file": "explosion.vdb",
// "material": "soot", "density_scale": …, …}. The tool's density grid is read
// as a mass concentration and turned into σa, σs and g through a material of
// the database, as `obscura prepare` does (medium/voxelise.h), when the file
// is read; a numbered sequence ("explosion_####.vdb") becomes an animated
// cloud whose keyframes are its frames at a frame rate.
#include <filesystem>
#include <string>
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/medium/species_optics.h"
#include "obscura/medium/voxel_grid.h"
#include "obscura/scene/scene.h"

namespace obscura {

// How the tool's grids map to a cloud.
struct VdbDensityMapping {
  std::string density_grid = "density";
  double density_scale_g_m3 = 1.0;  // g/m³ per unit of the density grid
  std::string temperature_grid;     // empty: the ambient temperature everywhere
  double temperature_scale = 1.0;   // K per unit of the temperature grid
  double temperature_offset_k = 0.0;
  double ambient_temperature_k = 288.15;
  Vec3 position_m{0, 0, 0};  // added to the file's translation
};

// The voxel grid of one VDB file, over its density grid's active bounding
// box: per voxel the concentration c = density_scale × density (g/m³) and
//   σa(λ) = c k_abs(λ),  σs(λ) = c k_sca(λ),  g(λ) = the species' g,
// and T = temperature_offset + temperature_scale × temperature (K), or the
// ambient temperature without a temperature grid. Throws InputError naming
// the file and the grid (and a voxel by its OpenVDB index where a value maps
// to a negative or non-finite concentration or temperature).
VoxelGrid read_vdb_density_cloud(const std::filesystem::path& file,
                                 const VdbDensityMapping& mapping, const SpeciesOptics& optics);

// The same, one grid per part of read_vdb_density_parts: where the active
// voxels lie in clusters far apart, a grid around each rather than one box
// around all (a static cloud; a sequence's frames stay one box each, as
// keyframes are interpolated voxel by voxel).
std::vector<VoxelGrid> read_vdb_density_cloud_parts(const std::filesystem::path& file,
                                                    const VdbDensityMapping& mapping,
                                                    const SpeciesOptics& optics);

// Parses one "/clouds/i" object of type "vdb-density" (`o`, relative paths
// against `base`) into `scene`: static clouds for one file (one per part of
// read_vdb_density_cloud_parts), an AnimatedCloud for a numbered sequence
// (its first frame read at once, so that a wrong grid name fails at load). Throws InputError naming
// the scene file and the JSON path, or the VDB file and its grid.
class JsonObject;
void parse_vdb_density_cloud(JsonObject& o, const std::filesystem::path& base, Scene& scene,
                             int index);

}  // namespace obscura
