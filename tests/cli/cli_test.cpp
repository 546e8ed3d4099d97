// End-to-end tests of the `obscura` tool: exit status, messages that name the
// file and the field, machine-readable output, and no partial output on error.
#include <gtest/gtest.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"
#include "support/test_puff.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class CliTest : public testing::TempDirTest {
 protected:
  testing::CliResult run(const std::string& args) { return testing::run_cli(args, dir_); }
  fs::path write_scene(const nlohmann::json& doc, const std::string& name = "scene.json") {
    const auto p = dir_ / name;
    std::ofstream(p) << doc.dump(2);
    return p;
  }
  static nlohmann::json scene_with_vdb(const std::string& vdb) {
    return {{"sensors",
             {{{"name", "ir"},
               {"position", {0, -30, 3}},
               {"look_at", {0, 0, 3}},
               {"fov_deg", 30},
               {"width", 24},
               {"height", 16},
               {"bands", {"mwir", "lwir"}}}}},
            {"clouds", {{{"type", "vdb"}, {"file", vdb}}}},
            {"surfaces", {{{"type", "ground"}, {"temperature", 290}}}},
            {"sky", {{"temperature", 250}}}};
  }
  fs::path write_puff(const std::string& name) {
    const GaussianPuffSpec spec = testing::small_puff_spec();
    const auto p = dir_ / name;
    write_cloud_keyframe(p, make_gaussian_puff(spec), 0.0);
    return p;
  }
  // Rewrites a keyframe file after `edit` changes its grids or metadata.
  void tamper(const fs::path& p,
              const std::function<void(openvdb::GridPtrVec&, openvdb::MetaMap&)>& edit) {
    openvdb::initialize();
    openvdb::io::File in(p.string());
    in.open();
    openvdb::GridPtrVecPtr grids = in.getGrids();
    openvdb::MetaMap::Ptr meta = in.getMetadata();
    in.close();
    edit(*grids, *meta);
    openvdb::io::File out(p.string());
    out.write(*grids, *meta);
  }
  // The render must fail, name `file` and `field`, and leave no file in the output folder.
  void expect_render_error(const fs::path& scene, const std::string& file,
                           const std::string& field) {
    const auto out_dir = dir_ / "out";
    const testing::CliResult r = run("render " + scene.string() + " -o " + out_dir.string());
    EXPECT_NE(r.status, 0);
    EXPECT_NE(r.err.find("error"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(file), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
    if (fs::exists(out_dir)) {
      EXPECT_TRUE(fs::is_empty(out_dir)) << "partial output left behind";
    }
  }
};

TEST_F(CliTest, VersionAndHelp) {
  testing::CliResult r = run("--version");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("obscura 0."), std::string::npos) << r.out;
  for (const char* sub : {"info", "render", "radiance", "make-puff"}) {
    r = run(std::string(sub) + " --help");
    EXPECT_EQ(r.status, 0) << sub;
    EXPECT_NE(r.out.find("--json"), std::string::npos) << sub << r.out;
  }
  EXPECT_NE(run("").status, 0);
  EXPECT_NE(run("frobnicate").status, 0);
}

TEST_F(CliTest, RadianceAndItsInverse) {
  testing::CliResult r = run("radiance --temperature 300 --band 8:12 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const double l = nlohmann::json::parse(r.out)["band_radiance"].get<double>();
  EXPECT_NEAR(l, 38.5, 0.1);  // docs/domain.md §5.3
  r = run("radiance --band-radiance " + std::to_string(l) + " --band lwir --json");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NEAR(nlohmann::json::parse(r.out)["temperature"].get<double>(), 300.0, 1e-3);
  r = run("radiance --temperature 300 --band mwir");
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("W m⁻² sr⁻¹"), std::string::npos);
  r = run("radiance --temperature 300 --band 12:8");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--band"), std::string::npos) << r.err;
  EXPECT_NE(run("radiance --band lwir").status, 0);
}

