#pragma once
// A plain triangle mesh: vertices in metres (double), triangles as index
// triples, and a named part per triangle (an OBJ group, a vehicle component).
// What is stored, apart from how it is intersected (scene/mesh_surface.h).
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/core/bbox.h"

namespace obscura {

struct TriangleMesh {
  std::vector<Vec3> vertices;                           // m
  std::vector<std::array<std::uint32_t, 3>> triangles;  // indices into vertices
  std::vector<std::uint32_t> triangle_part;             // per triangle, index into part_names
  std::vector<std::string> part_names;

  std::size_t triangle_count() const { return triangles.size(); }
  // The box around every vertex (empty for an empty mesh).
  BBox3 bounds() const;
  // Twice the area of triangle i, i.e. |(b − a) × (c − a)| (m²); 0 when degenerate.
  double double_area(std::size_t i) const;

  // Transforms, applied to every vertex in place.
  void scale(double factor);  // uniform, about the origin; factor > 0
  // Rotation about +z by `deg` degrees, counter-clockwise seen from above
  // (+x turns towards +y), about the origin.
  void rotate_heading_deg(double deg);
  void translate(const Vec3& offset);

  // Index of the part called `name`, or -1.
  int find_part(const std::string& name) const;
  // The triangles of one part as a mesh of its own (used vertices only, in
  // first-use order; a single part keeping the name).
  TriangleMesh part(std::size_t index) const;
};

}  // namespace obscura
