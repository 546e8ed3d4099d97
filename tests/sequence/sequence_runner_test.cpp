// The library sequence runner: frames handed over in order, as the renderer
// makes them; the time series, per-frame figures and screening metrics as
// data; time ranges parsed with errors naming the option.
#include "obscura/sequence/sequence_runner.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <mutex>

#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/renderer.h"
#include "support/input_error.h"

namespace obscura {
namespace {

// A warm absorbing box in front of a hot target box on a ground, seen by two
// one-band sensors; a region of interest on the first.
Scene test_scene() {
  Scene scene;
  for (const char* name : {"a", "b"}) {
    Sensor s;
    s.name = name;
    s.camera = PinholeCamera({0, -20, 2}, {0, 0, 1}, {0, 0, 1}, 30.0, 12, 8);
    s.bands = {Band::preset(std::string(name) == "a" ? "lwir" : "mwir")};
    scene.sensors.push_back(s);
  }
  scene.static_clouds.push_back(std::make_shared<HomogeneousMedium>(
      BBox3({-1, -8, 0}, {1, -6, 2}), std::vector<double>{4.0, 10.0}, std::vector<double>{0.5, 0.5},
      std::vector<double>{0.0, 0.0}, std::vector<double>{0.0, 0.0}, 300.0));
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{288, 0.9}, 0.0));
  auto target = std::make_unique<BoxSurface>("target", SurfaceMaterial{330, 0.9},
                                             BBox3({-2, 0, 0}, {2, 2, 2}));
  target->set_target(true);
  scene.surfaces.push_back(std::move(target));
  scene.sky = Sky::blackbody(250, true);
  scene.regions.push_back({"centre", "a", 4, 2, 8, 6});
  scene.settings.spectral_nodes_per_band = 2;
  scene.settings.threads = 2;
  return scene;
}

TEST(SequenceRunner, HandsOverEveryFrameInOrderAsTheRendererMakesIt) {
  Scene scene = test_scene();
  std::vector<std::size_t> seen;
  std::vector<std::vector<float>> first_radiance;
  SequenceOptions options;
  int masks_calls = 0;
  options.on_masks = [&](const std::vector<TargetMask>& masks) {
    ++masks_calls;
    EXPECT_EQ(masks.size(), 2u);
    EXPECT_TRUE(seen.empty());  // before the first frame
  };
  options.on_frame = [&](const RenderedFrame& f) {
    seen.push_back(f.index);
    ASSERT_EQ(f.images.size(), 2u);
    EXPECT_EQ(f.images[0].sensor, "a");
    EXPECT_EQ(f.time_s, f.index * 0.5);
    first_radiance.push_back(f.images[0].bands[0].radiance);
  };
  const SequenceResult r = render_sequence(scene, {0.0, 0.5, 1.0}, options);
  EXPECT_EQ(masks_calls, 1);
  EXPECT_EQ(seen, (std::vector<std::size_t>{0, 1, 2}));
  ASSERT_EQ(r.sensor_frames.size(), 6u);  // frame-major
  EXPECT_EQ(r.sensor_frames[1].sensor, "b");
  EXPECT_EQ(r.sensor_frames[2].time_s, 0.5);
  // Time series: per frame, the whole image of each sensor plus the region of a.
  EXPECT_EQ(r.time_series.size(), 3u * 3u);
  EXPECT_EQ(r.time_series[1].stats.region, "centre");
  // Screening metrics per frame, sensor and band, and one series per sensor/band.
  EXPECT_TRUE(r.with_metrics);
  EXPECT_EQ(r.metrics.size(), 6u);
  EXPECT_EQ(r.series.size(), 2u);
  // The frames are exactly what render_sensor makes of the staged scene.
  stage_scene(scene, 0.5);
  const SensorImage direct = render_sensor(scene, scene.sensors[0]);
  ASSERT_EQ(direct.bands[0].radiance.size(), first_radiance[1].size());
  EXPECT_EQ(0, std::memcmp(direct.bands[0].radiance.data(), first_radiance[1].data(),
                           first_radiance[1].size() * sizeof(float)));
}

TEST(SequenceRunner, ProgressNamesFrameAndSensor) {
  Scene scene = test_scene();
  std::atomic<int> calls{0}, last_rows{0};
  SequenceOptions options;
  options.progress = [&](const RenderProgress& p) {
    ++calls;
    EXPECT_EQ(p.frames, 2u);
    EXPECT_LT(p.sensor, 2);
    EXPECT_EQ(p.rows_total, 8);
    last_rows = p.rows_done;
  };
  render_sequence(scene, {0.0, 1.0}, options);
  EXPECT_EQ(calls.load(), 2 * 2 * 8);  // every row of every sensor of every frame
}

// A photon method's frame is prepared before its rows: the progress first
// counts the frame's photons (sensor −1), in increasing order up to all the
// spectral nodes' photons, then the sensors' rows. (The cloud absorbs only,
// over a ground: the radiance cache still traces every node's photons for
// the cloud's light on the ground.)
TEST(SequenceRunner, ProgressCountsAFramesPhotonsBeforeItsRows) {
  for (const RenderMethod method : {RenderMethod::kRadianceCache, RenderMethod::kPhotonMap}) {
    Scene scene = test_scene();
    scene.settings.method = method;
    scene.settings.radiance_cache.photons_per_node = 5000;
    scene.settings.photon_map.photons_per_node = 5000;
    std::mutex mutex;
    std::vector<RenderProgress> seen;
    SequenceOptions options;
    options.progress = [&](const RenderProgress& p) {
      std::lock_guard lock(mutex);
      seen.push_back(p);
    };
    render_sequence(scene, {0.0}, options);
    const auto first_row = std::find_if(seen.begin(), seen.end(),
                                        [](const RenderProgress& p) { return p.sensor >= 0; });
    ASSERT_NE(first_row, seen.begin()) << render_method_name(method);
    // 2 sensors × 1 band × 2 nodes (the photon map traces each sensor's
    // bands; the cache each distinct node once, here 4 as well).
    const long long total = 4 * 5000;
    long long before = 0;
    for (auto p = seen.begin(); p != first_row; ++p) {
      EXPECT_EQ(p->sensor, -1);
      EXPECT_EQ(p->photons_total, total) << render_method_name(method);
      EXPECT_GE(p->photons_done, before);
      before = p->photons_done;
    }
    EXPECT_EQ(before, total) << render_method_name(method);
    // Chunks of 2048 photons: three per node at least.
    EXPECT_GE(first_row - seen.begin(), 4 * 3) << render_method_name(method);
    EXPECT_TRUE(std::all_of(first_row, seen.end(), [](const RenderProgress& p) {
      return p.sensor >= 0 && p.photons_total == 0;
    }));
  }
}

TEST(SequenceRunner, ParsesTimeRanges) {
  EXPECT_EQ(parse_time_range("0:1:0.5"), (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(parse_time_range("2:2:1"), (std::vector<double>{2.0}));
  for (const char* bad : {"0:1", "a:1:1", "1:0:1", "0:1:0", "0:1e9:1e-3", "0:1:1x"}) {
    const InputError e = testing::expect_input_error([&] { parse_time_range(bad, "--time"); });
    EXPECT_EQ(e.field(), "--time") << bad;
  }
}

}  // namespace
}  // namespace obscura
