#pragma once
// A heightfield ground: heights (m) on a regular grid, read from a CSV file
// and triangulated into a TriangleMesh for a MeshSurface.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "obscura/core/triangle_mesh.h"

namespace obscura {

inline constexpr std::uint64_t kMaxHeightfieldSamples = 25'000'000;  // 50 M triangles

// Heights z (m) at the samples of a grid, row-major: rows × columns.
struct Heightfield {
  std::size_t rows = 0, columns = 0;
  std::vector<double> heights;
  double at(std::size_t row, std::size_t column) const { return heights[row * columns + column]; }
};

// A CSV file with one row of comma-separated heights (m) per line; blank
// lines and lines starting with '#' are skipped. Throws InputError naming the
// file and "line L column C" for a field that is not a finite number, a row
// whose length differs from the first row's, fewer than 2 × 2 samples, or more
// than kMaxHeightfieldSamples.
Heightfield read_heightfield_csv(const std::filesystem::path& path);

// The surface through the samples: sample (row i, column j) at
// x = origin_x + j·spacing_m, y = origin_y + i·spacing_m, z = height; each
// grid cell is split into two triangles along its diagonal from (i, j) to
// (i + 1, j + 1), normals upward. One part, named `part_name`.
TriangleMesh heightfield_mesh(const Heightfield& h, double origin_x, double origin_y,
                              double spacing_m, const std::string& part_name);

}  // namespace obscura
