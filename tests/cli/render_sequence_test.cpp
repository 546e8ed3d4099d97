// `obscura render --time A:B:STEP` on an animated cloud: numbered frames, the
// region time series, and a frame bit-identical to a single render at its time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <nlohmann/json.hpp>

#include "obscura/io/exr_writer.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class RenderSequenceTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    // Three keyframes of a puff that grows denser: 0 s, 2 s, 4 s.
    nlohmann::json frames = nlohmann::json::array();
    for (int k = 0; k < 3; ++k) {
      GaussianPuffSpec spec;
      spec.center_m = {0, 0, 3};
      spec.radius_m = 2;
      spec.resolution = 12;
      spec.wavelengths_um = {4, 10};
      spec.peak_sigma_a = {0.1 + 0.3 * k, 0.2 + 0.3 * k};
      spec.peak_sigma_s = {0.05, 0.02};
      spec.g = {0.5, 0.3};
      spec.temperature_excess_k = 10.0 * k;
      const std::string name = "k" + std::to_string(k) + ".vdb";
      write_cloud_keyframe(dir_ / name, make_gaussian_puff(spec), 2.0 * k);
      frames.push_back({{"file", name}, {"time", 2.0 * k}});
    }
    const nlohmann::json manifest = {{"keyframes", frames},
                                     {"lifecycle",
                                      {{"init_end", 0},
                                       {"loop_start", 0},
                                       {"loop_end", 1},
                                       {"loop_wrap", 2.0},
                                       {"extinction_start", 2}}},
                                     {"trajectory",
                                      {{"keys",
                                        {{{"time", 0.0}, {"position", {-2, 0, 0}}},
                                         {{"time", 4.0}, {"position", {2, 0, 0}}}}}}}};
    std::ofstream(dir_ / "cloud.json") << manifest.dump(2);
    const nlohmann::json scene = {
        {"sensors",
         {{{"name", "ir"},
           {"position", {0, -25, 3}},
           {"look_at", {0, 0, 3}},
           {"fov_deg", 30},
           {"width", 20},
           {"height", 14},
           {"bands", {"mwir", "lwir"}}}}},
        {"clouds", {{{"type", "animated"}, {"manifest", "cloud.json"}, {"activation", 1.0}}}},
        {"surfaces", {{{"type", "ground"}, {"temperature", 290}}}},
        {"sky", {{"temperature", 250}}},
        {"regions", {{{"name", "centre"}, {"sensor", "ir"}, {"pixels", {8, 5, 12, 9}}}}}};
    std::ofstream(dir_ / "scene.json") << scene.dump(2);
  }
};

TEST_F(RenderSequenceTest, WritesFramesAndTimeSeries) {
  const auto out = dir_ / "seq";
  const auto r = testing::run_cli("render " + (dir_ / "scene.json").string() + " -o " +
                                      out.string() + " --time 0:3:1.5 --threads 2",
                                  dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  for (int f = 0; f < 3; ++f) {
    const std::string n = "_f000" + std::to_string(f);
    EXPECT_TRUE(fs::exists(out / ("ir" + n + ".exr"))) << n;
    EXPECT_TRUE(fs::exists(out / ("ir_lwir_radiance" + n + ".png"))) << n;
  }
  EXPECT_FALSE(fs::exists(out / "ir_f0003.exr"));
  const std::string csv = testing::read_text_file(out / "time_series.csv");
  // Header + 3 times × (image + centre) × 2 bands.
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 2 * 2) << csv;
  EXPECT_NE(csv.find("0,ir,image,mwir"), std::string::npos) << csv;
  EXPECT_NE(csv.find("1.5,ir,centre,lwir"), std::string::npos) << csv;
  // Before activation (t = 0) the sky behind the centre is clear; at 1.5 s and 3 s
  // the cloud is there: the centre's transmittance drops.
  const auto t_at = [&](const std::string& key) {
    const auto pos = csv.find(key);
    std::stringstream line(csv.substr(pos, csv.find('\n', pos) - pos));
    std::string cell;
    for (int c = 0; c < 7; ++c) std::getline(line, cell, ',');
    return std::stod(cell);
  };
  EXPECT_DOUBLE_EQ(t_at("0,ir,centre,lwir"), 1.0);
  EXPECT_LT(t_at("1.5,ir,centre,lwir"), 0.95);
  EXPECT_LT(t_at("3,ir,centre,lwir"), t_at("1.5,ir,centre,lwir"));  // denser later
}

