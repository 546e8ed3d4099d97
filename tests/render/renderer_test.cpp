#include "obscura/render/renderer.h"

#include <gtest/gtest.h>

#include <cstring>

#include "medium/test_grids.h"
#include "obscura/core/planck.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "support/furnace_grid.h"
#include "support/render_helpers.h"

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
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.95}, 0.0));
  scene.surfaces.push_back(
      std::make_unique<BoxSurface>("box", SurfaceMaterial{330, 0.9}, BBox3({-1, 3, 0}, {1, 5, 2})));
  scene.sky = Sky::blackbody(240, true);
  scene.settings.samples_per_pixel = spp;
  return scene;
}

// The same image, bit for bit, whatever the thread count (per-pixel RNG streams).
TEST(Renderer, BitIdenticalWithOneAndTwoThreads) {
  Scene scene = test_scene(4);
  const SensorImage a = testing::render_first_sensor(scene, 1, 99);
  const SensorImage b = testing::render_first_sensor(scene, 2, 99);
  ASSERT_EQ(a.bands.size(), b.bands.size());
  for (std::size_t i = 0; i < a.bands.size(); ++i) {
    const auto& x = a.bands[i];
    const auto& y = b.bands[i];
    EXPECT_EQ(0,
              std::memcmp(x.radiance.data(), y.radiance.data(), x.radiance.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(x.transmittance.data(), y.transmittance.data(),
                             x.transmittance.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(x.apparent_temperature.data(), y.apparent_temperature.data(),
                             x.apparent_temperature.size() * sizeof(float)));
  }
  // And the seed matters when pixels are jittered.
  const SensorImage c = testing::render_first_sensor(scene, 1, 100);
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
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{301.5, 1.0}, 0.0));
  scene.sky = Sky::blackbody(230, true);
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
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-50, -50, 0}, {50, 50, 5}), std::vector<double>{4.0}, std::vector<double>{0.2},
      std::vector<double>{0.0}, std::vector<double>{0.0}, 300.0);
  scene.sky = Sky::blackbody(300.0, true);
  const SensorImage img = render_sensor(scene, sensor, {});
  for (float t : img.bands[0].apparent_temperature) EXPECT_NEAR(t, 300.0, 1e-3);
}

// Path tracer as a render method: on a non-scattering cloud over black surfaces
// it must agree with the exact emission–absorption image pixel by pixel, within
// 5 of its own standard errors (and its image mean within 4). (With grey
// surfaces the two differ by design: emission–absorption reflects only the
// uniform sky, the path tracer everything the surface sees.)
TEST(Renderer, PathTracerAgreesWithExactImageWithoutScattering) {
  Scene scene = test_scene(1);
  scene.surfaces.clear();
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 1.0}, 0.0));
  scene.surfaces.push_back(
      std::make_unique<BoxSurface>("box", SurfaceMaterial{330, 1.0}, BBox3({-1, 3, 0}, {1, 5, 2})));
  auto grid = testing::random_grid({12, 10, 8}, 3, 17);
  for (int s = 0; s < 3; ++s)
    for (std::size_t v = 0; v < grid->dims().count(); ++v) grid->sigma_s(s)[v] = 0.0f;
  scene.medium = std::make_shared<GridMedium>(grid);
  scene.sensors[0].camera = PinholeCamera({0, -15, 3}, {0, 0, 2}, {0, 0, 1}, 40.0, 12, 8);
  scene.settings.spectral_nodes_per_band = 3;
  // Both average over the pixel footprint: the exact image with 1024 stratified
  // rays per pixel, so that its own footprint error is small next to the path
  // tracer's standard error with 64.
  scene.settings.samples_per_pixel = 1024;
  const SensorImage exact = render_sensor(scene, scene.sensors[0], {});
  scene.settings.method = RenderMethod::kPathTracer;
  scene.settings.samples_per_pixel = 64;
  const SensorImage mc = render_sensor(scene, scene.sensors[0], {});
  for (std::size_t b = 0; b < mc.bands.size(); ++b) {
    double diff = 0, var = 0;
    for (std::size_t i = 0; i < mc.bands[b].radiance.size(); ++i) {
      const double se = mc.bands[b].radiance_stderr[i];
      const double d = mc.bands[b].radiance[i] - exact.bands[b].radiance[i];
      EXPECT_LE(std::abs(d), 5.0 * se + 1e-6 * exact.bands[b].radiance[i])
          << "band " << b << " pixel " << i;
      EXPECT_NEAR(mc.bands[b].transmittance[i], exact.bands[b].transmittance[i], 0.05);
      diff += d;
      var += se * se;
    }
    EXPECT_LE(std::abs(diff), 4.0 * std::sqrt(var) + 1e-9) << "band " << b;
  }
}

