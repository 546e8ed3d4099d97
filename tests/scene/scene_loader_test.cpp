#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>

#include "obscura/core/error.h"
#include "obscura/render/integrator.h"
#include "obscura/scene/scene.h"

namespace obscura {
namespace {

nlohmann::json minimal_scene() {
  return nlohmann::json::parse(R"({
    "sensors": [{"name": "ir", "position": [0, -50, 5], "look_at": [0, 0, 3], "fov_deg": 30,
                 "width": 16, "height": 12, "bands": ["mwir", "8:12",
                 {"name": "custom", "response": [[3.0, 0.0], [4.0, 1.0], [5.0, 0.0]]}]}],
    "clouds": [{"type": "homogeneous", "min": [-5, -5, 0], "max": [5, 5, 6],
                "wavelengths_um": [4, 10], "sigma_a": [0.1, 0.2], "sigma_s": [0.05, 0.01],
                "g": [0.5, 0.3], "temperature": 300}],
    "surfaces": [{"type": "ground", "temperature": 290, "emissivity": 0.95},
                 {"type": "box", "min": [-1, 0, 0], "max": [1, 2, 2], "temperature": 330}],
    "sky": {"temperature": 250},
    "render": {"samples_per_pixel": 2, "seed": 7, "threads": 1}
  })");
}

// Loads `doc` and returns the error message ("" if it loaded).
std::string load_error(const nlohmann::json& doc) {
  try {
    parse_scene(doc, "scene.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.json");
    return e.what();
  }
  return "";
}

TEST(SceneLoader, LoadsAValidScene) {
  const Scene s = parse_scene(minimal_scene(), "dir/scene.json");
  ASSERT_EQ(s.sensors.size(), 1u);
  EXPECT_EQ(s.sensors[0].bands.size(), 3u);
  EXPECT_EQ(s.sensors[0].bands[1].name(), "8:12");
  EXPECT_EQ(s.sensors[0].camera.width(), 16);
  ASSERT_TRUE(s.medium);
  EXPECT_EQ(s.medium->wavelengths_um().size(), 2u);
  EXPECT_EQ(s.surfaces.size(), 2u);
  EXPECT_EQ(s.sky.temperature_k(), 250);
  EXPECT_EQ(s.settings.samples_per_pixel, 2);
  EXPECT_EQ(s.settings.seed, 7u);
}

TEST(SceneLoader, MissingFieldNamesItsPath) {
  auto doc = minimal_scene();
  doc["sensors"][0].erase("fov_deg");
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/sensors/0/fov_deg"), std::string::npos) << m;
  EXPECT_NE(m.find("missing"), std::string::npos) << m;
}

TEST(SceneLoader, WrongTypeNamesItsPath) {
  auto doc = minimal_scene();
  doc["surfaces"][0]["temperature"] = "hot";
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/surfaces/0/temperature"), std::string::npos) << m;
  EXPECT_NE(m.find("expected a number"), std::string::npos) << m;
}

TEST(SceneLoader, NegativeCoefficientIsRejected) {
  auto doc = minimal_scene();
  doc["clouds"][0]["sigma_a"][1] = -0.2;
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/clouds/0/sigma_a[1]"), std::string::npos) << m;
  EXPECT_NE(m.find(">= 0"), std::string::npos) << m;
}

TEST(SceneLoader, AsymmetryOutsideOpenIntervalIsRejected) {
  auto doc = minimal_scene();
  doc["clouds"][0]["g"][0] = 1.0;
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/clouds/0/g[0]"), std::string::npos) << m;
  EXPECT_NE(m.find("(-1, 1)"), std::string::npos) << m;
}

TEST(SceneLoader, UnknownKeyIsAnError) {
  auto doc = minimal_scene();
  doc["sensors"][0]["fov"] = 30;
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/sensors/0/fov"), std::string::npos) << m;
  EXPECT_NE(m.find("unknown field"), std::string::npos) << m;
  EXPECT_NE(m.find("fov_deg"), std::string::npos) << m;  // suggests what was meant
}

TEST(SceneLoader, BadBandAndRangesAreRejected) {
  auto doc = minimal_scene();
  doc["sensors"][0]["bands"][1] = "12:8";
  EXPECT_NE(load_error(doc).find("/sensors/0/bands/1"), std::string::npos);
  doc = minimal_scene();
  doc["sensors"][0]["width"] = 0;
  EXPECT_NE(load_error(doc).find("/sensors/0/width"), std::string::npos);
  doc = minimal_scene();
  doc["surfaces"][0]["emissivity"] = 1.5;
  EXPECT_NE(load_error(doc).find("/surfaces/0/emissivity"), std::string::npos);
  doc = minimal_scene();
  doc["render"]["method"] = "magic";
  EXPECT_NE(load_error(doc).find("/render/method"), std::string::npos);
  doc = minimal_scene();
  doc["sensors"] = nlohmann::json::array();
  EXPECT_NE(load_error(doc).find("/sensors"), std::string::npos);
}

TEST(SceneLoader, RegionsAreCheckedAgainstTheirSensor) {
  auto doc = minimal_scene();
  doc["regions"] = {{{"name", "target"}, {"sensor", "ir"}, {"pixels", {2, 3, 10, 9}}}};
  const Scene s = parse_scene(doc, "scene.json");
  ASSERT_EQ(s.regions.size(), 1u);
  EXPECT_EQ(s.regions[0].x1, 10);
  doc["regions"][0]["sensor"] = "tv";
  EXPECT_NE(load_error(doc).find("/regions/0/sensor"), std::string::npos);
  doc["regions"][0]["sensor"] = "ir";
  doc["regions"][0]["pixels"] = {2, 3, 17, 9};  // beyond the 16-pixel width
  EXPECT_NE(load_error(doc).find("/regions/0/pixels"), std::string::npos);
  doc["regions"][0]["pixels"] = {2, 3, 2, 9};  // empty
  EXPECT_NE(load_error(doc).find("/regions/0/pixels"), std::string::npos);
}

TEST(SceneLoader, SeveralStaticCloudsMustShareWavelengths) {
  auto doc = minimal_scene();
  doc["clouds"].push_back(doc["clouds"][0]);
  EXPECT_NO_THROW(parse_scene(doc, "scene.json"));
  doc["clouds"][1]["wavelengths_um"] = {4, 11};
  EXPECT_NE(load_error(doc).find("clouds/1"), std::string::npos);
}

TEST(SceneLoader, MissingManifestIsNamed) {
  auto doc = minimal_scene();
  doc["clouds"] = {{{"type", "animated"}, {"manifest", "nowhere/cloud.json"}}};
  const std::string m = load_error(doc);
  EXPECT_NE(m.find("/clouds/0/manifest"), std::string::npos) << m;
  EXPECT_NE(m.find("no such file"), std::string::npos) << m;
}

TEST(SceneLoader, SunNeedsThePathTracerAndSaneValues) {
  auto doc = minimal_scene();
  doc["sun"] = {{"azimuth_deg", 120}, {"elevation_deg", 35}};
  EXPECT_NE(load_error(doc).find("/sun"), std::string::npos);  // emission-absorption has no sun
  doc["render"]["method"] = "path-tracer";
  const Scene s = parse_scene(doc, "scene.json");
  EXPECT_TRUE(s.sun.enabled);
  EXPECT_NEAR(s.sun.direction().z, std::sin(35.0 * M_PI / 180.0), 1e-12);
  doc["sun"]["elevation_deg"] = -5;
  EXPECT_NE(load_error(doc).find("/sun/elevation_deg"), std::string::npos);
  doc["sun"]["elevation_deg"] = 35;
  doc["sun"]["total_irradiance"] = -1;
  EXPECT_NE(load_error(doc).find("/sun/total_irradiance"), std::string::npos);
}

TEST(SceneLoader, SunSpectrumFromATable) {
  auto doc = minimal_scene();
  doc["render"]["method"] = "path-tracer";
  doc["sun"] = {{"azimuth_deg", 120},
                {"elevation_deg", 35},
                {"irradiance_table",
                 {{"wavelengths_um", {0.4, 0.6, 1.0}}, {"irradiance_w_m2_um", {1500, 1800, 700}}}}};
  const Scene s = parse_scene(doc, "scene.json");
  EXPECT_NEAR(s.sun.irradiance(0.5), 1650.0, 1e-9);  // linear between rows
  EXPECT_NEAR(s.sun.irradiance(1.0), 700.0, 1e-9);
  EXPECT_EQ(s.sun.irradiance(1.2), 0.0);  // zero outside the table
  doc["sun"]["irradiance_table"]["irradiance_w_m2_um"][1] = -3;
  EXPECT_NE(load_error(doc).find("/sun/irradiance_table/irradiance_w_m2_um/1"), std::string::npos);
  doc["sun"]["irradiance_table"]["irradiance_w_m2_um"] = {1, 2};
  EXPECT_NE(load_error(doc).find("/sun/irradiance_table/irradiance_w_m2_um"), std::string::npos);
  doc["sun"]["irradiance_table"]["irradiance_w_m2_um"] = {1, 2, 3};
  doc["sun"]["irradiance_table"]["wavelengths_um"] = {0.4, 0.3, 1.0};
  EXPECT_NE(load_error(doc).find("/sun/irradiance_table/wavelengths_um/1"), std::string::npos);
  doc["sun"]["irradiance_table"]["wavelengths_um"] = {0.4, 0.6, 1.0};
  doc["sun"]["temperature"] = 5000;
  EXPECT_NE(load_error(doc).find("not both"), std::string::npos);
}

TEST(SceneLoader, SkyByTemperatureOrByZenithTable) {
  auto doc = minimal_scene();
  doc["sky"] = {{"temperature", 250}, {"below_horizon", false}};
  Scene s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.sky.radiance({0, 0, -1}, 10.0), 0.0);
  EXPECT_GT(s.sky.radiance({0, 0, 1}, 10.0), 0.0);
  doc["sky"] = nlohmann::json::parse(R"({"zenith_deg": [0, 60, 90], "wavelengths_um": [8, 12],
                                         "radiance": [[1, 2], [3, 4], [5, 6]]})");
  s = parse_scene(doc, "scene.json");
  EXPECT_NEAR(s.sky.radiance({0, 0, 1}, 10.0), 1.5, 1e-12);
  doc["sky"]["radiance"][2] = {5};
  EXPECT_NE(load_error(doc).find("/sky/radiance/2"), std::string::npos) << load_error(doc);
  doc["sky"]["radiance"][2] = {5, "x"};
  EXPECT_NE(load_error(doc).find("/sky/radiance/2/1"), std::string::npos) << load_error(doc);
  doc["sky"]["radiance"][2] = {5, 6};
  doc["sky"]["zenith_deg"] = {0, 60, 80};
  EXPECT_NE(load_error(doc).find("/sky/zenith_deg/2"), std::string::npos) << load_error(doc);
  doc["sky"]["temperature"] = 200;
  EXPECT_NE(load_error(doc).find("not both"), std::string::npos);
  doc["sky"] = nlohmann::json::object();
  EXPECT_NE(load_error(doc).find("/sky/temperature"), std::string::npos);
}

