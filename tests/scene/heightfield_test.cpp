#include "obscura/scene/heightfield.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>

#include "obscura/scene/mesh_surface.h"
#include "support/input_error.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

using testing::contains;
using testing::expect_input_error;

constexpr double kInf = std::numeric_limits<double>::infinity();

class HeightfieldSurface : public testing::TempDirTest {
 protected:
  std::filesystem::path write(const std::string& text) {
    const auto path = dir_ / "h.csv";
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  // Reading `text` as a heightfield fails naming the file, `field` and `detail`.
  void expect_error(const std::string& text, const std::string& field, const std::string& detail) {
    testing::expect_file_error(
        dir_ / "bad.csv", text, [](const auto& p) { read_heightfield_csv(p); }, field, detail);
  }
  // A rows × columns grid of z = f(x, y), written as CSV and read back.
  template <class F>
  Heightfield sampled(std::size_t rows, std::size_t columns, double x0, double y0, double s, F f) {
    std::ostringstream csv;
    csv.precision(17);
    for (std::size_t i = 0; i < rows; ++i)
      for (std::size_t j = 0; j < columns; ++j)
        csv << f(x0 + j * s, y0 + i * s) << (j + 1 < columns ? "," : "\n");
    return read_heightfield_csv(write(csv.str()));
  }
};

TEST_F(HeightfieldSurface, ReadsRowsColumnsCommentsAndLineEnds) {
  const auto h =
      read_heightfield_csv(write("# heights\r\n1, 2,3\r\n\r\n  4,5 ,6.5e1\n# end\n-7,+8,9"));
  ASSERT_EQ(h.rows, 3u);
  ASSERT_EQ(h.columns, 3u);
  EXPECT_EQ(h.at(0, 1), 2.0);
  EXPECT_EQ(h.at(1, 2), 65.0);
  EXPECT_EQ(h.at(2, 0), -7.0);
  EXPECT_EQ(h.at(2, 1), 8.0);
}

TEST_F(HeightfieldSurface, MeshPlacesSamplesOnTheGrid) {
  Heightfield h{2, 3, {0, 1, 2, 3, 4, 5}};
  const TriangleMesh m = heightfield_mesh(h, 10, 20, 0.5, "t");
  ASSERT_EQ(m.vertices.size(), 6u);
  EXPECT_EQ(m.vertices[5], Vec3(11, 20.5, 5));
  EXPECT_EQ(m.triangle_count(), 4u);
  EXPECT_EQ(m.part_names, std::vector<std::string>{"t"});
  for (const auto& t : m.triangles)  // counter-clockwise seen from above
    EXPECT_GT(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]).z, 0);
}

// A flat heightfield is the ground plane wherever it extends.
TEST_F(HeightfieldSurface, FlatHeightfieldMatchesTheGroundPlane) {
  const auto h = sampled(4, 6, -250, -150, 100, [](double, double) { return 12.5; });
  const MeshSurface mesh("terrain", {290, 1}, heightfield_mesh(h, -250, -150, 100, "terrain"));
  const GroundPlane plane("ground", {290, 1}, 12.5);
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 2000; ++i) {
    // Towards a point of the footprint (x -250..250, y -150..150), from above or below, near or 2
    // km away.
    const Vec3 p(-249 + 498 * u(rng), -149 + 298 * u(rng), 12.5);
    const double range = i % 2 ? 2000.0 : 5.0 + 50 * u(rng);
    Vec3 d(u(rng) - 0.5, u(rng) - 0.5, (i % 4 < 2 ? -1 : 1) * (0.05 + u(rng)));
    d = normalize(d);
    const Ray ray{p - d * range, d};
    SurfaceHit a, b;
    ASSERT_TRUE(plane.intersect(ray, 0, kInf, a));
    ASSERT_TRUE(mesh.intersect(ray, 0, kInf, b)) << i;
    EXPECT_NEAR(b.t, a.t, 1e-9 * a.t);
    EXPECT_EQ(b.normal, a.normal);
  }
}

// z = a + b x + c y, sampled exactly: hits at the closed form.
TEST_F(HeightfieldSurface, TiltedPlaneHitsAtTheClosedForm) {
  const double a = 3.0, b = 0.05, c = -0.125;
  auto z = [&](double x, double y) { return a + b * x + c * y; };
  const auto h = sampled(5, 7, 1000, 2000, 10, z);
  const MeshSurface mesh("tilted", {290, 1}, heightfield_mesh(h, 1000, 2000, 10, "tilted"));
  const Vec3 up = normalize(Vec3(-b, -c, 1));
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 2000; ++i) {
    const double x = 1000.5 + 59 * u(rng), y = 2000.5 + 39 * u(rng);
    const Vec3 p(x, y, z(x, y));
    Vec3 d = normalize(Vec3(u(rng) - 0.5, u(rng) - 0.5, -(0.1 + u(rng))));
    if (i % 2) d = -d;  // from below
    const Ray ray{p - d * (1.0 + 500 * u(rng)), d};
    // Closed form: o_z + t d_z = a + b (o_x + t d_x) + c (o_y + t d_y).
    const double t =
        (a + b * ray.origin.x + c * ray.origin.y - ray.origin.z) / (d.z - b * d.x - c * d.y);
    SurfaceHit hit;
    ASSERT_TRUE(mesh.intersect(ray, 0, kInf, hit)) << i;
    EXPECT_NEAR(hit.t, t, 1e-9 * t);
    const Vec3 n = dot(up, d) < 0 ? up : -up;
    EXPECT_LT(length(hit.normal - n), 1e-12);
  }
}

