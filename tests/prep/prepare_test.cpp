// The preparation phase: σ = c·k per voxel, mass carried into the keyframes,
// the suggested lifecycle worked by hand, CFD input, and bad input that names
// its field and leaves nothing behind.
#include "obscura/prep/prepare.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/io/cloud_manifest.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/medium/voxelise.h"
#include "obscura/optics/material.h"
#include "obscura/prep/suggested_lifecycle.h"
#include "obscura/render/renderer.h"
#include "obscura/scene/scene.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

const std::filesystem::path kExample =
    std::filesystem::path(OBSCURA_SOURCE_DIR) / "examples" / "smoke-screen" / "prepare.json";

ConcentrationFrame small_frame(double time_s, float scale) {
  ConcentrationFrame f;
  f.time_s = time_s;
  ScalarGrid& c = f.concentration_g_m3;
  c.dims = {4, 3, 2};
  c.placement.origin_m = {-2, -1, 0};
  c.placement.voxel_size_m = 0.5;
  for (std::size_t v = 0; v < c.dims.count(); ++v)
    c.values.push_back(scale * static_cast<float>(v));
  return f;
}

TEST(Voxelise, CoefficientsAreConcentrationTimesMassCoefficients) {
  const SpeciesOptics optics{"test", {0.5, 10.0}, {0.1, 0.3}, {2.0, 0.05}, {0.7, 0.2}};
  const VoxelGrid g = voxelise(small_frame(0, 0.5f), optics, 290.0, "test");
  for (std::size_t v = 0; v < g.dims().count(); ++v) {
    const double c = 0.5 * v;
    EXPECT_FLOAT_EQ(g.sigma_a(0)[v], static_cast<float>(c * 0.1));
    EXPECT_FLOAT_EQ(g.sigma_s(0)[v], static_cast<float>(c * 2.0));
    EXPECT_FLOAT_EQ(g.sigma_a(1)[v], static_cast<float>(c * 0.3));
    EXPECT_FLOAT_EQ(g.g(1)[v], 0.2f);
    EXPECT_FLOAT_EQ(g.temperature()[v], 290.0f);
  }
  EXPECT_EQ(g.placement().voxel_size_m, 0.5);
  SpeciesOptics bad = optics;
  bad.asymmetry[1] = 1.0;
  EXPECT_THROW(voxelise(small_frame(0, 1), bad, 290.0, "test"), InputError);
  bad = optics;
  bad.mass_scattering_m2_g.pop_back();
  EXPECT_THROW(voxelise(small_frame(0, 1), bad, 290.0, "test"), InputError);
}

TEST(SuggestedLifecycle, WorkedByHand) {
  std::vector<double> times;
  for (int i = 0; i <= 10; ++i) times.push_back(i);
  // Burning until 2.7 s: initialisation K0..K2, loop K2..K6 (half of the 8
  // keyframes after K2), wrap over one interval, extinction K7..K10.
  const LifecycleSpec s = suggest_lifecycle(times, 2.7);
  EXPECT_EQ(s.init_end, 2);
  EXPECT_EQ(s.loop_start, 2);
  EXPECT_EQ(s.loop_end, 6);
  EXPECT_DOUBLE_EQ(s.loop_wrap_s, 1.0);
  EXPECT_EQ(s.extinction_start, 7);
  // Two keyframes: the least a lifecycle can be.
  const LifecycleSpec two = suggest_lifecycle({0, 5}, 100.0);
  EXPECT_EQ(two.init_end, 0);
  EXPECT_EQ(two.extinction_start, 1);
  EXPECT_NO_THROW(Lifecycle({0, 5}, two));
  EXPECT_THROW(suggest_lifecycle({0}, std::nullopt), InputError);
}

class PrepareTest : public testing::TempDirTest {
 protected:
  nlohmann::json example() const {
    std::ifstream in(kExample);
    return nlohmann::json::parse(in);
  }
  std::filesystem::path write(const nlohmann::json& doc,
                              const std::string& name = "config.json") const {
    std::ofstream(dir_ / name) << doc.dump(2);
    return dir_ / name;
  }
};