TEST_F(CliTest, InfoDescribesAKeyframe) {
  const auto vdb = write_puff("puff.vdb");
  testing::CliResult r = run("info " + vdb.string() + " --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["dims"], nlohmann::json({16, 16, 16}));
  EXPECT_EQ(j["wavelengths_um"], nlohmann::json({4.0, 10.0}));
  EXPECT_EQ(j["channels"].size(), 7u);
  EXPECT_GT(j["memory_bytes"].get<double>(), 16.0 * 16 * 16 * 7 * 4 - 1);
  r = run("info " + vdb.string());
  EXPECT_EQ(r.status, 0);
  EXPECT_NE(r.out.find("sigma_a_001"), std::string::npos) << r.out;
}

TEST_F(CliTest, RenderWritesImagesAndSummary) {
  write_puff("puff.vdb");
  const auto scene = write_scene(scene_with_vdb("puff.vdb"));
  const auto out = dir_ / "render";
  const testing::CliResult r =
      run("render " + scene.string() + " -o " + out.string() + " --threads 2 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["sensors"][0]["bands"].size(), 2u);
  for (const char* f : {"ir.exr", "ir_mwir_radiance.png", "ir_lwir_apparent_temperature.png",
                        "ir_lwir_transmittance.png", "summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;
  // The cloud is in view: some pixels see less than full transmittance.
  const double mean_t = j["sensors"][0]["bands"][1]["mean_transmittance"].get<double>();
  EXPECT_LT(mean_t, 0.999);
  EXPECT_GT(mean_t, 0.0);
  // Nothing left under a temporary name.
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << e.path();
}

TEST_F(CliTest, ABandOutsideTheCloudsSamplesIsWarnedAboutOnce) {
  // The puff is sampled at 4 and 10 µm only: a visible band would see its
  // 4 µm coefficients, which the user must be told. A sequence of three
  // frames gives the warning once.
  write_puff("puff.vdb");
  nlohmann::json doc = scene_with_vdb("puff.vdb");
  doc["sensors"][0]["bands"] = {"visible", "lwir"};
  const auto scene = write_scene(doc);
  const testing::CliResult r = run("render " + scene.string() + " -o " + (dir_ / "out").string() +
                                   " --time 0:2:1 --threads 1");
  ASSERT_EQ(r.status, 0) << r.err;
  const std::string warning =
      "obscura: warning: sensor ir, band visible (0.4-0.7 µm) lies outside the clouds' spectral "
      "samples (4-10 µm): their coefficients are held at the 4 µm values across it";
  const auto at = r.err.find(warning);
  ASSERT_NE(at, std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(warning, at + 1), std::string::npos) << "given twice:\n" << r.err;
  EXPECT_EQ(r.err.find("band lwir"), std::string::npos) << r.err;
}

TEST_F(CliTest, MissingFieldFails) {
  auto doc = scene_with_vdb("puff.vdb");
  doc["sensors"][0].erase("look_at");
  expect_render_error(write_scene(doc), "scene.json", "/sensors/0/look_at");
}

TEST_F(CliTest, WrongTypeFails) {
  auto doc = scene_with_vdb("puff.vdb");
  doc["sensors"][0]["width"] = "wide";
  expect_render_error(write_scene(doc), "scene.json", "/sensors/0/width");
}

TEST_F(CliTest, NegativeCoefficientFails) {
  auto doc = scene_with_vdb("puff.vdb");
  doc["clouds"] = {{{"type", "homogeneous"},
                    {"min", {-1, -1, 0}},
                    {"max", {1, 1, 2}},
                    {"wavelengths_um", {10}},
                    {"sigma_a", {-0.1}},
                    {"sigma_s", {0}},
                    {"temperature", 300}}};
  expect_render_error(write_scene(doc), "scene.json", "/clouds/0/sigma_a[0]");
}

TEST_F(CliTest, NegativeCoefficientInKeyframeFails) {
  const auto vdb = write_puff("puff.vdb");
  tamper(vdb, [](openvdb::GridPtrVec& grids, openvdb::MetaMap&) {
    for (auto& g : grids)
      if (g->getName() == "sigma_s_001")
        openvdb::gridPtrCast<openvdb::FloatGrid>(g)->tree().setValue(openvdb::Coord(8, 8, 8),
                                                                     -1.0f);
  });
  expect_render_error(write_scene(scene_with_vdb("puff.vdb")), "puff.vdb", "sigma_s_001");
}

TEST_F(CliTest, NaNInKeyframeFails) {
  const auto vdb = write_puff("puff.vdb");
  tamper(vdb, [](openvdb::GridPtrVec& grids, openvdb::MetaMap&) {
    for (auto& g : grids)
      if (g->getName() == "temperature")
        openvdb::gridPtrCast<openvdb::FloatGrid>(g)->tree().setValue(openvdb::Coord(3, 4, 5),
                                                                     std::nanf(""));
  });
  expect_render_error(write_scene(scene_with_vdb("puff.vdb")), "puff.vdb", "temperature");
}

TEST_F(CliTest, AsymmetryOutsideRangeFails) {
  const auto vdb = write_puff("puff.vdb");
  tamper(vdb, [](openvdb::GridPtrVec& grids, openvdb::MetaMap&) {
    for (auto& g : grids)
      if (g->getName() == "g_000")
        openvdb::gridPtrCast<openvdb::FloatGrid>(g)->tree().setValue(openvdb::Coord(1, 2, 3), 1.5f);
  });
  expect_render_error(write_scene(scene_with_vdb("puff.vdb")), "puff.vdb", "g_000");
}

TEST_F(CliTest, ZeroSizeGridFails) {
  const auto vdb = write_puff("puff.vdb");
  tamper(vdb, [](openvdb::GridPtrVec&, openvdb::MetaMap& meta) {
    meta.removeMeta("dims");
    meta.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(16, 0, 16)));
  });
  expect_render_error(write_scene(scene_with_vdb("puff.vdb")), "puff.vdb", "dims");
}

TEST_F(CliTest, OverflowingOrHugeDimsFail) {
  for (int side : {2000000000, 100000}) {
    const auto vdb = write_puff("puff.vdb");
    tamper(vdb, [side](openvdb::GridPtrVec&, openvdb::MetaMap& meta) {
      meta.removeMeta("dims");
      meta.insertMeta("dims", openvdb::Vec3IMetadata(openvdb::Vec3i(side, side, side)));
    });
    expect_render_error(write_scene(scene_with_vdb("puff.vdb")), "puff.vdb", "dims");
  }
}

TEST_F(CliTest, UnreadableFileFails) {
  expect_render_error(write_scene(scene_with_vdb("missing.vdb")), "missing.vdb", "cannot");
  const testing::CliResult r = run("info " + (dir_ / "nope.vdb").string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("nope.vdb"), std::string::npos) << r.err;
  expect_render_error(dir_ / "absent.json", "absent.json", "no such file");
}

}  // namespace
}  // namespace obscura
