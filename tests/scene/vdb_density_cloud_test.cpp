// Clouds from other tools' VDB files in a scene (scene/vdb_density_cloud.h):
// the staged medium is density × the material's mass coefficients, the
// temperature mapping, numbered sequences as keyframes at a frame rate, the
// refusals, and a render equal to that of the same cloud written as an
// obscura keyframe.
#include "obscura/scene/vdb_density_cloud.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <tuple>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/optics/material.h"
#include "obscura/optics/material_species_optics.h"
#include "obscura/sequence/sequence_runner.h"
#include "support/input_error.h"
#include "support/render_helpers.h"
#include "support/temp_dir_test.h"
#include "support/tool_vdb.h"

namespace obscura {
namespace {

using openvdb::Coord;
using openvdb::CoordBBox;
using testing::contains;
using testing::expect_input_error;
using testing::tool_grid;
using testing::tool_transform;
using testing::write_tool_vdb;

const std::vector<double> kWavelengths = {0.55, 4.0, 10.0};
const CoordBBox kBox(Coord(-6, 4, 0), Coord(5, 11, 9));  // 12 × 8 × 10 voxels of 0.5 m

// A smoke ball, densest in the middle; `scale` varies it between frames.
float smoke(int i, int j, int k, float scale = 1.0f) {
  const float r2 =
      static_cast<float>((i + 0.5) * (i + 0.5) + (j - 7.5) * (j - 7.5) + (k - 4.5) * (k - 4.5));
  return scale * 1.6f / (1.0f + 0.08f * r2);
}
float heat(int i, int j, int k) { return 0.002f * static_cast<float>(i + j + k + 20); }

class VdbDensityCloud : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    write_frame("explosion.vdb", 1.0f);
  }
  // density, temperature (Houdini's: 0 in ambient air) and flame grids.
  void write_frame(const std::string& name, float scale) {
    const auto xf = tool_transform(0.5, {0.25, -30.0, 0.25});
    write_tool_vdb(dir_ / name,
                   {tool_grid("density", xf, kBox,
                              [scale](int i, int j, int k) { return smoke(i, j, k, scale); }),
                    tool_grid("temperature", xf, kBox, heat),
                    tool_grid("flame", xf, kBox, [](int, int, int) { return 0.25f; })});
  }
  static nlohmann::json cloud(const std::string& file = "explosion.vdb") {
    return {{"type", "vdb-density"},    {"file", file},
            {"material", "soot"},       {"wavelengths_um", kWavelengths},
            {"density_scale", 0.75},    {"temperature_grid", "temperature"},
            {"temperature_scale", 900}, {"temperature_offset", 290}};
  }
  static nlohmann::json scene_with(const nlohmann::json& c) {
    return {{"sensors",
             {{{"name", "ir"},
               {"position", {0, -60, 3}},
               {"look_at", {0, -25, 2.5}},
               {"fov_deg", 14},
               {"width", 24},
               {"height", 16},
               {"bands", {"visible", "mwir", "lwir"}}}}},
            {"clouds", {c}},
            {"surfaces", {{{"type", "ground"}, {"temperature", 288}, {"emissivity", 0.95}}}},
            {"sky", {{"temperature", 250}}},
            {"render", {{"method", "emission-absorption"}}}};
  }
  Scene load(const nlohmann::json& c) { return parse_scene(scene_with(c), dir_ / "scene.json"); }
  std::string error_of(const nlohmann::json& c) {
    return expect_input_error([&] { load(c); }).what();
  }
  static const VoxelGrid& grid_of(const Scene& s) {
    return dynamic_cast<const GridMedium&>(*s.static_clouds.at(0)).grid();
  }
};

