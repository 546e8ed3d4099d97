#pragma once
// The geometry of a VTK STRUCTURED_POINTS dataset (DIMENSIONS, ORIGIN,
// SPACING) and how its POINT_DATA or CELL_DATA become obscura voxels (the
// placement rules in io/vtk_structured_points.h). Internal to io/.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/io/vtk_token_reader.h"
#include "obscura/medium/concentration_series.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura::vtk_legacy {

// Where an array lies: on the points or the cells of the grid, or in the
// dataset-level FIELD data (not on the grid).
enum class Section { kNone, kPoints, kCells };

// "POINT_DATA", "CELL_DATA" or "dataset FIELD", for messages.
const char* section_keyword(Section s);

class GridGeometry {
 public:
  explicit GridGeometry(TokenReader& tokens) : tokens_(tokens) {}

  // The values after the keyword token `kw` (DIMENSIONS, ORIGIN, SPACING or
  // its pre-VTK-4 name ASPECT_RATIO).
  void read_dimensions(const Token& kw);
  void read_origin();
  void read_spacing(const Token& kw);

  // At POINT_DATA / CELL_DATA (`kw`): checks that the geometry is complete and
  // the voxels cubic, then reads the section's count and checks it against
  // DIMENSIONS. Returns the count.
  std::uint64_t read_section_count(const Token& kw, Section s);

  // DIMENSIONS, once read.
  const std::optional<GridDims>& dims() const { return dims_; }

  // The grid of an array of section s (kPoints or kCells) read at token `at`;
  // `role` names it in errors.
  ScalarGrid make_grid(Section s, const Token& at, std::vector<float> values,
                       const std::string& role) const;

 private:
  double voxel_size() const;

  TokenReader& tokens_;
  std::optional<GridDims> dims_;
  Token dims_at_;
  std::optional<Vec3> origin_;
  std::optional<Vec3> spacing_;
  Token spacing_at_;
  double voxel_size_ = 0.0;
};

}  // namespace obscura::vtk_legacy