// White furnace as an image: a conservative cloud under a uniform sky.
TEST(Renderer, PathTracerFurnaceImage) {
  Scene scene = testing::furnace_grid_scene(8, 2.0f, 6);
  const Sensor& sensor = scene.sensors[0];
  scene.settings.method = RenderMethod::kPathTracer;
  scene.settings.samples_per_pixel = 200;
  scene.settings.spectral_nodes_per_band = 2;
  const SensorImage img = render_sensor(scene, sensor, {});
  const double l0 = BandQuadrature(Band::preset("lwir"), 2, 0.0).blackbody_radiance(300.0);
  for (std::size_t i = 0; i < img.bands[0].radiance.size(); ++i) {
    EXPECT_NEAR(img.bands[0].radiance[i], l0, 5.0 * img.bands[0].radiance_stderr[i] + 1e-6 * l0)
        << i;
    EXPECT_NEAR(img.bands[0].radiance[i] / l0, 1.0, 0.02) << i;
  }
}

TEST(Renderer, PathTracerIsBitIdenticalWithOneAndTwoThreads) {
  Scene scene = test_scene(3);
  scene.settings.method = RenderMethod::kPathTracer;
  const SensorImage a = testing::render_first_sensor(scene, 1);
  const SensorImage b = testing::render_first_sensor(scene, 2);
  for (std::size_t i = 0; i < a.bands.size(); ++i) {
    EXPECT_EQ(0, std::memcmp(a.bands[i].radiance.data(), b.bands[i].radiance.data(),
                             a.bands[i].radiance.size() * sizeof(float)));
    EXPECT_EQ(0, std::memcmp(a.bands[i].radiance_stderr.data(), b.bands[i].radiance_stderr.data(),
                             a.bands[i].radiance_stderr.size() * sizeof(float)));
  }
}

// A target relative standard error: pixels keep sampling (in rounds of
// samples_per_pixel) until every band meets it or the cap is reached; the
// result is still independent of the thread count.
TEST(Renderer, PathTracerMeetsATargetRelativeStandardError) {
  Scene scene = test_scene(4);
  scene.settings.method = RenderMethod::kPathTracer;
  scene.settings.target_relative_stderr = 0.02;
  scene.settings.max_samples_per_pixel = 2048;
  const SensorImage a = testing::render_first_sensor(scene, 1);
  const SensorImage b = testing::render_first_sensor(scene, 2);
  const std::size_t pixels = a.bands[0].radiance.size();
  EXPECT_GT(a.stats.rays, 4 * pixels);  // some pixels needed more than one round
  EXPECT_LE(a.stats.rays, 2048 * pixels);
  EXPECT_EQ(a.stats.rays, b.stats.rays);
  int capped = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint32_t n = a.samples_per_pixel[i];
    EXPECT_EQ(n % 4, 0u);
    if (n + 4 > 2048) {  // the cap: the next round would exceed it
      ++capped;
      continue;
    }
    for (const auto& band : a.bands)
      EXPECT_LE(band.radiance_stderr[i], 0.02 * band.radiance[i] * (1 + 1e-6))
          << band.band.name() << " " << i;
  }
  EXPECT_LT(capped, static_cast<int>(pixels / 4));
  for (std::size_t i = 0; i < a.bands.size(); ++i)
    EXPECT_EQ(0, std::memcmp(a.bands[i].radiance.data(), b.bands[i].radiance.data(),
                             a.bands[i].radiance.size() * sizeof(float)));
}

}  // namespace
}  // namespace obscura
