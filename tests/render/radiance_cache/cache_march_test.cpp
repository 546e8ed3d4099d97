// The radiance cache's two camera marches (render/radiance_cache/cache_march.h)
// on one cache: over the records alone (the lattice laid on the cloud's
// grid) and over the medium's cells, reading the light from the records. The
// same cells, points and light, so the same radiance up to float rounding:
// with the sun, a surface shading part of the cloud, every SH degree, and
// nodes between the grid's spectral samples.
#include "obscura/render/radiance_cache/cache_march.h"

#include <gtest/gtest.h>

#include "medium/test_grids.h"
#include "obscura/core/sampling.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {
namespace {

Scene sunlit_grid_scene(int sh_degree) {
  Scene scene;
  auto grid = testing::random_grid({10, 8, 6}, 3, 9, rotation_from_euler_deg({10, 0, 30}));
  scene.medium = std::make_shared<GridMedium>(grid);
  Sensor sensor;
  sensor.name = "cam";
  sensor.bands = {Band::flat("b", 3.2, 4.9)};
  sensor.camera = PinholeCamera({0, -12, 3}, {0, 0, 2}, {0, 0, 1}, 40.0, 8, 8);
  scene.sensors.push_back(sensor);
  // A ground through the cloud: the nodes below it are shaded from the sun.
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.7}, 2.6));
  scene.sky = Sky::blackbody(240, true);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 40.0;
  scene.sun.azimuth_deg = 120.0;
  scene.settings.spectral_nodes_per_band = 3;
  scene.settings.radiance_cache.photons_per_node = 4000;
  scene.settings.radiance_cache.sh_degree = sh_degree;
  scene.settings.threads = 2;
  return scene;
}

TEST(CacheMarch, OverTheRecordsEqualsOverTheMediumsCells) {
  for (const int degree : {0, 1, 2, 3, 4, 5, 6}) {
    const Scene scene = sunlit_grid_scene(degree);
    const FrameSpectra spectra = frame_spectra(scene);
    const DistinctNodes distinct = distinct_nodes(spectra);
    const RadianceCache cache(scene, distinct.nodes);
    ASSERT_TRUE(cache.volume().has_medium());
    const SpectralNodes& nodes = spectra[0][0];
    const int* record = distinct.index[0][0].data();
    Rng rng(3, 0);
    const BBox3 box = scene.medium->bounds();
    int lit = 0;
    for (int i = 0; i < 300; ++i) {
      CameraRay camera;
      const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
      const Vec3 e = box.extent();
      const Vec3 target =
          box.lo + Vec3(e.x * rng.uniform(), e.y * rng.uniform(), e.z * rng.uniform());
      camera.ray = Ray{i % 3 == 0 ? target : target - d * 30.0, d};
      if (i % 4 == 0) {  // a surface part-way
        camera.on_surface = true;
        camera.hit.t = 5.0 * rng.uniform();
      }
      double l_records[3] = {0, 0, 0}, t_records[3] = {1, 1, 1}, a_records[3] = {1, 1, 1};
      double l_medium[3] = {0, 0, 0}, t_medium[3] = {1, 1, 1}, a_medium[3] = {1, 1, 1};
      const auto a = march_cache_lattice(scene, cache, camera, nodes, record, -1, l_records,
                                         t_records, a_records);
      const auto b =
          march_cache_medium(scene, cache, camera, nodes, record, l_medium, t_medium, a_medium);
      EXPECT_EQ(a, b) << "degree " << degree << " ray " << i;
      lit += l_medium[0] > 0;
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(l_records[j], l_medium[j], 1e-5 * std::abs(l_medium[j]) + 1e-9)
            << "degree " << degree << " ray " << i << " node " << j;
        EXPECT_NEAR(t_records[j], t_medium[j], 2e-6 * t_medium[j] + 1e-12);
        EXPECT_NEAR(a_records[j], a_medium[j], 2e-6 * a_medium[j] + 1e-12);
      }
    }
    EXPECT_GT(lit, 100);
  }
}

}  // namespace
}  // namespace obscura