TEST_F(VdbDensityCloud, TheMediumIsDensityTimesTheMaterialsMassCoefficients) {
  const Scene s = load(cloud());
  ASSERT_EQ(s.static_clouds.size(), 1u);
  const VoxelGrid& g = grid_of(s);
  EXPECT_EQ(g.dims(), (GridDims{12, 8, 10}));
  EXPECT_EQ(g.wavelengths_um(), kWavelengths);
  const std::vector<MaterialOptics> soot = optics_at(load_material_by_name("soot"), kWavelengths);
  for (const auto& [i, j, k] : {std::tuple{0, 0, 0}, std::tuple{6, 3, 4}, std::tuple{11, 7, 9}}) {
    const int x = kBox.min().x() + i, y = kBox.min().y() + j, z = kBox.min().z() + k;
    const std::size_t v = g.index(i, j, k);
    const double c = static_cast<float>(0.75 * smoke(x, y, z));  // g/m3
    for (int w = 0; w < 3; ++w) {
      EXPECT_EQ(g.sigma_a(w)[v], static_cast<float>(c * soot[w].mass_absorption_m2_g));
      EXPECT_EQ(g.sigma_s(w)[v], static_cast<float>(c * soot[w].mass_scattering_m2_g));
      EXPECT_EQ(g.g(w)[v], static_cast<float>(soot[w].asymmetry));
    }
    EXPECT_EQ(g.temperature()[v], static_cast<float>(290.0 + 900.0 * heat(x, y, z)));
  }
  // Where the tool put it: index (x, y, z) centred at 0.5·(x, y, z) + (0.25, −30, 0.25).
  MediumPoint p;
  s.static_clouds[0]->coefficients_at(Vec3(0.5 * 0 + 0.25, 0.5 * 7 - 30.0, 0.5 * 4 + 0.25), p);
  const double c = static_cast<float>(0.75 * smoke(0, 7, 4));
  EXPECT_NEAR(p.sigma_a[1], c * soot[1].mass_absorption_m2_g, 1e-5 * p.sigma_a[1]);
  EXPECT_EQ(s.input_files.back().filename(), "explosion.vdb");
}

TEST_F(VdbDensityCloud, WithoutATemperatureGridTheCloudIsAtTheAmbientTemperature) {
  nlohmann::json c = cloud();
  for (const char* key : {"temperature_grid", "temperature_scale", "temperature_offset"})
    c.erase(key);
  c["ambient_temperature"] = 275;
  c["position"] = {10, 0, 0};
  const Scene s = load(c);
  const VoxelGrid& g = grid_of(s);
  EXPECT_EQ(g.temperature()[g.index(3, 3, 3)], 275.0f);
  EXPECT_NEAR(g.placement().index_to_world(Vec3(0, 0, 0)).x, 10.0 + 0.5 * -6 + 0.25, 1e-12);
}

TEST_F(VdbDensityCloud, ANumberedSequenceIsKeyframesAtTheFrameRate) {
  for (int f = 1; f <= 3; ++f) write_frame(fmt::format("smoke_{:04d}.vdb", f), 0.5f * f);
  nlohmann::json c = cloud("smoke_####.vdb");
  c["frame_rate_hz"] = 4;
  c["activation"] = 1.0;
  c["deactivation"] = 3.0;
  Scene s = load(c);
  ASSERT_EQ(s.animated_clouds.size(), 1u);
  AnimatedCloud& cloud = *s.animated_clouds[0];
  const auto frame = [&](int f) {
    VdbDensityMapping m;
    m.density_scale_g_m3 = 0.75;
    m.temperature_grid = "temperature";
    m.temperature_scale = 900;
    m.temperature_offset_k = 290;
    std::vector<std::string> warnings;
    return read_vdb_density_cloud(
        dir_ / fmt::format("smoke_{:04d}.vdb", f), m,
        material_species_optics(load_material_by_name("soot"), kWavelengths, 0, 0, warnings));
  };
  const std::size_t v = frame(1).index(6, 3, 4);
  EXPECT_EQ(cloud.stage_grid(0.9), nullptr);  // before the activation
  EXPECT_EQ(cloud.stage_grid(1.25)->sigma_a(1)[v], frame(2).sigma_a(1)[v]);  // frame 2 at 1/4 s
  const float halfway = cloud.stage_grid(1.375)->sigma_a(1)[v];
  EXPECT_NEAR(halfway, 0.5 * (frame(2).sigma_a(1)[v] + frame(3).sigma_a(1)[v]), 1e-6 * halfway);
  EXPECT_EQ(cloud.stage_grid(2.9)->sigma_a(1)[v], frame(3).sigma_a(1)[v]);  // the last, held
  EXPECT_NE(cloud.stage_grid(3.2), nullptr);   // one frame interval after the deactivation…
  EXPECT_EQ(cloud.stage_grid(3.25), nullptr);  // …it is gone
  EXPECT_EQ(s.input_files.size(), 4u);  // soot.json and three frames (load_scene adds the scene)
}

