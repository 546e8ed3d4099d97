// `obscura render --format netcdf`: render.nc beside the usual outputs, from
// the option or the scene's "outputs"; an unknown format is a usage error
// (exit 64) that names the formats, before anything is rendered; a sequence
// that fails part-way keeps render.nc with the frames that completed.
#include <gtest/gtest.h>
#include <netcdf.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "obscura/io/vdb_keyframe.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"
#include "support/test_puff.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class RenderNetcdfTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    out_ = dir_ / "out";
    write_scene(scene_doc());
  }
  static nlohmann::json scene_doc() {
    return nlohmann::json::parse(R"({
      "sensors": [{"name": "ir", "position": [0, -40, 3], "look_at": [0, 0, 1.5],
                   "fov_deg": 20, "width": 10, "height": 6, "bands": ["lwir"]}],
      "clouds": [{"type": "homogeneous", "min": [-1.5, -6, 0], "max": [0.5, -2, 4],
                  "wavelengths_um": [4, 10], "sigma_a": [0.3, 0.2], "sigma_s": [0.2, 0.05],
                  "g": [0.6, 0.4], "temperature": 300}],
      "surfaces": [{"type": "box", "min": [-2, 0, 0], "max": [2, 4, 2.5], "temperature": 330,
                    "target": true}],
      "sky": {"temperature": 250}
    })");
  }
  void write_scene(const nlohmann::json& doc) { std::ofstream(dir_ / "scene.json") << doc.dump(); }
  testing::CliResult render(const std::string& options) {
    return testing::run_cli(
        "render " + (dir_ / "scene.json").string() + " -o " + out_.string() + " " + options, dir_);
  }
  // The length of `dim` in render.nc (0 when it cannot be read).
  std::size_t dim_length(const char* dim) const {
    int nc = -1, id = -1;
    std::size_t n = 0;
    if (nc_open((out_ / "render.nc").c_str(), NC_NOWRITE, &nc) != NC_NOERR) return 0;
    if (nc_inq_dimid(nc, dim, &id) == NC_NOERR) nc_inq_dimlen(nc, id, &n);
    nc_close(nc);
    return n;
  }
  fs::path out_;
};

TEST_F(RenderNetcdfTest, FormatNetcdfAddsRenderNcToTheUsualOutputs) {
  const auto r = render("--time 0:1:0.5 --format netcdf");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out_ / "render.nc"));
  EXPECT_EQ(dim_length("time"), 3u);
  EXPECT_EQ(dim_length("x_ir"), 10u);
  EXPECT_TRUE(fs::is_regular_file(out_ / "ir_f0002.exr"));
  EXPECT_TRUE(fs::is_regular_file(out_ / "metrics.csv"));
  EXPECT_NE(r.out.find("  render.nc\n"), std::string::npos) << r.out;
  // Without it: no render.nc.
  out_ = dir_ / "plain";
  ASSERT_EQ(render("--at 0").status, 0);
  EXPECT_TRUE(fs::is_regular_file(out_ / "ir.exr"));
  EXPECT_FALSE(fs::exists(out_ / "render.nc"));
}

TEST_F(RenderNetcdfTest, TheSceneCanAskForItAndTheOptionRepeats) {
  auto doc = scene_doc();
  doc["outputs"] = {"netcdf"};
  write_scene(doc);
  out_ = dir_ / "scene_asks";
  ASSERT_EQ(render("--at 2").status, 0);
  EXPECT_EQ(dim_length("time"), 1u);
  out_ = dir_ / "twice";
  const auto r = render("--at 0 --format netcdf,netcdf --format netcdf");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(out_ / "render.nc"));
}

TEST_F(RenderNetcdfTest, AnUnknownFormatIsAUsageError) {
  const auto r = render("--format netcdf,tiff");
  EXPECT_EQ(r.status, 64) << r.err;
  EXPECT_NE(r.err.find("obscura: error: "), std::string::npos) << r.err;
  EXPECT_NE(
      r.err.find("unknown output format 'tiff' (expected: netcdf, envi; EXR, PNG, CSV and JSON "
                 "files are always written)"),
      std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(out_));  // refused before anything was read or written
}

TEST_F(RenderNetcdfTest, AnUnknownFormatInTheSceneIsAnInputErrorNamingItsPath) {
  auto doc = scene_doc();
  doc["outputs"] = {"exr"};
  write_scene(doc);
  const auto r = render("");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("scene.json: /outputs/0: unknown output format 'exr'"), std::string::npos)
      << r.err;
}

TEST_F(RenderNetcdfTest, ASequenceThatFailsPartWayKeepsTheCompletedFrames) {
  // Keyframes at 0 and 2 s and a corrupt one at 4 s, read when extinction
  // reaches it (after deactivation at 3 s): frames 0–4 s render, 5 s fails.
  const GaussianPuffSpec spec = testing::small_puff_spec();
  write_cloud_keyframe(dir_ / "k0.vdb", make_gaussian_puff(spec), 0.0);
  write_cloud_keyframe(dir_ / "k1.vdb", make_gaussian_puff(spec), 2.0);
  std::ofstream(dir_ / "k2.vdb") << "junk";
  std::ofstream(dir_ / "cloud.json") << R"({
    "keyframes": [{"file": "k0.vdb", "time": 0}, {"file": "k1.vdb", "time": 2},
                  {"file": "k2.vdb", "time": 4}],
    "lifecycle": {"init_end": 0, "loop_start": 0, "loop_end": 1, "loop_wrap": 2.0,
                  "extinction_start": 2}})";
  auto doc = scene_doc();
  doc["clouds"] = {
      {{"type", "animated"}, {"manifest", "cloud.json"}, {"activation", 0}, {"deactivation", 3}}};
  write_scene(doc);
  const auto r = render("--time 0:6:1 --format netcdf");
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("k2.vdb"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("frames 0–4, render.nc and summary.json"), std::string::npos) << r.err;
  EXPECT_EQ(dim_length("time"), 5u);
  int nc = -1;
  ASSERT_EQ(nc_open((out_ / "render.nc").c_str(), NC_NOWRITE, &nc), NC_NOERR);
  char status[16] = {};
  EXPECT_EQ(nc_get_att_text(nc, NC_GLOBAL, "run_status", status), NC_NOERR);
  nc_close(nc);
  EXPECT_STREQ(status, "failed");
}

}  // namespace
}  // namespace obscura