TEST(SceneLoader, TargetStandardErrorIsForThePathTracer) {
  auto doc = minimal_scene();
  doc["render"]["target_relative_stderr"] = 0.01;
  EXPECT_NE(load_error(doc).find("target_relative_stderr"), std::string::npos);
  doc["render"]["method"] = "path-tracer";
  EXPECT_NEAR(parse_scene(doc, "scene.json").settings.target_relative_stderr, 0.01, 1e-15);
  doc["render"]["target_relative_stderr"] = -1;
  EXPECT_NE(load_error(doc).find("/render/target_relative_stderr"), std::string::npos);
  doc["render"]["target_relative_stderr"] = 0.01;
  doc["render"]["max_samples_per_pixel"] = 0;
  EXPECT_NE(load_error(doc).find("/render/max_samples_per_pixel"), std::string::npos);
  doc["render"]["max_samples_per_pixel"] = 64;
  doc["render"]["samples_per_pixel"] = 0;
  EXPECT_NE(load_error(doc).find("/render/samples_per_pixel"), std::string::npos);  // zero samples
}

TEST(SceneLoader, PhotonMapSettings) {
  auto doc = minimal_scene();
  doc["render"]["photon_map"] = {{"photons", 1000}};
  EXPECT_NE(load_error(doc).find("/render/photon_map"),
            std::string::npos);  // not the photonmap method
  doc["render"]["method"] = "photonmap";
  doc["render"]["photon_map"] = {
      {"photons", 5000}, {"k", 30}, {"max_radius_m", 0.5}, {"step_m", 0.1}, {"form", "pure"}};
  const Scene s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.settings.photon_map.photons_per_node, 5000);
  EXPECT_EQ(s.settings.photon_map.k, 30);
  EXPECT_TRUE(s.settings.photon_map.pure);
  doc["render"]["photon_map"]["form"] = "mixed";
  EXPECT_NE(load_error(doc).find("/render/photon_map/form"), std::string::npos);
  doc["render"]["photon_map"]["form"] = "hybrid";
  doc["render"]["photon_map"]["k"] = 0;
  EXPECT_NE(load_error(doc).find("/render/photon_map/k"), std::string::npos);
  doc["render"]["photon_map"]["k"] = 30;
  doc["render"]["photon_map"]["photons"] = 0;
  EXPECT_NE(load_error(doc).find("/render/photon_map/photons"), std::string::npos);
}

