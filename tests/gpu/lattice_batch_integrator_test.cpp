// "device": "gpu"'s integrator (gpu/lattice_batch_integrator.h) with the
// CPU's threads in the device's place (gpu/host_executor.h), through the
// renderer's batched path (render/renderer.h, render/batch_integrator.h):
// the same images as the CPU's integrators. Emission–absorption to the bit
// (the same arithmetic per node, the same background and band sums, with
// jittered samples, a ground, two bands and the air path); the radiance
// cache to the records' float rounding of τ_sun, which the executor marches
// through the records rather than the medium. Anything but one grid cloud,
// or another method, is refused rather than rendered otherwise.
#include "obscura/gpu/lattice_batch_integrator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "medium/test_grids.h"
#include "obscura/core/check.h"
#include "obscura/gpu/host_executor.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/integrator_registry.h"
#include "obscura/render/renderer.h"
#include "support/input_error.h"

namespace obscura {
namespace {

Scene grid_scene(RenderMethod method) {
  Scene scene;
  const auto grid =
      testing::random_grid({14, 11, 9}, 3, 17, rotation_from_euler_deg({10, -20, 35}));
  scene.medium = std::make_shared<GridMedium>(grid);
  Sensor a;
  a.name = "a";
  a.camera = PinholeCamera({1, -12, 5}, {0, 0, 3}, {0, 0, 1}, 40.0, 24, 16);
  a.bands = {Band::flat("m", 3.2, 4.9), Band::flat("n", 4.1, 4.6)};
  Sensor b = a;
  b.name = "b";
  b.camera = PinholeCamera({-9, 6, 4}, {0, 1, 3}, {0, 0, 1}, 55.0, 17, 13);
  b.bands = {Band::flat("m", 3.2, 4.9)};
  scene.sensors = {a, b};
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{300, 0.8}, 2.4));
  scene.sky = Sky::blackbody(250, true);
  scene.atmosphere.enabled = true;
  scene.atmosphere.temperature_k = 288.0;
  scene.atmosphere.extinction_per_m = {{"*", 2e-3}};
  scene.settings.method = method;
  scene.settings.spectral_nodes_per_band = 3;
  scene.settings.samples_per_pixel = 4;  // jittered: the batched path draws the same positions
  scene.settings.threads = 2;
  scene.settings.radiance_cache.photons_per_node = 3000;
  if (method == RenderMethod::kRadianceCache) {
    scene.sun.enabled = true;
    scene.sun.elevation_deg = 40.0;
    scene.sun.azimuth_deg = 200.0;
  }
  return scene;
}

std::unique_ptr<LatticeBatchIntegrator> on_host(const Scene& scene, const FrameSpectra& spectra) {
  return std::make_unique<LatticeBatchIntegrator>(scene, spectra,
                                                  std::make_unique<HostExecutor>(2));
}

// Images a (batched) and b (the CPU's) of sensor s are the same to the bit,
// with the same samples and cells.
void expect_same_images(const SensorImage& a, const SensorImage& b, int s) {
  ASSERT_EQ(a.bands.size(), b.bands.size());
  for (std::size_t i = 0; i < a.bands.size(); ++i) {
    EXPECT_EQ(a.bands[i].radiance, b.bands[i].radiance) << "sensor " << s << " band " << i;
    EXPECT_EQ(a.bands[i].transmittance, b.bands[i].transmittance);
    EXPECT_EQ(a.bands[i].apparent_temperature, b.bands[i].apparent_temperature);
  }
  EXPECT_EQ(a.samples_per_pixel, b.samples_per_pixel);
  EXPECT_EQ(a.stats.rays, b.stats.rays);
  EXPECT_EQ(a.stats.segments, b.stats.segments);
}

TEST(LatticeBatchIntegrator, EmissionAbsorptionImagesEqualTheCpusBitForBit) {
  const Scene scene = grid_scene(RenderMethod::kEmissionAbsorption);
  const FrameSpectra spectra = frame_spectra(scene);
  const auto batched = on_host(scene, spectra);
  const auto cpu = make_integrator(scene, spectra);
  EXPECT_EQ(batched->method(), RenderMethod::kEmissionAbsorption);
  for (int s = 0; s < 2; ++s) {
    const SensorImage a = render_sensor(scene, s, *batched, spectra);
    const SensorImage b = render_sensor(scene, s, *cpu, spectra);
    expect_same_images(a, b, s);
    EXPECT_GT(a.stats.segments, 1000u);  // the rays cross the cloud
  }
  // One ray on its own (BatchIntegrator::band_radiance) is the CPU's too.
  const CameraRay ray = find_camera_ray_hit(scene, scene.sensors[0].camera.generate_ray(12, 8));
  double l0[kMaxSpectralNodes], t0[kMaxSpectralNodes], l1[kMaxSpectralNodes], t1[kMaxSpectralNodes];
  Rng rng(1, 0);
  const auto ws0 = batched->make_workspace(), ws1 = cpu->make_workspace();
  batched->band_radiance(ray, 0, 1, rng, *ws0, l0, t0);
  cpu->band_radiance(ray, 0, 1, rng, *ws1, l1, t1);
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(l0[j], l1[j]);
    EXPECT_EQ(t0[j], t1[j]);
  }
  EXPECT_LT(t0[0], 1.0);
  EXPECT_EQ(ws0->segments, ws1->segments);
}