// What lies below a terrain is inside its solid, where no light travels
// (Surface::encloses: the environment photons launch none there): for a
// heightfield as for the ground plane; a mesh not taken as terrain encloses
// nothing it does not know; a box its inside.
TEST_F(HeightfieldSurface, ATerrainEnclosesWhatLiesBelowIt) {
  const double a = 3.0, b = 0.05, c = -0.125;
  auto z = [&](double x, double y) { return a + b * x + c * y; };
  const auto h = sampled(5, 7, 1000, 2000, 10, z);
  MeshSurface mesh("tilted", {290, 1}, heightfield_mesh(h, 1000, 2000, 10, "tilted"));
  const GroundPlane plane("ground", {290, 1}, 12.5);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0, 1);
  for (int i = 0; i < 200; ++i) {
    const double x = 1000.5 + 59 * u(rng), y = 2000.5 + 39 * u(rng), dz = 0.01 + 5 * u(rng);
    mesh.set_terrain(true);
    EXPECT_TRUE(mesh.encloses({x, y, z(x, y) - dz})) << i;
    EXPECT_FALSE(mesh.encloses({x, y, z(x, y) + dz})) << i;
    mesh.set_terrain(false);
    EXPECT_FALSE(mesh.encloses({x, y, z(x, y) - dz})) << i;
    EXPECT_TRUE(plane.encloses({x, y, 12.5 - dz})) << i;
    EXPECT_FALSE(plane.encloses({x, y, 12.5 + dz})) << i;
  }
  const BoxSurface box("box", {290, 1}, BBox3({-1, -2, 0}, {1, 2, 3}));
  EXPECT_TRUE(box.encloses({0.9, -1.9, 2.9}));
  EXPECT_FALSE(box.encloses({1.1, 0, 1}));
  EXPECT_FALSE(box.encloses({0, 0, 3}));  // on a face: outside
}

// Watertight: rays aimed exactly at the grid's vertices and at the middles of
// its edges and diagonals find the ground there, never slipping through.
TEST_F(HeightfieldSurface, NoLeaksThroughEdgesAndVertices) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u(0, 1);
  Heightfield h{6, 7, {}};
  for (std::size_t i = 0; i < h.rows * h.columns; ++i) h.heights.push_back(20 * u(rng));
  const TriangleMesh m = heightfield_mesh(h, 3000, -2000, 25, "bumps");
  const MeshSurface s("bumps", {290, 1}, m);
  int rays = 0;
  for (const auto& tri : m.triangles)
    for (int k = 0; k < 3; ++k)
      for (const double f : {0.0, 0.5}) {
        const Vec3 target = m.vertices[tri[k]] * (1 - f) + m.vertices[tri[(k + 1) % 3]] * f;
        // Inner ones only: a ray through the border of an open mesh may go either way.
        if (!(target.x > 3000 && target.x < 3150 && target.y > -2000 && target.y < -1875)) continue;
        const Vec3 d = normalize(Vec3(u(rng) - 0.5, u(rng) - 0.5, -1.0));
        const double range = rays % 2 ? 1500.0 : 40.0;
        SurfaceHit hit;
        ASSERT_TRUE(s.intersect(Ray{target - d * range, d}, 0, kInf, hit)) << "ray " << rays;
        // The nearest hit may be a hill in front, never beyond the target.
        EXPECT_LE(hit.t, range * (1 + 1e-12));
        ++rays;
      }
  EXPECT_GT(rays, 250);
}

TEST_F(HeightfieldSurface, RaggedRow) {
  expect_error("1,2,3\n4,5,6\n7,8\n", "line 3", "2 values, but the first row has 3");
}

TEST_F(HeightfieldSurface, NotANumber) {
  expect_error("1,2,3\n4,five,6\n", "line 2 column 2", "'five' is not a number");
  expect_error("1,2,3\n4,5,6,\n", "line 2 column 4", "empty field");
  expect_error("1 2 3\n4 5 6\n", "line 1 column 1", "is not a number");  // not comma-separated
}

TEST_F(HeightfieldSurface, NotFinite) {
  expect_error("1,2\nnan,4\n", "line 2 column 1", "'nan' is not a finite height");
  expect_error("1,inf\n3,4\n", "line 1 column 2", "not a finite height");
  expect_error("1,2\n3,1e999\n", "line 2 column 2", "not a finite height");  // overflows
}

TEST_F(HeightfieldSurface, TooFewSamples) {
  expect_error("1,2,3,4\n", "", "at least 2 x 2");
  expect_error("1\n2\n3\n", "", "at least 2 x 2");
  expect_error("# nothing\n\n", "", "at least 2 x 2");
  expect_error("", "", "at least 2 x 2");
}

TEST_F(HeightfieldSurface, MissingFile) {
  const InputError e = expect_input_error([&] { read_heightfield_csv(dir_ / "none.csv"); });
  EXPECT_TRUE(contains(e.detail(), "no such file")) << e.what();
}

}  // namespace
}  // namespace obscura