// The radiance cache's photons per band: a count for every band, or one per
// band name with "*" for the others; a band no sensor renders is refused by
// its path, with the bands the sensors have.
TEST(SceneLoader, RadianceCachePhotonsPerBand) {
  auto doc = minimal_scene();
  doc["render"]["method"] = "radiance-cache";
  doc["render"]["radiance_cache"] = {{"photons", 5000}};
  Scene s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.settings.radiance_cache.photons_per_node, 5000);
  EXPECT_TRUE(s.settings.radiance_cache.photons_by_band.empty());
  doc["render"]["radiance_cache"]["photons"] = {{"*", 7000}, {"8:12", 300}, {"custom", 20}};
  s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.settings.radiance_cache.photons_per_node, 7000);
  EXPECT_EQ(s.settings.radiance_cache.photons_by_band,
            (std::map<std::string, long long>{{"8:12", 300}, {"custom", 20}}));
  doc["render"]["radiance_cache"]["photons"] = {{"8:12", 300}};  // the others: the default
  EXPECT_EQ(parse_scene(doc, "scene.json").settings.radiance_cache.photons_per_node,
            RadianceCacheSettings{}.photons_per_node);
  doc["render"]["radiance_cache"]["photons"] = {{"lwir", 300}};
  std::string m = load_error(doc);
  EXPECT_NE(m.find("/render/radiance_cache/photons/lwir"), std::string::npos) << m;
  EXPECT_NE(m.find("mwir, 8:12, custom"), std::string::npos) << m;
  doc["render"]["radiance_cache"]["photons"] = {{"8:12", 0}};
  m = load_error(doc);
  EXPECT_NE(m.find("/render/radiance_cache/photons/8:12"), std::string::npos) << m;
  doc["render"]["radiance_cache"]["photons"] = {{"8:12", "many"}};
  m = load_error(doc);
  EXPECT_NE(m.find("/render/radiance_cache/photons/8:12"), std::string::npos) << m;
  doc["render"]["radiance_cache"]["photons"] = {{"*", 0}};
  m = load_error(doc);
  EXPECT_NE(m.find("/render/radiance_cache/photons"), std::string::npos) << m;
}

