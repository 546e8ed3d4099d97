#include "obscura/render/renderer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "medium/test_grids.h"
#include "obscura/core/planck.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

Scene test_scene(int spp) {
  Scene scene;
  Sensor sensor;
  sensor.name = "ir";
  sensor.camera = PinholeCamera({0, -15, 3}, {0, 0, 2}, {0, 0, 1}, 40.0, 48, 32);
  sensor.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.medium = std::make_shared<GridMedium>(testing::random_grid({12, 10, 8}, 3, 17));
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.95}, 0.0));
  scene.surfaces.push_back(
      std::make_unique<BoxSurface>("box", SurfaceMaterial{330, 0.9}, BBox3({-1, 3, 0}, {1, 5, 2})));
  scene.sky.temperature_k = 240;
  scene.settings.samples_per_pixel = spp;
  return scene;
}

// The same image, bit for bit, whatever the thread count (per-pixel RNG streams).
TEST(Renderer, BitIdenticalWithOneAndTwoThreads) {
  const Scene scene = test_scene(4);
  RenderOptions one, two;
  one.threads = 1;
  two.threads = 2;
  one.seed = two.seed = 99;
  const SensorImage a = render_sensor(scene, scene.sensors[0], one);
  const SensorImage b = render_sensor(scene, scene.sensors[0], two);
  ASSERT_EQ(a.bands.size(), b.bands.size());
  for (std::size_t i = 0; i < a.bands.size(); ++i) {
    const auto& x = a.bands[i];
    const auto& y = b.bands[i];
    EXPECT_EQ(0, std::memcmp(x.radiance.data(), y.radiance.data(), x.radiance.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(x.transmittance.data(), y.transmittance.data(),
                             x.transmittance.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(x.apparent_temperature.data(), y.apparent_temperature.data(),
                             x.apparent_temperature.size() * sizeof(float)));
  }
  // And the seed matters when pixels are jittered.
  RenderOptions other = one;
  other.seed = 100;
  const SensorImage c = render_sensor(scene, scene.sensors[0], other);
  EXPECT_NE(0, std::memcmp(a.bands[0].radiance.data(), c.bands[0].radiance.data(),
                           a.bands[0].radiance.size() * sizeof(float)));
}

// Without a medium, a blackbody ground at T is seen at apparent temperature T
// and transmittance 1; the sky above the horizon at its own temperature.
TEST(Renderer, BlackbodySurfacesAreSeenAtTheirTemperature) {
  Scene scene;
  Sensor sensor;
  sensor.name = "cam";
  sensor.camera = PinholeCamera({0, 0, 10}, {0, 100, 10}, {0, 0, 1}, 60.0, 8, 8);
  sensor.bands = {Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{301.5, 1.0}, 0.0));
  scene.sky.temperature_k = 230;
  const SensorImage img = render_sensor(scene, sensor, {});
  const auto& b = img.bands[0];
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const std::size_t i = y * 8 + x;
      EXPECT_NEAR(b.apparent_temperature[i], y < 4 ? 230.0 : 301.5, 1e-3);
      EXPECT_FLOAT_EQ(b.transmittance[i], 1.0f);
    }
}

// A grey surface reflecting a uniform sky at its own temperature is in
// equilibrium: it looks like a blackbody (Kirchhoff), whatever its emissivity.
TEST(Renderer, GreySurfaceInEquilibriumWithSkyLooksBlack) {
  Scene scene;
  Sensor sensor;
  sensor.name = "cam";
  sensor.camera = PinholeCamera({0, 0, 10}, {0, 10, 0}, {0, 0, 1}, 30.0, 4, 4);
  sensor.bands = {Band::preset("mwir")};
  scene.sensors.push_back(sensor);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("g", SurfaceMaterial{300.0, 0.3}, 0.0));
  scene.medium = std::make_shared<HomogeneousMedium>(BBox3({-50, -50, 0}, {50, 50, 5}),
                                                     std::vector<double>{4.0},
                                                     std::vector<double>{0.2},
                                                     std::vector<double>{0.0},
                                                     std::vector<double>{0.0}, 300.0);
  scene.sky.temperature_k = 300.0;
  const SensorImage img = render_sensor(scene, sensor, {});
  for (float t : img.bands[0].apparent_temperature) EXPECT_NEAR(t, 300.0, 1e-3);
}

}  // namespace
}  // namespace obscura
