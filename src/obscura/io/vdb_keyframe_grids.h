#pragma once
// The float grids of a cloud-keyframe file (io/vdb_keyframe.h): their headers
// checked against the layout of the file's form (type, per-grid metadata,
// one shared transform), their voxels read into dense arrays and written
// from them, and the file written atomically. Internal to io/.
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <filesystem>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "obscura/io/vdb_keyframe_layout.h"
#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vdb_format {

// Refuses a grid named <prefix>NNN (one of `prefixes`) with NNN >= n, e.g.
// sigma_a_005 with spectral_count 5; `problem(NNN)` says why it makes the file
// inconsistent.
void check_no_extra_indexed_grids(openvdb::io::File& f, std::initializer_list<const char*> prefixes,
                                  int n, const std::string& file,
                                  const std::function<std::string(int)>& problem);

// Checks the headers of `layout`'s grids (present, float grids, per-grid
// metadata, one shared transform) without reading voxel data, and returns the
// placement: the exact "placement" record when present and agreeing with the
// transform, else the transform's.
GridPlacement read_layout_placement(openvdb::io::File& f, const openvdb::MetaMap& file_metadata,
                                    const std::vector<GridSpec>& layout, const GridDims& dims,
                                    const std::string& file);

// Reads grid `name` into `out` (dims.count() floats, x fastest): voxels not
// stored take the background. Active voxels outside the dims are an error.
void read_dense_grid(openvdb::io::File& f, const std::string& name, const GridDims& dims,
                     float* out, const std::string& file);

// One float grid of `spec` holding `values` (dims.count() floats, x fastest).
openvdb::FloatGrid::Ptr make_float_grid(const GridSpec& spec, const float* values,
                                        const GridDims& d, const openvdb::math::Transform& xf);

// Writes `grids` and `meta` to `path` through an AtomicFile.
void write_keyframe_file(const std::filesystem::path& path, const openvdb::GridPtrVec& grids,
                         const openvdb::MetaMap& meta);

}  // namespace obscura::vdb_format