// Spectral nodes per band, in the same forms; the renderer's spectra and the
// metrics' quadrature take each band's own count.
TEST(SceneLoader, SpectralNodesPerBand) {
  auto doc = minimal_scene();
  doc["render"]["spectral_nodes_per_band"] = 3;
  Scene s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.settings.spectral_nodes_per_band, 3);
  EXPECT_TRUE(s.settings.spectral_nodes_by_band.empty());
  doc["render"]["spectral_nodes_per_band"] = {{"*", 5}, {"8:12", 1}};
  s = parse_scene(doc, "scene.json");
  EXPECT_EQ(s.settings.spectral_nodes_per_band, 5);
  EXPECT_EQ(s.settings.spectral_nodes_by_band, (std::map<std::string, int>{{"8:12", 1}}));
  const FrameSpectra spectra = frame_spectra(s);
  for (std::size_t b = 0; b < s.sensors[0].bands.size(); ++b) {
    const Band& band = s.sensors[0].bands[b];
    const int nodes = band.name() == "8:12" ? 1 : 5;
    EXPECT_EQ(s.settings.spectral_nodes(band), nodes) << band.name();
    // Nodes per panel of the band's response (one panel for a flat band,
    // two for "custom"'s triangle).
    const std::size_t panels = band.name() == "custom" ? 2 : 1;
    EXPECT_EQ(spectra[0][b].size(), panels * nodes) << band.name();
  }
  doc["render"]["spectral_nodes_per_band"] = {{"lwir", 2}};
  std::string m = load_error(doc);
  EXPECT_NE(m.find("/render/spectral_nodes_per_band/lwir"), std::string::npos) << m;
  EXPECT_NE(m.find("mwir, 8:12, custom"), std::string::npos) << m;
  doc["render"]["spectral_nodes_per_band"] = {{"8:12", 65}};
  m = load_error(doc);
  EXPECT_NE(m.find("/render/spectral_nodes_per_band/8:12"), std::string::npos) << m;
  EXPECT_NE(m.find("[1, 64]"), std::string::npos) << m;
  doc["render"]["spectral_nodes_per_band"] = {{"*", 0}};
  m = load_error(doc);
  EXPECT_NE(m.find("/render/spectral_nodes_per_band"), std::string::npos) << m;
}

