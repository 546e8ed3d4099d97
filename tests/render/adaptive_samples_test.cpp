// Adaptive samples for the deterministic methods (RenderSettings::
// adaptive_threshold, render/renderer.h): each pixel is either its centre
// sample or its full stratified samples, bit for bit the images without the
// threshold at one and at samples_per_pixel samples; the refined pixels are
// where the image has an edge, so that the others lie within the threshold of
// the full image while the centres alone do not; and the pixels do not
// depend on the threads or on which rows are rendered.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>

#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/render/renderer.h"
#include "support/render_helpers.h"

namespace obscura {
namespace {

// A warm, smooth puff half in front of a hot box on the ground, under a cold
// sky: the horizon and the box's edges are edges; the puff, the ground and
// the sky are smooth (the puff's radiance changes from pixel to pixel, but
// by little).
Scene edge_scene(int spp, double threshold) {
  Scene scene;
  Sensor sensor;
  sensor.name = "ir";
  sensor.camera = PinholeCamera({0, -15, 3}, {0, 0, 2}, {0, 0, 1}, 40.0, 48, 32);
  sensor.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  GaussianPuffSpec puff;
  puff.center_m = {1.5, 0, 2.5};
  puff.radius_m = 1.5;
  puff.extent_radii = 3.0;
  puff.resolution = 32;
  puff.wavelengths_um = {4.0, 10.0};
  puff.peak_sigma_a = {0.8, 0.6};
  puff.peak_sigma_s = {0.0, 0.0};
  puff.g = {0.0, 0.0};
  puff.ambient_temperature_k = 290;
  puff.temperature_excess_k = 40;
  scene.medium =
      std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(puff)));
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.95}, 0.0));
  scene.surfaces.push_back(
      std::make_unique<BoxSurface>("box", SurfaceMaterial{330, 0.9}, BBox3({-1, 3, 0}, {1, 5, 2})));
  scene.sky = Sky::blackbody(240, true);
  scene.settings.samples_per_pixel = spp;
  scene.settings.adaptive_threshold = threshold;
  return scene;
}

bool same_pixel(const SensorImage& a, const SensorImage& b, std::size_t i) {
  for (std::size_t k = 0; k < a.bands.size(); ++k)
    if (std::memcmp(&a.bands[k].radiance[i], &b.bands[k].radiance[i], sizeof(float)) != 0 ||
        std::memcmp(&a.bands[k].transmittance[i], &b.bands[k].transmittance[i], sizeof(float)) !=
            0 ||
        std::memcmp(&a.bands[k].apparent_temperature[i], &b.bands[k].apparent_temperature[i],
                    sizeof(float)) != 0)
      return false;
  return true;
}

// The largest relative difference in band radiance between images a and b
// over the pixels `keep` accepts.
template <class Keep>
double largest_difference(const SensorImage& a, const SensorImage& b, Keep keep) {
  double worst = 0.0;
  for (std::size_t k = 0; k < a.bands.size(); ++k)
    for (std::size_t i = 0; i < a.bands[k].radiance.size(); ++i)
      if (keep(i))
        worst = std::max(
            worst, std::abs(static_cast<double>(a.bands[k].radiance[i]) - b.bands[k].radiance[i]) /
                       b.bands[k].radiance[i]);
  return worst;
}

TEST(AdaptiveSamples, EachPixelIsItsCentreOrItsFullSamples) {
  Scene adaptive = edge_scene(4, 0.05), full = edge_scene(4, 0.0), centre = edge_scene(1, 0.0);
  const SensorImage a = testing::render_first_sensor(adaptive, 2);
  const SensorImage f = testing::render_first_sensor(full, 2);
  const SensorImage c = testing::render_first_sensor(centre, 2);
  const std::size_t pixels = a.samples_per_pixel.size();
  std::size_t refined = 0;
  for (std::size_t i = 0; i < pixels; ++i) {
    const std::uint32_t n = a.samples_per_pixel[i];
    ASSERT_TRUE(n == 1 || n == 4) << i;
    refined += n == 4;
    EXPECT_TRUE(same_pixel(a, n == 4 ? f : c, i)) << "pixel " << i << ", " << n << " samples";
  }
  // Both kinds, many of each (670 of 1536 refined when written).
  EXPECT_GT(refined, pixels / 5);
  EXPECT_LT(refined, pixels * 3 / 5);
  // The centres of every pixel, plus 4 samples in each refined one.
  EXPECT_EQ(a.stats.rays, pixels + 4 * refined);
}

