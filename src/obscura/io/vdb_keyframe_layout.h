#pragma once
// The conventions of the cloud-keyframe OpenVDB files (io/vdb_keyframe.h,
// docs/formats.md "Cloud keyframe (OpenVDB)") that the reader and the writer
// of both forms share: the format's names and units, the reserved metadata
// keys, and the float grids each form holds. Internal to io/.
#include <openvdb/openvdb.h>
#include <openvdb/tools/Dense.h>

#include <set>
#include <string>
#include <vector>

#include "obscura/medium/species_optics.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vdb_format {

// A dense block of floats, x fastest, as obscura's grids store them.
using DenseXYZ = openvdb::tools::Dense<float, openvdb::tools::LayoutXYZ>;

inline constexpr const char* kFormatName = "cloud-keyframe";
inline constexpr const char* kFormSpectral = "spectral";
inline constexpr const char* kFormSpecies = "species";
inline constexpr const char* kCoefficientUnits = "1/m";
inline constexpr const char* kConcentrationUnits = "g/m3";
inline constexpr const char* kTemperatureUnits = "K";
// The grid whose transform is the keyframe's placement (every form has it).
inline constexpr const char* kTransformGrid = "temperature";

// File-level metadata keys this format owns (either form); extra_metadata
// must not use them.
const std::set<std::string>& reserved_keys();

// openvdb::initialize registers grid, map and metadata types; reading a file
// before it fails with "unregistered type" errors, and it is not thread-safe.
void ensure_openvdb_initialized();

// One float grid of a keyframe file, as written and as expected on reading
// (docs/formats.md): its name, units and class, and the per-grid metadata
// that ties it to the file.
struct GridSpec {
  std::string name;
  std::string units;
  bool fog_volume = false;  // grid class: fog volume (densities) or unknown
  int spectral_index = -1;  // spectral grids: k, with wavelength_um
  double wavelength_um = 0.0;
  std::string species;  // concentration grids: the species' name
};

// The grids of the spectral form, in VoxelGrid channel order (σa, σs, g per
// wavelength, then temperature); names as VoxelGrid::channel_name.
std::vector<GridSpec> spectral_layout(const std::vector<double>& wavelengths_um);

// The grids of the species form: one concentration per species, then temperature.
std::vector<GridSpec> species_layout(const std::vector<SpeciesOptics>& species);

// The index box of a dense grid of dims d.
openvdb::CoordBBox dense_bbox(const GridDims& d);

}  // namespace obscura::vdb_format
