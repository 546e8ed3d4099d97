#include "obscura/core/triangle_mesh.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace obscura {

BBox3 TriangleMesh::bounds() const {
  BBox3 b;
  for (const Vec3& v : vertices) b.expand(v);
  return b;
}

double TriangleMesh::double_area(std::size_t i) const {
  const auto& t = triangles[i];
  const Vec3& a = vertices[t[0]];
  return length(cross(vertices[t[1]] - a, vertices[t[2]] - a));
}

void TriangleMesh::scale(double factor) {
  for (Vec3& v : vertices) v *= factor;
}

void TriangleMesh::rotate_heading_deg(double deg) {
  const double r = deg * std::numbers::pi / 180.0;
  const double c = std::cos(r), s = std::sin(r);
  for (Vec3& v : vertices) v = Vec3(c * v.x - s * v.y, s * v.x + c * v.y, v.z);
}

void TriangleMesh::translate(const Vec3& offset) {
  for (Vec3& v : vertices) v += offset;
}

int TriangleMesh::find_part(const std::string& name) const {
  for (std::size_t i = 0; i < part_names.size(); ++i)
    if (part_names[i] == name) return static_cast<int>(i);
  return -1;
}

TriangleMesh TriangleMesh::part(std::size_t index) const {
  constexpr std::uint32_t kUnused = std::numeric_limits<std::uint32_t>::max();
  TriangleMesh out;
  out.part_names = {part_names.at(index)};
  std::vector<std::uint32_t> remap(vertices.size(), kUnused);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (triangle_part[i] != index) continue;
    std::array<std::uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      std::uint32_t& r = remap[triangles[i][k]];
      if (r == kUnused) {
        r = static_cast<std::uint32_t>(out.vertices.size());
        out.vertices.push_back(vertices[triangles[i][k]]);
      }
      t[k] = r;
    }
    out.triangles.push_back(t);
    out.triangle_part.push_back(0);
  }
  return out;
}

}  // namespace obscura
