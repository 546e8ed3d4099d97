// The render settings: parsed and range-checked in one place
// (scene/render_settings.h), every method's own settings reachable from a
// scene file, and every method name known to the registry of integrators.
#include "obscura/scene/render_settings.h"

#include <gtest/gtest.h>

#include "obscura/io/json_reader.h"
#include "obscura/render/integrator_registry.h"
#include "support/input_error.h"

namespace obscura {
namespace {

RenderSettings parse(const nlohmann::json& render) {
  JsonObject o(render, "scene.json", "/render");
  return parse_render_settings(o);
}

InputError parse_error(const nlohmann::json& render) {
  return testing::expect_input_error([&] { parse(render); });
}

TEST(RenderSettings, EveryMethodHasANameThatParsesBackAndAnIntegrator) {
  for (const RenderMethod m : kRenderMethods) {
    EXPECT_EQ(parse_render_method(render_method_name(m)), m);
    EXPECT_NO_THROW(integrator_factory(m)) << render_method_name(m);
  }
  EXPECT_FALSE(parse_render_method("magic"));
  EXPECT_EQ(render_method_names(), "emission-absorption, path-tracer, photonmap, radiance-cache");
  EXPECT_FALSE(method_scatters(RenderMethod::kEmissionAbsorption));
  EXPECT_TRUE(method_is_monte_carlo(RenderMethod::kPhotonMap));
}

TEST(RenderSettings, PathTracerSettingsComeFromTheSceneFile) {
  const RenderSettings s =
      parse({{"method", "path-tracer"},
             {"camera_sees_sun", false},
             {"path_tracer",
              {{"russian_roulette_depth", 7}, {"max_depth", 500}, {"sky_next_event", "always"}}}});
  EXPECT_EQ(s.method, RenderMethod::kPathTracer);
  EXPECT_FALSE(s.camera_sees_sun);
  EXPECT_EQ(s.path_tracer.russian_roulette_depth, 7);
  EXPECT_EQ(s.path_tracer.max_depth, 500);
  EXPECT_EQ(s.path_tracer.sky_next_event, PathTracerSettings::SkySampling::kAlways);
}

TEST(RenderSettings, ErrorsNameTheJsonPath) {
  InputError e =
      parse_error({{"method", "path-tracer"}, {"path_tracer", {{"sky_next_event", "often"}}}});
  EXPECT_EQ(e.field(), "/render/path_tracer/sky_next_event");
  e = parse_error({{"method", "path-tracer"}, {"path_tracer", {{"russian_roulette_depth", 0}}}});
  EXPECT_EQ(e.field(), "/render/path_tracer/russian_roulette_depth");
  e = parse_error({{"method", "path-tracer"}, {"path_tracer", {{"depth", 3}}}});
  EXPECT_TRUE(testing::contains(e.what(), "depth")) << e.what();  // unknown key
  e = parse_error({{"method", "photonmap"}, {"path_tracer", nlohmann::json::object()}});
  EXPECT_EQ(e.field(), "/render/path_tracer");  // another method's settings
  e = parse_error({{"method", "photonmap"}, {"photon_map", {{"k", 99999999999LL}}}});
  EXPECT_EQ(e.field(), "/render/photon_map/k");  // saturated, not wrapped
  EXPECT_TRUE(testing::contains(e.detail(), "[1, 4096]")) << e.what();
  e = parse_error({{"target_relative_stderr", 0.01}});  // emission–absorption
  EXPECT_EQ(e.field(), "/render/target_relative_stderr");
  e = parse_error({{"samples_per_pixel", -5}});
  EXPECT_EQ(e.field(), "/render/samples_per_pixel");
  e = parse_error({{"method", "magic"}});
  EXPECT_TRUE(testing::contains(e.detail(), render_method_names())) << e.what();
}

// "device": "gpu" is range-checked with the method it renders (docs/gpu.md):
// the GPU marches emission–absorption and the radiance cache with the cell
// quadrature, and nothing else slips through to the CPU.
TEST(RenderSettings, TheGpuTakesTheLatticeMethodsOnly) {
  EXPECT_EQ(parse(nlohmann::json::object()).device, RenderDevice::kCpu);
  EXPECT_EQ(parse({{"device", "gpu"}}).device, RenderDevice::kGpu);
  EXPECT_EQ(parse({{"device", "gpu"}, {"method", "radiance-cache"}}).device, RenderDevice::kGpu);
  EXPECT_EQ(parse({{"device", "cpu"}, {"method", "photonmap"}}).device, RenderDevice::kCpu);
  EXPECT_EQ(parse_render_device(render_device_name(RenderDevice::kGpu)), RenderDevice::kGpu);
  EXPECT_FALSE(parse_render_device("tpu"));
  InputError e = parse_error({{"device", "tpu"}});
  EXPECT_EQ(e.field(), "/render/device");
  for (const char* method : {"path-tracer", "photonmap"}) {
    e = parse_error({{"device", "gpu"}, {"method", method}});
    EXPECT_EQ(e.field(), "/render/device");
    EXPECT_TRUE(testing::contains(e.detail(), "\"emission-absorption\" and \"radiance-cache\"") &&
                testing::contains(e.detail(), method))
        << e.what();
  }
  e = parse_error({{"device", "gpu"}, {"emission_quadrature", "adaptive"}});
  EXPECT_EQ(e.field(), "/render/device");
  EXPECT_TRUE(testing::contains(e.detail(), "\"cell\"")) << e.what();
  // The device's kernels hold spherical harmonics to degree 3, the CPU's to 6.
  const nlohmann::json degree_4 = {{"sh_degree", 4}};
  EXPECT_EQ(
      parse({{"method", "radiance-cache"}, {"radiance_cache", degree_4}}).radiance_cache.sh_degree,
      4);
  e = parse_error({{"device", "gpu"}, {"method", "radiance-cache"}, {"radiance_cache", degree_4}});
  EXPECT_EQ(e.field(), "/render/radiance_cache/sh_degree");
  EXPECT_TRUE(testing::contains(e.detail(), "\"cpu\"")) << e.what();
  e = parse_error({{"method", "radiance-cache"}, {"radiance_cache", {{"sh_degree", 7}}}});
  EXPECT_EQ(e.field(), "/render/radiance_cache/sh_degree");
  EXPECT_TRUE(testing::contains(e.detail(), "[1, 6]")) << e.what();
}

// The adaptive threshold refines a deterministic method's pixels to
// samples_per_pixel samples (render/renderer.h): refused where it would do
// nothing or has no meaning, by name, with what to change.
TEST(RenderSettings, TheAdaptiveThresholdIsForDeterministicMethodsWithSeveralSamples) {
  EXPECT_EQ(parse(nlohmann::json::object()).adaptive_threshold, 0.0);
  EXPECT_EQ(parse({{"samples_per_pixel", 4}, {"adaptive_threshold", 0.02}}).adaptive_threshold,
            0.02);
  EXPECT_EQ(
      parse({{"method", "radiance-cache"}, {"samples_per_pixel", 4}, {"adaptive_threshold", 0.05}})
          .adaptive_threshold,
      0.05);
  InputError e = parse_error({{"samples_per_pixel", 4}, {"adaptive_threshold", 1.5}});
  EXPECT_EQ(e.field(), "/render/adaptive_threshold");
  EXPECT_TRUE(testing::contains(e.detail(), "[0, 1)")) << e.what();
  e = parse_error({{"adaptive_threshold", 0.02}});  // one sample per pixel
  EXPECT_EQ(e.field(), "/render/adaptive_threshold");
  EXPECT_TRUE(testing::contains(e.detail(), "samples_per_pixel")) << e.what();
  for (const char* method : {"path-tracer", "photonmap"}) {
    e = parse_error({{"method", method}, {"samples_per_pixel", 4}, {"adaptive_threshold", 0.02}});
    EXPECT_EQ(e.field(), "/render/adaptive_threshold");
    EXPECT_TRUE(testing::contains(e.detail(), "target_relative_stderr") &&
                testing::contains(e.detail(), method))
        << e.what();
  }
  EXPECT_EQ(
      parse({{"device", "gpu"}, {"samples_per_pixel", 4}, {"adaptive_threshold", 0.02}}).device,
      RenderDevice::kGpu);
}

// The radiance cache's forward peak towards narrow sensors is on unless
// the scene turns it off; a value that is not a boolean is refused by name.
TEST(RenderSettings, TheSensorPeaksAreOnByDefault) {
  EXPECT_TRUE(parse(nlohmann::json::object()).radiance_cache.sensor_peaks);
  const nlohmann::json off = {{"method", "radiance-cache"},
                              {"radiance_cache", {{"sensor_peaks", false}}}};
  EXPECT_FALSE(parse(off).radiance_cache.sensor_peaks);
  const InputError e =
      parse_error({{"method", "radiance-cache"}, {"radiance_cache", {{"sensor_peaks", "yes"}}}});
  EXPECT_EQ(e.field(), "/render/radiance_cache/sensor_peaks");
}

// The command line names its own options: the same checks, another namer.
TEST(RenderSettings, OneCheckForTheSceneFileAndTheCommandLine) {
  RenderSettings s;
  s.method = RenderMethod::kPhotonMap;
  s.photon_map.step_m = 0.0;
  const InputError e = testing::expect_input_error([&] {
    check_render_settings(s, [](std::string_view key, std::string_view what) {
      return InputError("", key == "photon_map/step_m" ? "--step" : std::string(key),
                        std::string(what));
    });
  });
  EXPECT_EQ(e.field(), "--step");
  EXPECT_NO_THROW(
      check_render_settings(RenderSettings{}, [](auto, auto) { return InputError("", "", ""); }));
}

}  // namespace
}  // namespace obscura
