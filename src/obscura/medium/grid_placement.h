#pragma once
// Where a regular voxel grid sits in the world (docs/formats.md, "Grid placement").
// Voxel (i, j, k) is a cube of side voxel_size_m whose centre has index-space
// coordinates (i, j, k). The grid's minimum corner — the outer corner of voxel
// (0, 0, 0) — is at world position origin_m, and the grid axes are rotated by
// `rotation` (columns are the grid's x, y, z axes in world coordinates):
//   world = origin_m + rotation · (voxel_size_m · (index + ½)).
#include "obscura/core/mat3.h"
#include "obscura/core/vec3.h"

namespace obscura {

struct GridPlacement {
  Vec3 origin_m{0, 0, 0};
  double voxel_size_m = 1.0;
  Mat3 rotation = Mat3::identity();

  Vec3 index_to_world(const Vec3& index) const {
    return origin_m + rotation * ((index + Vec3(0.5, 0.5, 0.5)) * voxel_size_m);
  }
  Vec3 world_to_index(const Vec3& world) const {
    return rotation.transposed() * (world - origin_m) / voxel_size_m - Vec3(0.5, 0.5, 0.5);
  }
  // A world direction expressed in index units per metre.
  Vec3 world_to_index_direction(const Vec3& d) const {
    return rotation.transposed() * d / voxel_size_m;
  }
};

}  // namespace obscura
