#pragma once
// The voxel data of the two forms of a cloud-keyframe file (io/vdb_keyframe.h),
// read once the common header is known: the spectral grids as a VoxelGrid,
// or the species concentrations and temperature with their optics table.
// Their writers are write_cloud_keyframe and write_species_keyframe.
// Internal to io/.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <memory>
#include <string>

#include "obscura/io/vdb_keyframe_metadata.h"
#include "obscura/medium/species_optics.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vdb_format {

// The spectral form's grids (σa, σs, g per wavelength, temperature),
// validated. Moves h.wavelengths_um into the grid.
std::shared_ptr<VoxelGrid> read_spectral_grids(openvdb::io::File& f, const MetaReader& meta,
                                               const openvdb::MetaMap& file_metadata,
                                               CommonHeader& h, const std::string& file);

// The species form's optics table, concentrations and temperature,
// validated. Moves h.wavelengths_um into the cloud.
SpeciesCloud read_species_grids(openvdb::io::File& f, const MetaReader& meta,
                                const openvdb::MetaMap& file_metadata, CommonHeader& h,
                                const std::string& file);

}  // namespace obscura::vdb_format