// What the threshold buys: the pixels it leaves at their centre lie within
// about the threshold of the full image, where the centres alone miss the
// edges by far more.
TEST(AdaptiveSamples, PixelsLeftAtTheirCentreAreWithinTheThresholdOfTheFullImage) {
  Scene adaptive = edge_scene(4, 0.05), full = edge_scene(4, 0.0), centre = edge_scene(1, 0.0);
  const SensorImage a = testing::render_first_sensor(adaptive, 2);
  const SensorImage f = testing::render_first_sensor(full, 2);
  const SensorImage c = testing::render_first_sensor(centre, 2);
  const double centres_alone = largest_difference(c, f, [](std::size_t) { return true; });
  const double adaptive_everywhere = largest_difference(a, f, [](std::size_t) { return true; });
  EXPECT_GT(centres_alone, 0.2);         // 0.81 when written
  EXPECT_LT(adaptive_everywhere, 0.05);  // 0.0035 when written
}

// Progress counts each row twice, for its centres and for its samples, and
// ends at its total.
TEST(AdaptiveSamples, ProgressCountsTheCentresAndTheSamples) {
  Scene scene = edge_scene(4, 0.05);
  scene.settings.threads = 2;
  std::mutex mutex;
  int calls = 0, last_done = 0, total = 0;
  RenderOptions options;
  options.progress = [&](int done, int rows) {
    const std::lock_guard<std::mutex> lock(mutex);
    ++calls;
    last_done = std::max(last_done, done);
    total = rows;
  };
  render_sensor(scene, scene.sensors[0], options);
  const int height = scene.sensors[0].camera.height();
  EXPECT_EQ(calls, 2 * height);
  EXPECT_EQ(last_done, 2 * height);
  EXPECT_EQ(total, 2 * height);
}

TEST(AdaptiveSamples, NoEdgeNoRefinement) {
  Scene scene = edge_scene(4, 0.05);
  scene.medium = nullptr;
  scene.surfaces.clear();  // the uniform sky alone
  const SensorImage a = testing::render_first_sensor(scene, 2);
  for (const std::uint32_t n : a.samples_per_pixel) EXPECT_EQ(n, 1u);
  EXPECT_EQ(a.stats.rays, a.samples_per_pixel.size());
}

TEST(AdaptiveSamples, BitIdenticalWithOneAndTwoThreads) {
  Scene scene = edge_scene(4, 0.05);
  const SensorImage a = testing::render_first_sensor(scene, 1);
  const SensorImage b = testing::render_first_sensor(scene, 2);
  for (std::size_t i = 0; i < a.samples_per_pixel.size(); ++i) {
    EXPECT_EQ(a.samples_per_pixel[i], b.samples_per_pixel[i]);
    EXPECT_TRUE(same_pixel(a, b, i)) << i;
  }
}

// A process's share of the rows (sequence/distributed_frame.h) gives those
// rows' pixels exactly: the centres of the rows next to them are taken too.
TEST(AdaptiveSamples, RowsRenderedApartGiveTheSamePixels) {
  Scene scene = edge_scene(4, 0.05);
  scene.settings.threads = 2;
  const SensorImage whole = render_sensor(scene, scene.sensors[0]);
  RenderOptions share;
  share.row_offset = 1;
  share.row_stride = 3;
  const SensorImage part = render_sensor(scene, scene.sensors[0], share);
  const int width = whole.width;
  for (int y = 1; y < whole.height; y += 3)
    for (int x = 0; x < width; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * width + x;
      EXPECT_EQ(part.samples_per_pixel[i], whole.samples_per_pixel[i]) << x << "," << y;
      EXPECT_TRUE(same_pixel(part, whole, i)) << x << "," << y;
    }
}

}  // namespace
}  // namespace obscura
