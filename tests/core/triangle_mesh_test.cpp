#include "obscura/core/triangle_mesh.h"

#include <gtest/gtest.h>

namespace obscura {
namespace {

TriangleMesh two_parts() {
  TriangleMesh m;
  m.part_names = {"a", "b"};
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {5, 5, 5}, {6, 5, 5}, {5, 6, 7}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {1, 2, 4}};
  m.triangle_part = {0, 1, 0};
  return m;
}

bool near(const Vec3& a, const Vec3& b) { return length(a - b) < 1e-12; }

TEST(MeshGeometry, BoundsAndArea) {
  const TriangleMesh m = two_parts();
  EXPECT_EQ(m.bounds().lo, Vec3(0, 0, 0));
  EXPECT_EQ(m.bounds().hi, Vec3(6, 6, 7));
  EXPECT_DOUBLE_EQ(m.double_area(0), 2.0);
  EXPECT_TRUE(TriangleMesh().bounds().empty());
}

// position + Rz(heading) (scale · v), heading counter-clockwise seen from above.
TEST(MeshGeometry, ScaleHeadingTranslate) {
  TriangleMesh m = two_parts();
  m.scale(2.0);
  m.rotate_heading_deg(90.0);
  m.translate({10, 20, 1});
  EXPECT_TRUE(near(m.vertices[1], Vec3(10, 22, 1)));  // +x turns to +y
  EXPECT_TRUE(near(m.vertices[2], Vec3(6, 20, 1)));   // +y turns to -x
  EXPECT_TRUE(near(m.vertices[5], Vec3(-2, 30, 15)));
  m.rotate_heading_deg(-90.0);
  EXPECT_TRUE(near(m.vertices[1], Vec3(22, -10, 1)));
}

TEST(MeshGeometry, PartKeepsItsTrianglesAndCompactsVertices) {
  const TriangleMesh m = two_parts();
  EXPECT_EQ(m.find_part("b"), 1);
  EXPECT_EQ(m.find_part("c"), -1);
  const TriangleMesh a = m.part(0);
  EXPECT_EQ(a.part_names, std::vector<std::string>{"a"});
  ASSERT_EQ(a.triangle_count(), 2u);
  ASSERT_EQ(a.vertices.size(), 4u);  // 0, 1, 2 and 4
  for (int t = 0; t < 2; ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(a.vertices[a.triangles[t][k]], m.vertices[m.triangles[t == 0 ? 0 : 2][k]]);
  EXPECT_EQ(a.triangle_part, (std::vector<std::uint32_t>{0, 0}));
  EXPECT_EQ(m.part(1).vertices.size(), 3u);
}

}  // namespace
}  // namespace obscura
