#pragma once
// Wavefront OBJ meshes (read with tinyobjloader): vertices ("v") and faces
// ("f", polygons triangulated); the parts are the file's groups and objects
// ("g"/"o" names; faces before any are in the part "default"; parts of the
// same name are merged). Materials, normals and texture coordinates are not
// used. Triangles with zero area are dropped.
#include <cstdint>
#include <filesystem>

#include "obscura/core/triangle_mesh.h"

namespace obscura {

// Limits checked before anything large is allocated.
inline constexpr std::uintmax_t kMaxObjFileBytes = std::uintmax_t{2} << 30;  // 2 GiB
inline constexpr std::uint64_t kMaxMeshTriangles = 50'000'000;
inline constexpr std::uint64_t kMaxMeshVertices = 150'000'000;

// Throws InputError naming the file (and the line where there is one) for a
// missing file, one over the limits (bytes, vertices, triangles), a parse
// error, a vertex that is not a finite number, a face index out of range, a
// file without triangles, or a part whose triangles all have zero area.
TriangleMesh read_obj_mesh(const std::filesystem::path& path);

}  // namespace obscura
