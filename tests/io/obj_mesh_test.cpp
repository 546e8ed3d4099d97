#include "obscura/io/obj_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

using testing::contains;
using testing::expect_input_error;

class ObjMesh : public testing::TempDirTest {
 protected:
  std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  // Reading `text` as an OBJ fails naming the file, `field` and `detail`.
  void expect_error(const std::string& text, const std::string& field, const std::string& detail) {
    testing::expect_file_error(
        dir_ / "bad.obj", text, [](const auto& p) { read_obj_mesh(p); }, field, detail);
  }
};

TEST_F(ObjMesh, ReadsVerticesFacesAndParts) {
  // A tetrahedron in group "a", a quad (triangulated) in object "b", faces
  // before any group in "default", and "a" again (merged).
  const auto path = write("m.obj",
                          "# test\r\n"
                          "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                          "v 2 0 0\nv 3 0 0\nv 3 1 0\nv 2 1 0\n"
                          "f 1 3 2\n"
                          "g a\nf 1 2 4\nf 2 3 4\nf 1 4 3\n"
                          "o b\nf 5/1 6/2 7/3 8/4\n"
                          "g a\nf -8 -6 -7\n");
  const TriangleMesh m = read_obj_mesh(path);
  ASSERT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.vertices[6], Vec3(3, 1, 0));
  ASSERT_EQ(m.part_names, (std::vector<std::string>{"default", "a", "b"}));
  ASSERT_EQ(m.triangle_count(), 7u);
  std::vector<int> per_part(3, 0);
  for (auto p : m.triangle_part) ++per_part[p];
  EXPECT_EQ(per_part, (std::vector<int>{1, 4, 2}));
  // The relative face "-8 -6 -7" is vertices 1, 3, 2.
  EXPECT_EQ(m.triangles.back(), (std::array<std::uint32_t, 3>{0, 2, 1}));
  // The quad's two triangles cover its area (1 m²).
  double area = 0;
  for (std::size_t i = 0; i < m.triangle_count(); ++i)
    if (m.triangle_part[i] == 2) area += 0.5 * m.double_area(i);
  EXPECT_NEAR(area, 1.0, 1e-12);
}

TEST_F(ObjMesh, RoundTripsAWrittenMesh) {
  TriangleMesh in;
  in.part_names = {"left", "right"};
  for (int i = 0; i < 6; ++i)
    in.vertices.emplace_back(0.1 * i - 0.3, 1000.0 / (i + 3), std::sqrt(i + 0.5));
  in.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 2, 4}};
  in.triangle_part = {0, 1, 1};
  std::ofstream out(dir_ / "rt.obj");
  out.precision(17);
  for (const Vec3& v : in.vertices) out << "v " << v.x << ' ' << v.y << ' ' << v.z << '\n';
  for (std::size_t p = 0; p < in.part_names.size(); ++p) {
    out << "g " << in.part_names[p] << '\n';
    for (std::size_t i = 0; i < in.triangles.size(); ++i)
      if (in.triangle_part[i] == p)
        out << "f " << in.triangles[i][0] + 1 << ' ' << in.triangles[i][1] + 1 << ' '
            << in.triangles[i][2] + 1 << '\n';
  }
  out.close();
  const TriangleMesh m = read_obj_mesh(dir_ / "rt.obj");
  // tinyobjloader's own number parser is close to, not always exactly, correctly rounded.
  ASSERT_EQ(m.vertices.size(), in.vertices.size());
  for (std::size_t i = 0; i < in.vertices.size(); ++i)
    EXPECT_LT(length(m.vertices[i] - in.vertices[i]), 1e-12);
  EXPECT_EQ(m.part_names, in.part_names);
  ASSERT_EQ(m.triangle_count(), 3u);
  EXPECT_EQ(m.triangles[0], in.triangles[0]);
  EXPECT_EQ(m.triangles[1], in.triangles[1]);
  EXPECT_EQ(m.triangles[2], in.triangles[2]);
  EXPECT_EQ(m.triangle_part, (std::vector<std::uint32_t>{0, 1, 1}));
}

