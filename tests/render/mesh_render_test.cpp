// A box made of 12 triangles (an OBJ, through Embree) renders the same image
// as the analytic BoxSurface.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "medium/test_grids.h"
#include "obscura/io/obj_mesh.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/mesh_surface.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class RendererMesh : public testing::TempDirTest {};

// The box lo..hi as an OBJ of 12 outward-facing triangles.
void write_box_obj(const std::filesystem::path& path, const Vec3& lo, const Vec3& hi) {
  std::ofstream out(path);
  out.precision(17);
  out << "g box\n";
  for (int k = 0; k < 8; ++k)
    out << "v " << (k & 1 ? hi.x : lo.x) << ' ' << (k & 2 ? hi.y : lo.y) << ' '
        << (k & 4 ? hi.z : lo.z) << '\n';
  // Corner k has bits (x, y, z); each face as two triangles, counter-clockwise from outside.
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& f : faces)
    out << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << "\nf " << f[0] + 1 << ' '
        << f[2] + 1 << ' ' << f[3] + 1 << '\n';
}

Scene scene_with(std::unique_ptr<Surface> box) {
  Scene scene;
  Sensor sensor;
  sensor.name = "ir";
  sensor.camera = PinholeCamera({5, -10, 6}, {0, 4, 1}, {0, 0, 1}, 35.0, 48, 32);
  sensor.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.medium = std::make_shared<GridMedium>(testing::random_grid({12, 10, 8}, 3, 17));
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.95}, 0.0));
  scene.surfaces.push_back(std::move(box));
  scene.sky = Sky::blackbody(240, true);
  scene.settings.spectral_nodes_per_band = 3;
  return scene;
}

TEST_F(RendererMesh, TriangleBoxRendersLikeTheAnalyticBox) {
  const Vec3 lo(-1, 3, 0), hi(1, 5, 2);
  // Grey, with a spectral emissivity: the sky reflection depends on the normal.
  SurfaceMaterial m{330, 0.0, {{3.0, 0.6}, {12.0, 0.9}}};
  write_box_obj(dir_ / "box.obj", lo, hi);
  const TriangleMesh mesh = read_obj_mesh(dir_ / "box.obj");
  ASSERT_EQ(mesh.triangle_count(), 12u);
  Scene analytic = scene_with(std::make_unique<BoxSurface>("box", m, BBox3(lo, hi)));
  Scene triangles = scene_with(std::make_unique<MeshSurface>("box", m, mesh));
  analytic.settings.threads = triangles.settings.threads = 2;
  const SensorImage a = render_sensor(analytic, analytic.sensors[0]);
  const SensorImage b = render_sensor(triangles, triangles.sensors[0]);
  ASSERT_EQ(a.bands.size(), b.bands.size());
  int box_pixels = 0;
  for (std::size_t k = 0; k < a.bands.size(); ++k)
    for (std::size_t i = 0; i < a.bands[k].radiance.size(); ++i) {
      EXPECT_NEAR(b.bands[k].radiance[i], a.bands[k].radiance[i], 1e-5 * a.bands[k].radiance[i])
          << "pixel " << i;
      EXPECT_NEAR(b.bands[k].transmittance[i], a.bands[k].transmittance[i], 1e-5) << "pixel " << i;
      box_pixels += k == 0 && a.bands[k].apparent_temperature[i] > 300;
    }
  EXPECT_GT(box_pixels, 40);  // the box fills part of the image
}

}  // namespace
}  // namespace obscura