TEST(SceneLoader, SyntaxErrorNamesLineAndColumn) {
  const auto path = std::filesystem::temp_directory_path() / "obscura_syntax_error.json";
  {
    std::ofstream f(path);
    f << "{\n  \"sensors\": [\n    {\"name\": \"a\",,}\n  ]\n}\n";
  }
  try {
    load_scene(path);
    FAIL();
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(path.string()), std::string::npos) << m;
    EXPECT_NE(m.find("line 3"), std::string::npos) << m;
  }
  std::filesystem::remove(path);
}

TEST(SceneLoader, UnreadableFileIsAnError) {
  try {
    load_scene("/nonexistent/scene.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scene.json"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos);
  }
}

}  // namespace
}  // namespace obscura

namespace obscura {
namespace {

TEST(SceneLoader, AtmosphereMetricsTargetAndEmissivityTable) {
  auto doc = minimal_scene();
  doc["atmosphere"] = {{"temperature", 285.0}, {"extinction_per_km", {{"mwir", 0.3}, {"*", 0.2}}}};
  doc["metrics"] = {
      {"transmittance_threshold", 0.02}, {"screened_fraction", 0.8}, {"background_margin_px", 5}};
  doc["surfaces"][1]["target"] = true;
  doc["surfaces"][0]["emissivity"] = nlohmann::json::parse("[[4, 0.9], [10, 0.95]]");
  const Scene s = parse_scene(doc, "scene.json");
  EXPECT_TRUE(s.atmosphere.enabled);
  EXPECT_DOUBLE_EQ(s.atmosphere.temperature_k, 285.0);
  EXPECT_DOUBLE_EQ(s.atmosphere.extinction_for(Band::preset("mwir")), 0.3e-3);
  EXPECT_DOUBLE_EQ(s.atmosphere.extinction_for(Band::preset("lwir")), 0.2e-3);
  EXPECT_DOUBLE_EQ(s.metrics.transmittance_threshold, 0.02);
  EXPECT_DOUBLE_EQ(s.metrics.screened_fraction, 0.8);
  EXPECT_EQ(s.metrics.background_margin_px, 5);
  EXPECT_FALSE(s.surfaces[0]->is_target());
  EXPECT_TRUE(s.surfaces[1]->is_target());
  EXPECT_DOUBLE_EQ(s.surfaces[0]->material().emissivity_at(7.0), 0.925);
  // Without "atmosphere" there is none.
  EXPECT_FALSE(parse_scene(minimal_scene(), "scene.json").atmosphere.enabled);
}

TEST(SceneLoader, BadAtmosphereMetricsAndEmissivityTablesAreRejected) {
  auto with = [](const char* key, nlohmann::json value) {
    auto doc = minimal_scene();
    doc[key] = std::move(value);
    return load_error(doc);
  };
  // A band without a coefficient, naming the band and the sensor.
  std::string m =
      with("atmosphere", {{"temperature", 285.0}, {"extinction_per_km", {{"mwir", 0.3}}}});
  EXPECT_NE(m.find("/atmosphere/extinction_per_km"), std::string::npos) << m;
  EXPECT_NE(m.find("'8:12'"), std::string::npos) << m;
  m = with("atmosphere", {{"temperature", 285.0}, {"extinction_per_km", -1.0}});
  EXPECT_NE(m.find("/atmosphere/extinction_per_km"), std::string::npos) << m;
  m = with("atmosphere", {{"extinction_per_km", 0.1}});
  EXPECT_NE(m.find("/atmosphere/temperature"), std::string::npos) << m;
  m = with("atmosphere", {{"temperature", 285.0}, {"extinction_per_km", 0.1}, {"visibility", 3}});
  EXPECT_NE(m.find("/atmosphere/visibility"), std::string::npos) << m;
  m = with("metrics", {{"transmittance_threshold", 1.5}});
  EXPECT_NE(m.find("/metrics/transmittance_threshold"), std::string::npos) << m;
  m = with("metrics", {{"screened_fraction", 0.0}});
  EXPECT_NE(m.find("/metrics/screened_fraction"), std::string::npos) << m;

  auto table = [](const char* json) {
    auto doc = minimal_scene();
    doc["surfaces"][0]["emissivity"] = nlohmann::json::parse(json);
    return load_error(doc);
  };
  EXPECT_NE(table("[[4, 0.9], [3, 0.95]]").find("/surfaces/0/emissivity/1"), std::string::npos);
  EXPECT_NE(table("[[4, 1.2]]").find("/surfaces/0/emissivity/0"), std::string::npos);
  EXPECT_NE(table("[[4]]").find("/surfaces/0/emissivity/0"), std::string::npos);
  EXPECT_NE(table("[]").find("/surfaces/0/emissivity"), std::string::npos);
  auto doc = minimal_scene();
  doc["surfaces"][0]["target"] = "yes";
  EXPECT_NE(load_error(doc).find("/surfaces/0/target"), std::string::npos);
}

}  // namespace
TEST(SceneLoader, OutputsNameTheOptionalFormats) {
  EXPECT_TRUE(parse_scene(minimal_scene(), "scene.json").outputs.empty());
  auto doc = minimal_scene();
  doc["outputs"] = {"netcdf", "netcdf"};  // named twice: written once
  EXPECT_EQ(parse_scene(doc, "scene.json").outputs,
            std::vector<OutputFormat>{OutputFormat::kNetcdf});
  doc["outputs"] = nlohmann::json::array();
  EXPECT_TRUE(parse_scene(doc, "scene.json").outputs.empty());
}

TEST(SceneLoader, BadOutputsNameTheirPath) {
  auto doc = minimal_scene();
  doc["outputs"] = {"netcdf", "tiff"};
  std::string m = load_error(doc);
  EXPECT_NE(
      m.find("/outputs/1: unknown output format 'tiff' (expected: netcdf, envi; EXR, PNG, CSV "
             "and JSON files are always written)"),
      std::string::npos)
      << m;
  doc["outputs"] = {1};
  m = load_error(doc);
  EXPECT_NE(m.find("/outputs/0: must be a format name"), std::string::npos) << m;
  doc["outputs"] = "netcdf";
  m = load_error(doc);
  EXPECT_NE(m.find("/outputs: expected an array"), std::string::npos) << m;
}

}  // namespace obscura