TEST_F(VdbDensityCloud, AMissingFrameIsNamed) {
  for (int f : {1, 2, 4}) write_frame(fmt::format("smoke_{:04d}.vdb", f), 1.0f);
  nlohmann::json c = cloud("smoke_####.vdb");
  c["frame_rate_hz"] = 24;
  std::string e = error_of(c);
  EXPECT_TRUE(contains(e,
                       "scene.json: /clouds/0/file: frame 3 of the sequence is missing: no "
                       "file"))
      << e;
  EXPECT_TRUE(contains(e, "smoke_0003.vdb (the folder holds frames 1-2, 4)")) << e;
  c["frames"] = {1, 2};
  EXPECT_NO_THROW(load(c));
  c["frames"] = {4, 6};
  EXPECT_TRUE(contains(error_of(c), "frame 5 of the sequence is missing")) << error_of(c);
}

TEST_F(VdbDensityCloud, ABandWithExtinctionOnlyIsAWarningOfTheRun) {
  nlohmann::json c = cloud();
  c["material"] = "phosphorus_smoke";  // tabulated (extinction only) in the infrared
  Scene s = load(c);
  ASSERT_EQ(s.warnings.size(), 2u);
  EXPECT_TRUE(contains(s.warnings[1],
                       "phosphorus_smoke at 10 um: the sources give extinction "
                       "only"))
      << s.warnings[1];
  std::vector<std::string> given;
  SequenceOptions options;
  options.on_warning = [&](const std::string& w) { given.push_back(w); };
  render_sequence(s, {0.0, 1.0}, options);
  EXPECT_EQ(given, s.warnings);  // once per run, not per frame
}

TEST_F(VdbDensityCloud, BadKeysAreNamed) {
  nlohmann::json c = cloud();
  c.erase("density_scale");
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/density_scale: missing required field"));
  c = cloud();
  c["frame_rate_hz"] = 24;
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/frame_rate_hz: belongs to a numbered sequence"));
  c = cloud();
  c.erase("temperature_grid");
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/temperature_scale: maps the temperature grid's"));
  c = cloud();
  c["material"] = "no_such_smoke";
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/material: no material 'no_such_smoke'"));
  c = cloud();
  c["wavelengths_um"] = {4, 0.55};
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/wavelengths_um: 0.55 µm"));
  c = cloud("smoke_####.vdb");
  c["frame_rate_hz"] = 24;
  EXPECT_TRUE(contains(error_of(c), "/clouds/0/file: no file of the sequence 'smoke_####.vdb'"));
  c = cloud();
  c["density_grid"] = "smoke";
  EXPECT_TRUE(contains(error_of(c), "explosion.vdb: smoke: no grid of that name"));
}

TEST_F(VdbDensityCloud, ANegativeTemperatureNamesTheVoxel) {
  nlohmann::json c = cloud();
  c["temperature_offset"] = -100;  // heat() is 0.036 at index (-6, 4, 0): 32.4 K − 100 K
  const std::string e = error_of(c);
  EXPECT_TRUE(contains(e, "explosion.vdb: temperature voxel (-6,4,0): value 0.036"));
  EXPECT_TRUE(contains(e, "which must be finite and >= 0")) << e;
}