TEST_F(ObjMesh, ReadsTheExampleTank) {
  const TriangleMesh m = read_obj_mesh(std::string(OBSCURA_SOURCE_DIR) + "/examples/tank/tank.obj");
  EXPECT_EQ(m.part_names,
            (std::vector<std::string>{"hull", "turret", "gun", "tracks", "engine_deck"}));
  EXPECT_EQ(m.triangle_count(), 136u);
  const BBox3 b = m.bounds();
  EXPECT_LT(length(b.lo - Vec3(-1.85, -3.85, 0)), 1e-12);
  EXPECT_LT(length(b.hi - Vec3(1.85, 6.75, 2.4)), 1e-12);
  // Closed and facing outwards: the signed volume of each part is positive.
  for (std::size_t p = 0; p < m.part_names.size(); ++p) {
    const TriangleMesh part = m.part(p);
    double volume = 0;
    for (const auto& t : part.triangles)
      volume += dot(part.vertices[t[0]], cross(part.vertices[t[1]], part.vertices[t[2]])) / 6;
    EXPECT_GT(volume, 0.1) << m.part_names[p];
  }
}

TEST_F(ObjMesh, DropsZeroAreaTriangles) {
  const auto path =
      write("z.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\nf 1 1 3\n");
  EXPECT_EQ(read_obj_mesh(path).triangle_count(), 1u);
}

TEST_F(ObjMesh, MissingFile) {
  const auto path = dir_ / "none.obj";
  const InputError e = expect_input_error([&] { read_obj_mesh(path); });
  EXPECT_EQ(e.file(), path.string());
  EXPECT_TRUE(contains(e.detail(), "no such file")) << e.what();
}

// Refused from its size, before a byte is read (a sparse file: no disk used).
TEST_F(ObjMesh, RefusesAnOversizedFile) {
  const auto path = dir_ / "huge.obj";
  std::ofstream(path) << "v 0 0 0\n";
  std::filesystem::resize_file(path, kMaxObjFileBytes + 1);
  const InputError e = expect_input_error([&] { read_obj_mesh(path); });
  EXPECT_EQ(e.file(), path.string());
  EXPECT_TRUE(contains(e.detail(), "more than the 2147483648 accepted")) << e.what();
}

TEST_F(ObjMesh, EmptyAndGarbageFilesHaveNoTriangles) {
  expect_error("", "", "no faces");
  expect_error("hello world\nthis is not a mesh\n", "", "no faces");
  expect_error(std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), "", "no faces");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "", "no faces");
}

TEST_F(ObjMesh, VertexThatIsNotAFiniteNumber) {
  expect_error("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "line 2", "'nan' is not finite");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 abc\nf 1 2 3\n", "line 3", "'abc' is not a number");
  expect_error("v 0 0 0\nv 1 0\nv 0 1 0\nf 1 2 3\n", "line 2", "three coordinates");
  expect_error("v 0 0 1e999\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "line 1", "'1e999' is not finite");
}

TEST_F(ObjMesh, FaceIndexOutOfRange) {
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\ng x\nf 1 2 9\n", "line 6",
               "vertex index 9 is out of range: the file has 3 vertices");
  // In a polygon, before tinyobjloader triangulates it.
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 4 3 7\n", "line 5", "vertex index 7");
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n", "line 4", "before the first vertex");
  // Index 0 does not exist in OBJ: tinyobjloader's parse error, with its line.
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "", "line 4");
}

// tinyobjloader's int arithmetic wrapped 99999999999999 to 276447231: an index
// beyond int's range is refused before it parses, in every slot of a corner.
TEST_F(ObjMesh, FaceIndexBeyondIntRangeIsAnErrorNotWrapped) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expect_error(tri + "f 1 2 99999999999999\n", "line 4", "'99999999999999' is out of range");
  expect_error(tri + "f 1 2 2147483648\n", "line 4", "'2147483648' is out of range");
  expect_error(tri + "f 1 2 -99999999999999999999\n", "line 4", "is out of range");
  expect_error(tri + "vn 0 0 1\nf 1//1 2//1 3//99999999999\n", "line 5", "is out of range");
  expect_error(tri + "f 1 2 x\n", "line 4", "'x' is not an integer");
}

TEST_F(ObjMesh, FaceWithTooFewVertices) {
  expect_error("v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3", "at least 3 vertices");
}

TEST_F(ObjMesh, PartWithOnlyZeroAreaTriangles) {
  expect_error("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\ng good\nf 1 2 3\ng flat\nf 1 2 4\nf 2 4 1\n",
               "", "part 'flat': all its 2 triangles have zero area");
}

}  // namespace
}  // namespace obscura