TEST_F(RenderSequenceTest, FrameIsBitIdenticalToASingleRenderAtItsTime) {
  const auto seq = dir_ / "seq", single = dir_ / "single";
  ASSERT_EQ(testing::run_cli("render " + (dir_ / "scene.json").string() + " -o " + seq.string() +
                                 " --time 0:3:1.5 --threads 2",
                             dir_)
                .status,
            0);
  const auto r = testing::run_cli("render " + (dir_ / "scene.json").string() + " -o " +
                                      single.string() + " --at 1.5 --threads 1",
                                  dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  const ExrImage a = read_exr(seq / "ir_f0001.exr");
  const ExrImage b = read_exr(single / "ir.exr");
  ASSERT_EQ(a.channels.size(), b.channels.size());
  for (const auto& [name, pixels] : a.channels) {
    ASSERT_TRUE(b.channels.count(name)) << name;
    EXPECT_EQ(0,
              std::memcmp(pixels.data(), b.channels.at(name).data(), pixels.size() * sizeof(float)))
        << name;
  }
}

TEST_F(RenderSequenceTest, BadTimeRangeIsAnError) {
  for (const char* bad : {"0:3", "3:0:1", "0:3:0", "a:b:c"}) {
    const auto r = testing::run_cli("render " + (dir_ / "scene.json").string() + " -o " +
                                        (dir_ / "bad").string() + " --time " + bad,
                                    dir_);
    EXPECT_NE(r.status, 0) << bad;
    EXPECT_NE(r.err.find("--time"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad")) << bad;
  }
}

// A sequence whose second frame meets a corrupt keyframe keeps frame 0 (whole)
// and writes summary.json with the failure and the frames done; before, it
// exited 1 leaving the frames and no summary.
TEST_F(RenderSequenceTest, FailurePartWayKeepsCompletedFramesAndASummary) {
  fs::resize_file(dir_ / "k1.vdb", 100);
  const auto out = dir_ / "seq";
  const auto r = testing::run_cli("render " + (dir_ / "scene.json").string() + " -o " +
                                      out.string() + " --time 0:3:1.5 --threads 2",
                                  dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.rfind("obscura: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find("k1.vdb"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("kept the 1 completed frames 0–0 and summary.json"), std::string::npos)
      << r.err;
  EXPECT_TRUE(fs::exists(out / "ir_f0000.exr"));
  EXPECT_TRUE(fs::exists(out / "ir_lwir_radiance_f0000.png"));
  EXPECT_FALSE(fs::exists(out / "ir_f0001.exr"));
  const auto summary = nlohmann::json::parse(testing::read_text_file(out / "summary.json"));
  EXPECT_EQ(summary["failed"]["frames_completed"], nlohmann::json({0}));
  EXPECT_EQ(summary["failed"]["frames_planned"], 3);
  EXPECT_NE(summary["failed"]["error"].get<std::string>().find("k1.vdb"), std::string::npos);
  for (const auto& e : fs::directory_iterator(out))
    EXPECT_NE(e.path().filename().string()[0], '.') << "temporary left: " << e.path();
}

// Temporaries of a killed run (its pid no longer alive) are removed by the
// next run in the folder; those of a live run are left alone.
TEST_F(RenderSequenceTest, NextRunRemovesAKilledRunsTemporaries) {
  const auto out = dir_ / "seq";
  fs::create_directories(out / ".x.partial-999999999");
  std::ofstream(out / ".ir_f0000.exr.tmp-999999999-3") << "half a file";
  const std::string live = ".mine.exr.tmp-" + std::to_string(::getpid()) + "-0";
  std::ofstream(out / live) << "being written";
  const auto r = testing::run_cli(
      "render " + (dir_ / "scene.json").string() + " -o " + out.string() + " --at 0 --threads 2",
      dir_);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / ".x.partial-999999999"));
  EXPECT_FALSE(fs::exists(out / ".ir_f0000.exr.tmp-999999999-3"));
  EXPECT_TRUE(fs::exists(out / live));
}

// An output name taken by a folder is refused before rendering: nothing else
// is written (before, ir.exr was left behind).
TEST_F(RenderSequenceTest, OutputNameTakenByAFolderLeavesNothing) {
  const auto out = dir_ / "seq";
  fs::create_directories(out / "ir_lwir_radiance.png");
  const auto r = testing::run_cli(
      "render " + (dir_ / "scene.json").string() + " -o " + out.string() + " --at 0", dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("ir_lwir_radiance.png: is a folder where obscura writes a file"),
            std::string::npos)
      << r.err;
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(out)) left.push_back(e.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"ir_lwir_radiance.png"});
}

}  // namespace
}  // namespace obscura