TEST_F(PrepareTest, TheEightGrenadeExampleCarriesItsMassIntoTheKeyframes) {
  const PrepareReport r = prepare_cloud(kExample, dir_ / "cloud");
  ASSERT_EQ(r.keyframes.size(), 31u);
  EXPECT_NEAR(r.released_mass_g, 8 * 200 * 4.5, 1e-9);
  const CloudManifest m = read_cloud_manifest(r.manifest);
  EXPECT_EQ(m.keyframes.size(), 31u);
  // At 10 s every grenade has burnt out and the cloud is inside the grid: the
  // scattering coefficient at 0.55 µm summed over the voxels, divided by the
  // material's k_sca, is the released mass (≤ 1 % lost beyond the grid).
  const CloudKeyframe k = read_cloud_keyframe(r.keyframes[10]);
  const MaterialOptics o = optics_at(load_material_by_name("phosphorus_smoke"), 0.55, 0.6);
  double sum = 0;
  for (std::size_t v = 0; v < k.grid->dims().count(); ++v) sum += k.grid->sigma_s(0)[v];
  const double h = k.grid->placement().voxel_size_m;
  EXPECT_NEAR(sum * h * h * h / o.mass_scattering_m2_g / r.released_mass_g, 1.0, 0.01);
  // The fresh smoke is warmer than the air.
  float t_max = 0;
  const CloudKeyframe k1 = read_cloud_keyframe(r.keyframes[1]);
  for (std::size_t v = 0; v < k1.grid->dims().count(); ++v)
    t_max = std::max(t_max, k1.grid->temperature()[v]);
  EXPECT_GT(t_max, 300.0f);
}

// The compact species form (output_form "species") stores concentration and
// temperature; read back, its keyframes are the spectral form's bit for bit,
// and so is a render of the scene through them.
TEST_F(PrepareTest, SpeciesFormReadsAndRendersExactlyAsTheSpectralForm) {
  nlohmann::json doc = example();
  doc["times_s"] = {{"start", 0}, {"end", 10}, {"step", 2}};
  const PrepareReport spectral = prepare_cloud(write(doc, "spectral.json"), dir_ / "spectral");
  doc["output_form"] = "species";
  const PrepareReport species = prepare_cloud(write(doc, "species.json"), dir_ / "species");
  EXPECT_EQ(spectral.output_form, "spectral");
  EXPECT_EQ(species.output_form, "species");
  ASSERT_EQ(species.keyframes.size(), 6u);
  ASSERT_EQ(spectral.keyframes.size(), 6u);
  for (std::size_t i = 0; i < species.keyframes.size(); ++i) {
    const KeyframeInfo info = inspect_cloud_keyframe(species.keyframes[i]);
    EXPECT_EQ(info.form, "species");
    ASSERT_EQ(info.species.size(), 1u);
    EXPECT_EQ(info.species[0].optics.name, "phosphorus_smoke");
    EXPECT_EQ(inspect_cloud_keyframe(spectral.keyframes[i]).form, "spectral");
    const CloudKeyframe a = read_cloud_keyframe(spectral.keyframes[i]);
    const CloudKeyframe b = read_cloud_keyframe(species.keyframes[i]);
    EXPECT_EQ(a.time_s, b.time_s);
    ASSERT_EQ(a.grid->dims(), b.grid->dims());
    EXPECT_EQ(a.grid->wavelengths_um(), b.grid->wavelengths_um());
    EXPECT_EQ(a.grid->placement().origin_m, b.grid->placement().origin_m);
    EXPECT_EQ(a.grid->placement().voxel_size_m, b.grid->placement().voxel_size_m);
    for (int c = 0; c < a.grid->channel_count(); ++c)
      EXPECT_EQ(std::memcmp(a.grid->channel(c), b.grid->channel(c),
                            a.grid->dims().count() * sizeof(float)),
                0)
          << "keyframe " << i << " " << a.grid->channel_name(c);
  }
  // Two floats per voxel instead of 13: the files are smaller.
  EXPECT_LT(species.bytes_written, spectral.bytes_written);

  // The example's scene through either folder, small and without its region.
  std::ifstream in(kExample.parent_path() / "scene.json");
  nlohmann::json scene_doc = nlohmann::json::parse(in);
  scene_doc.erase("regions");
  auto& sensor = scene_doc["sensors"][0];
  sensor["width"] = 48;
  sensor["height"] = 24;
  sensor["bands"] = {"visible", "lwir"};
  std::vector<SensorImage> images;
  for (const std::string folder : {"spectral", "species"}) {
    scene_doc["clouds"][0]["manifest"] = folder + "/cloud.json";
    Scene scene = parse_scene(scene_doc, dir_ / "scene.json");
    for (const double t : {1.0, 7.0}) {
      stage_scene(scene, t);
      scene.settings.threads = 2;
      images.push_back(render_sensor(scene, scene.sensors[0]));
    }
  }
  ASSERT_EQ(images.size(), 4u);
  for (std::size_t k = 0; k < 2; ++k) {
    const SensorImage &a = images[k], &b = images[k + 2];
    ASSERT_EQ(a.bands.size(), b.bands.size());
    for (std::size_t band = 0; band < a.bands.size(); ++band) {
      EXPECT_EQ(a.bands[band].radiance, b.bands[band].radiance) << k << " " << band;
      EXPECT_EQ(a.bands[band].transmittance, b.bands[band].transmittance) << k << " " << band;
    }
    // The screen is in view: not a comparison of two empty skies.
    const auto& t = a.bands[0].transmittance;
    EXPECT_LT(*std::min_element(t.begin(), t.end()), 0.01f) << k;
  }
}