// Samples only where the image has an edge (render/adaptive_samples.h): the
// batched path takes the same centres, refines the same pixels and gives
// the CPU's pixels to the bit, for a whole image and for a process's share
// of its rows.
TEST(LatticeBatchIntegrator, AdaptiveSamplesEqualTheCpusBitForBit) {
  Scene scene = grid_scene(RenderMethod::kEmissionAbsorption);
  scene.settings.adaptive_threshold = 0.05;
  const FrameSpectra spectra = frame_spectra(scene);
  const auto batched = on_host(scene, spectra);
  const auto cpu = make_integrator(scene, spectra);
  RenderOptions share;
  share.row_offset = 1;
  share.row_stride = 2;
  for (const RenderOptions& options : {RenderOptions{}, share})
    for (int s = 0; s < 2; ++s) {
      const SensorImage a = render_sensor(scene, s, *batched, spectra, options);
      const SensorImage b = render_sensor(scene, s, *cpu, spectra, options);
      expect_same_images(a, b, s);
      // Both kinds of pixel in the rendered rows.
      int refined = 0, centred = 0;
      for (std::size_t p = 0; p < a.samples_per_pixel.size(); ++p) {
        refined += a.samples_per_pixel[p] == 4;
        centred += a.samples_per_pixel[p] == 1;
      }
      EXPECT_GT(refined, 10) << "sensor " << s;
      EXPECT_GT(centred, 10) << "sensor " << s;
    }
}

TEST(LatticeBatchIntegrator, RadianceCacheImagesEqualTheCpusToTheRecordsRounding) {
  const Scene scene = grid_scene(RenderMethod::kRadianceCache);
  const FrameSpectra spectra = frame_spectra(scene);
  const auto batched = on_host(scene, spectra);
  const auto cpu = make_integrator(scene, spectra);
  ASSERT_TRUE(batched->cache());
  EXPECT_EQ(batched->preparation(0).photons, cpu->preparation(0).photons);
  for (int s = 0; s < 2; ++s) {
    const SensorImage a = render_sensor(scene, s, *batched, spectra);
    const SensorImage b = render_sensor(scene, s, *cpu, spectra);
    double worst = 0.0;
    for (std::size_t i = 0; i < a.bands.size(); ++i)
      for (std::size_t p = 0; p < a.bands[i].radiance.size(); ++p) {
        const double x = a.bands[i].radiance[p], y = b.bands[i].radiance[p];
        worst = std::max(worst, std::abs(x - y) / std::abs(y));
        EXPECT_EQ(a.bands[i].transmittance[p], b.bands[i].transmittance[p]);
      }
    EXPECT_LT(worst, 1e-5) << "sensor " << s;
    EXPECT_EQ(a.stats.segments, b.stats.segments);
  }
}

TEST(LatticeBatchIntegrator, RefusesWhatItDoesNotMarch) {
  Scene scene = grid_scene(RenderMethod::kPathTracer);
  FrameSpectra spectra = frame_spectra(scene);
  InputError e = testing::expect_input_error([&] { on_host(scene, spectra); });
  EXPECT_EQ(e.field(), "render/device");
  EXPECT_TRUE(testing::contains(e.detail(), "\"emission-absorption\" and \"radiance-cache\"") &&
              testing::contains(e.detail(), "path-tracer"))
      << e.what();
  for (const RenderMethod method :
       {RenderMethod::kEmissionAbsorption, RenderMethod::kRadianceCache}) {
    scene = grid_scene(method);
    scene.medium = std::make_shared<HomogeneousMedium>(
        BBox3({0, 0, 0}, {1, 1, 1}), std::vector<double>{4.0}, std::vector<double>{0.5},
        std::vector<double>{0.5}, std::vector<double>{0.0}, 300.0);
    spectra = frame_spectra(scene);
    e = testing::expect_input_error([&] { on_host(scene, spectra); });
    EXPECT_EQ(e.field(), "render/device");
    EXPECT_TRUE(testing::contains(e.detail(), "one voxel grid")) << e.what();
  }
  // The CPU's registry never stands in for the GPU.
  scene = grid_scene(RenderMethod::kEmissionAbsorption);
  scene.settings.device = RenderDevice::kGpu;
  EXPECT_THROW(make_integrator(scene, spectra), InternalError);
}

TEST(LatticeBatchIntegrator, WithoutACloudOnlyTheBackgroundIsLeft) {
  Scene scene = grid_scene(RenderMethod::kEmissionAbsorption);
  scene.medium.reset();
  const FrameSpectra spectra = frame_spectra(scene);
  const auto batched = on_host(scene, spectra);
  EXPECT_FALSE(batched->volume());
  const SensorImage a = render_sensor(scene, 0, *batched, spectra);
  const SensorImage b = render_sensor(scene, 0, *make_integrator(scene, spectra), spectra);
  for (std::size_t i = 0; i < a.bands.size(); ++i)
    EXPECT_EQ(a.bands[i].radiance, b.bands[i].radiance);
}

}  // namespace
}  // namespace obscura