TEST_F(VdbDensityCloud, FarClustersBecomeOneGridEachWithTheSameMedium) {
  // Two puffs 300 voxels apart: two grids of their own size, and the medium
  // they make is the one box around both (read whole) wherever both define it.
  const auto xf = tool_transform(0.5, {0.0, -30.0, 0.0});
  const auto puff = [](int i, int j, int k) { return smoke(i, j, k); };
  auto density = tool_grid("density", xf, CoordBBox(Coord(-6, 4, 0), Coord(5, 11, 9)), puff);
  testing::add_blob(*density, CoordBBox(Coord(300, 4, 0), Coord(307, 9, 5)), puff);
  write_tool_vdb(dir_ / "two.vdb", {density});
  nlohmann::json c = cloud("two.vdb");
  c.erase("temperature_grid");
  c.erase("temperature_scale");
  c.erase("temperature_offset");
  const Scene s = load(c);
  ASSERT_EQ(s.static_clouds.size(), 2u);
  const VoxelGrid& a = dynamic_cast<const GridMedium&>(*s.static_clouds[0]).grid();
  const VoxelGrid& b = dynamic_cast<const GridMedium&>(*s.static_clouds[1]).grid();
  EXPECT_EQ(a.dims(), (GridDims{14, 10, 12}));
  EXPECT_EQ(b.dims(), (GridDims{10, 8, 8}));
  VdbDensityMapping m;
  m.density_scale_g_m3 = 0.75;
  std::vector<std::string> warnings;
  const SpeciesOptics optics =
      material_species_optics(load_material_by_name("soot"), kWavelengths, 0, 0, warnings);
  const GridMedium whole(
      std::make_shared<VoxelGrid>(read_vdb_density_cloud(dir_ / "two.vdb", m, optics)));
  EXPECT_EQ(whole.grid().dims(), (GridDims{314, 8, 10}));
  // Points over each puff's voxel centres and between them.
  MediumPoint pw, pp;
  int dense = 0;
  for (const auto& [cloud, lo, hi] :
       {std::tuple{s.static_clouds[0].get(), Coord(-6, 4, 0), Coord(5, 11, 9)},
        std::tuple{s.static_clouds[1].get(), Coord(300, 4, 0), Coord(307, 9, 5)}})
    for (double t = 0.0; t <= 1.0; t += 0.0625) {
      const openvdb::Vec3d i(lo.x() + t * (hi.x() - lo.x()), lo.y() + t * t * (hi.y() - lo.y()),
                             lo.z() + (1 - t) * (hi.z() - lo.z()));
      const openvdb::Vec3d w = xf->indexToWorld(i);
      const Vec3 x(w.x(), w.y(), w.z());
      whole.coefficients_at(x, pw);
      cloud->coefficients_at(x, pp);
      for (std::size_t k = 0; k < kWavelengths.size(); ++k) {
        EXPECT_NEAR(pp.sigma_a[k], pw.sigma_a[k], 1e-5 * pw.sigma_a[k] + 1e-12) << i;
        EXPECT_NEAR(pp.sigma_s[k], pw.sigma_s[k], 1e-5 * pw.sigma_s[k] + 1e-12) << i;
      }
      dense += pw.sigma_a[0] > 0.0;
    }
  EXPECT_GT(dense, 20);
  // Between the puffs neither holds medium.
  const openvdb::Vec3d gap = xf->indexToWorld(openvdb::Vec3d(150, 7, 3));
  EXPECT_FALSE(s.static_clouds[0]->bounds().contains(Vec3(gap.x(), gap.y(), gap.z())));
  EXPECT_FALSE(s.static_clouds[1]->bounds().contains(Vec3(gap.x(), gap.y(), gap.z())));
}

TEST_F(VdbDensityCloud, RendersAsTheSameCloudWrittenAsAnObscuraKeyframe) {
  // The cloud built here from the formula and the tool's transform, without
  // the reader: concentration 0.75 × density in the species form.
  std::vector<std::string> warnings;
  SpeciesCloud sc;
  sc.dims = {12, 8, 10};
  sc.placement.voxel_size_m = 0.5;
  sc.placement.origin_m = Vec3(0.5 * -6, 0.5 * 4 - 30.25, 0.0);  // corner of index (−6, 4, 0)
  sc.wavelengths_um = kWavelengths;
  sc.species = {
      material_species_optics(load_material_by_name("soot"), kWavelengths, 0, 0, warnings)};
  sc.concentration_g_m3.resize(1);
  for (int k = 0; k < 10; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 12; ++i) {
        const int x = i - 6, y = j + 4, z = k;
        sc.concentration_g_m3[0].push_back(static_cast<float>(0.75 * smoke(x, y, z)));
        sc.temperature_k.push_back(static_cast<float>(290.0 + 900.0 * heat(x, y, z)));
      }
  write_species_keyframe(dir_ / "keyframe.vdb", sc, 0.0);
  Scene ours = load(cloud());
  Scene reference = load({{"type", "vdb"}, {"file", "keyframe.vdb"}});
  const SensorImage a = testing::render_first_sensor(ours, 1);
  const SensorImage b = testing::render_first_sensor(reference, 1);
  double darkest = 1.0;
  for (std::size_t band = 0; band < 3; ++band)
    for (std::size_t px = 0; px < a.bands[band].radiance.size(); ++px) {
      const float ra = a.bands[band].radiance[px], rb = b.bands[band].radiance[px];
      EXPECT_NEAR(ra, rb, 1e-5 * std::abs(rb)) << "band " << band << " pixel " << px;
      EXPECT_NEAR(a.bands[band].transmittance[px], b.bands[band].transmittance[px], 1e-6);
      darkest = std::min(darkest, static_cast<double>(b.bands[band].transmittance[px]));
    }
  EXPECT_LT(darkest, 0.5);  // the cloud is in view and thick enough to matter
}

}  // namespace
}  // namespace obscura