TEST_F(PrepareTest, CfdFramesFromVtk) {
  write_vtk_frame(dir_ / "f0.vtk", small_frame(0, 1.0f), VtkEncoding::kBinary);
  write_vtk_frame(dir_ / "f1.vtk", small_frame(4, 2.0f), VtkEncoding::kAscii);
  const nlohmann::json doc = {
      {"source", "vtk"},
      {"vtk",
       {{"frames", {{{"time_s", 0}, {"file", "f0.vtk"}}, {{"time_s", 4}, {"file", "f1.vtk"}}}},
        {"ambient_temperature_k", 280}}},
      {"material", "soot"},
      {"wavelengths_um", {0.55, 10.0}}};
  const PrepareReport r = prepare_cloud(write(doc), dir_ / "out");
  ASSERT_EQ(r.keyframes.size(), 2u);
  const CloudKeyframe k = read_cloud_keyframe(r.keyframes[1]);
  const MaterialOptics o = optics_at(load_material_by_name("soot"), 0.55);
  EXPECT_NEAR(k.grid->sigma_a(0)[5], 2.0 * 5 * o.mass_absorption_m2_g, 1e-5);
  EXPECT_FLOAT_EQ(k.grid->temperature()[5], 280.0f);
  EXPECT_DOUBLE_EQ(k.time_s, 4.0);
}

TEST_F(PrepareTest, BadInputNamesItsFieldAndLeavesNothingBehind) {
  auto error_of = [&](const nlohmann::json& doc) {
    try {
      prepare_cloud(write(doc), dir_ / "out");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  nlohmann::json doc = example();
  doc["material"] = "unobtainium";
  EXPECT_NE(error_of(doc).find("/material"), std::string::npos);
  doc = example();
  doc["dispersion"]["devices"][2]["agent_mass_g"] = -5;
  EXPECT_NE(error_of(doc).find("/dispersion/devices/2/agent_mass_g"), std::string::npos)
      << error_of(doc);
  doc = example();
  doc["lifecycle"] = {{"init_end", 0},
                      {"loop_start", 0},
                      {"loop_end", 40},
                      {"loop_wrap", 1},
                      {"extinction_start", 41}};
  EXPECT_NE(error_of(doc).find("lifecycle"), std::string::npos) << error_of(doc);
  doc = example();
  doc["wavelengths_um"] = {10.0, 4.0};
  EXPECT_NE(error_of(doc).find("/wavelengths_um/1"), std::string::npos);
  doc = example();
  doc["output_form"] = "compact";
  EXPECT_NE(error_of(doc).find("/output_form"), std::string::npos) << error_of(doc);
  doc = example();
  doc["colour"] = "grey";
  EXPECT_NE(error_of(doc).find("/colour"), std::string::npos);
  // No output, no temporary folder.
  for (const auto& e : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(e.path().extension(), ".json") << e.path();
  // An existing, non-empty output folder is refused.
  std::filesystem::create_directories(dir_ / "full");
  std::ofstream(dir_ / "full" / "x") << "x";
  EXPECT_THROW(prepare_cloud(kExample, dir_ / "full"), InputError);
}

// The whole configuration is checked before the model runs: a misspelt key or
// a huge lifecycle index is reported before the first progress line, not
// after the dispersion run.
TEST_F(PrepareTest, TheWholeConfigurationIsCheckedBeforeAnythingIsComputed) {
  std::vector<std::string> progress;
  PrepareOptions options;
  options.progress = [&](const std::string& line) { progress.push_back(line); };
  nlohmann::json doc = example();
  doc["colour"] = "grey";
  EXPECT_THROW(prepare_cloud(write(doc), dir_ / "out", options), InputError);
  EXPECT_TRUE(progress.empty()) << progress.front();
  doc = example();
  doc["lifecycle"] = {{"init_end", 0},
                      {"loop_start", 4294967297LL},  // 2^32 + 1: wraps to 1 in an int
                      {"loop_end", 1},
                      {"loop_wrap", 1},
                      {"extinction_start", 2}};
  try {
    prepare_cloud(write(doc), dir_ / "out", options);
    ADD_FAILURE() << "a lifecycle index beyond an int was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "/lifecycle/loop_start") << e.what();
  }
  EXPECT_TRUE(progress.empty()) << progress.front();
}

TEST_F(PrepareTest, CommandLine) {
  const auto r = testing::run_cli(
      "prepare " + kExample.string() + " -o " + (dir_ / "c").string() + " --json -q", dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["keyframes"].get<int>(), 31);
  EXPECT_TRUE(j["lifecycle"]["suggested"].get<bool>());
  EXPECT_TRUE(std::filesystem::exists(dir_ / "c" / "cloud.json"));
  const auto bad = testing::run_cli(
      "prepare " + (dir_ / "missing.json").string() + " -o " + (dir_ / "d").string(), dir_);
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.err.find("missing.json"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace obscura
