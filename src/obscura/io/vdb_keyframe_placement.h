#pragma once
// A GridPlacement (origin, voxel size, rotation) in a cloud-keyframe file
// (io/vdb_keyframe.h): as the grids' OpenVDB transform, and as the exact
// "placement" metadata record that travels beside it. Internal to io/.
#include <openvdb/math/Transform.h>

#include <optional>
#include <string>

#include "obscura/medium/grid_placement.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vdb_format {

// The exact affine index→world map of GridPlacement,
//   world = origin + R·(s·(index + ½)),
// in OpenVDB's row-vector convention (world = index·M, translation in row 3).
openvdb::math::Transform::Ptr placement_to_transform(const GridPlacement& p);

// Inverse of placement_to_transform. The transform holds s·R, not s and R
// apart, and OpenVDB re-simplifies maps as it reads them, so the placement is
// recovered to within a few ulp (~1e-15 relative), not bit for bit.
GridPlacement transform_to_placement(const openvdb::math::Transform& xf, const std::string& file,
                                     const std::string& grid_name);

// The placement as exact decimal text ("origin_m=x,y,z;voxel_size_m=s;rotation=r00,...,r22",
// 17 significant digits): OpenVDB re-simplifies transforms on read, which moves
// their last bits, so the exact values travel beside the transform.
std::string format_placement(const GridPlacement& p);

// Parses format_placement's text; nullopt if it is malformed.
std::optional<GridPlacement> parse_placement(const std::string& text);

// True when two placements map every voxel of the grid to the same world
// point within `tolerance` voxels.
bool placements_agree(const GridPlacement& a, const GridPlacement& b, const GridDims& d,
                      double tolerance);

}  // namespace obscura::vdb_format
