// `obscura render` with a target surface: screening metrics (metrics.csv,
// metrics.json, plots, target masks), the contact sheet, the printed summary,
// and the warning when a sensor does not see the target.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

#include "support/cli_runner.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class RenderMetricsTest : public testing::TempDirTest {
 protected:
  // A hot box target on the ground, seen from above at 45° in a short-wave
  // band and the two thermal ones, inside an opaque cloud (σa = 10 /m) when
  // `cloud`; `look_at` aims the sensor.
  fs::path write_scene(bool cloud, bool target = true, nlohmann::json look_at = {0, 0, 1}) {
    nlohmann::json scene = {
        {"sensors",
         {{{"name", "ir"},
           {"position", {0, -20, 20}},
           {"look_at", look_at},
           {"fov_deg", 20},
           {"width", 32},
           {"height", 24},
           {"bands", {{{"name", "swir"}, {"min_um", 1.5}, {"max_um", 2.5}}, "mwir", "lwir"}}}}},
        {"surfaces",
         {{{"type", "ground"}, {"temperature", 290}},
          {{"type", "box"},
           {"name", "tank"},
           {"min", {-2, -2, 0}},
           {"max", {2, 2, 2}},
           {"temperature", 330},
           {"target", target}}}},
        {"metrics", {{"background_margin_px", 4}}}};
    if (cloud)
      scene["clouds"] = {{{"type", "homogeneous"},
                          {"min", {-5, -5, 0}},
                          {"max", {5, 5, 5}},
                          {"wavelengths_um", {1.5, 13}},
                          {"sigma_a", {10, 10}},
                          {"sigma_s", {0, 0}},
                          {"temperature", 280}}};
    const auto p = dir_ / "scene.json";
    std::ofstream(p) << scene.dump(2);
    return p;
  }
  testing::CliResult render(const fs::path& scene, const fs::path& out, const std::string& extra) {
    return testing::run_cli(
        "render " + scene.string() + " -o " + out.string() + " --threads 2 " + extra, dir_);
  }
};

TEST_F(RenderMetricsTest, SequenceWritesMetricsPlotsMaskAndContactSheet) {
  const auto out = dir_ / "out";
  const auto r = render(write_scene(true), out, "--time 0:2:1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.find("warning"), std::string::npos) << r.err;
  for (const char* f :
       {"metrics.csv", "metrics.json", "metrics_transmittance.png", "metrics_screened_fraction.png",
        "metrics_contrast.png", "metrics_delta_t.png", "target_mask_ir.png", "contact_sheet.png",
        "time_series.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(out / f)) << f;

  const std::string csv = testing::read_text_file(out / "metrics.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 3) << csv;  // 3 frames × 3 bands
  EXPECT_EQ(csv.rfind("time_s,sensor,band,", 0), 0u);
  EXPECT_NE(csv.find("\n0,ir,swir,1.5,2.5,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\n2,ir,lwir,8,12,"), std::string::npos) << csv;

  // Screened in every frame: from the first frame (the reference time is 0
  // without animated clouds) to the last.
  const auto j = nlohmann::json::parse(testing::read_text_file(out / "metrics.json"));
  ASSERT_EQ(j["series"].size(), 3u);
  for (const auto& s : j["series"]) {
    EXPECT_GT(s["target_pixels"].get<int>(), 10);
    EXPECT_EQ(s["time_to_screen_s"], 0.0) << s.dump();
    EXPECT_EQ(s["screening_duration_s"], 2.0) << s.dump();
    EXPECT_LT(s["min_transmittance_mean"].get<double>(), 1e-6);
  }
  EXPECT_EQ(j["frames"].size(), 9u);
  EXPECT_EQ(j["frames"][0]["screened_fraction"], 1.0);
  EXPECT_EQ(j["settings"]["background_margin_px"], 4);

  const auto summary = nlohmann::json::parse(testing::read_text_file(out / "summary.json"));
  EXPECT_EQ(summary["metrics"]["series"].size(), 3u);
  EXPECT_NE(r.out.find("screening metrics"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("ir / lwir  time to screen 0 s, screened 2 s in all (first 0–2 s)"),
            std::string::npos)
      << r.out;
}

TEST_F(RenderMetricsTest, ClearViewIsNeverScreened) {
  const auto out = dir_ / "out";
  const auto r = render(write_scene(false), out, "--time 0:1:1 --json");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const auto& s : j["metrics"]["series"]) {
    EXPECT_TRUE(s["time_to_screen_s"].is_null()) << s.dump();
    EXPECT_EQ(s["screening_duration_s"], 0.0);
    EXPECT_EQ(s["max_screened_fraction"], 0.0);
    EXPECT_EQ(s["min_transmittance_mean"], 1.0);
  }
}

TEST_F(RenderMetricsTest, SingleRenderWritesTablesOnly) {
  const auto out = dir_ / "out";
  const auto r = render(write_scene(true), out, "--at 3");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "metrics.csv"));
  EXPECT_TRUE(fs::exists(out / "metrics.json"));
  EXPECT_FALSE(fs::exists(out / "metrics_transmittance.png"));
  EXPECT_FALSE(fs::exists(out / "target_mask_ir.png"));
  EXPECT_FALSE(fs::exists(out / "contact_sheet.png"));
  const std::string csv = testing::read_text_file(out / "metrics.csv");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3);
  EXPECT_NE(csv.find("\n3,ir,mwir,"), std::string::npos) << csv;
}

TEST_F(RenderMetricsTest, TargetOutOfViewWarnsOnceAndWritesNulls) {
  const auto out = dir_ / "out";
  const auto r = render(write_scene(true, true, {0, -40, 20}), out, "--time 0:1:1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("warning: no target pixel in view of sensor ir"), std::string::npos)
      << r.err;
  const auto j = nlohmann::json::parse(testing::read_text_file(out / "metrics.json"));
  EXPECT_EQ(j["targets"][0]["target_pixels"], 0);
  EXPECT_TRUE(j["series"][0]["time_to_screen_s"].is_null());
  EXPECT_TRUE(j["series"][0]["screening_duration_s"].is_null());
  EXPECT_TRUE(j["frames"][0]["transmittance_mean"].is_null());
  EXPECT_NE(r.out.find("no target pixel in view"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(out / "metrics_screened_fraction.png"));
  EXPECT_TRUE(fs::exists(out / "target_mask_ir.png"));
}

TEST_F(RenderMetricsTest, NoTargetSurfaceMeansNoMetrics) {
  const auto out = dir_ / "out";
  const auto r = render(write_scene(true, false), out, "--time 0:1:1");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(out / "metrics.csv"));
  EXPECT_FALSE(fs::exists(out / "metrics.json"));
  EXPECT_TRUE(fs::exists(out / "contact_sheet.png"));
  EXPECT_EQ(r.out.find("screening metrics"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace obscura

namespace obscura {
namespace {

// summary.json says how the photons went: a radiance-cache render of a
// scattering cloud (its cache charged to the sensor, the only one) traces
// photons, some of which meet the cloud, each with at least one collision.
TEST_F(RenderMetricsTest, SummaryCountsThePhotonsWalks) {
  auto scene = nlohmann::json::parse(testing::read_text_file(write_scene(true)));
  scene["clouds"][0]["sigma_a"] = {0.1, 0.1};
  scene["clouds"][0]["sigma_s"] = {0.5, 0.5};
  scene["render"] = {{"method", "radiance-cache"},
                     {"spectral_nodes_per_band", 1},
                     {"radiance_cache", {{"photons", 3000}}}};
  std::ofstream(dir_ / "cache.json") << scene.dump(2);
  const auto out = dir_ / "out";
  const auto r = render(dir_ / "cache.json", out, "--at 0");
  ASSERT_EQ(r.status, 0) << r.err;
  const auto summary = nlohmann::json::parse(testing::read_text_file(out / "summary.json"));
  ASSERT_EQ(summary["sensors"].size(), 1u) << summary.dump();
  const auto& s = summary["sensors"][0];
  const auto traced = s["photons_traced"].get<std::uint64_t>(),
             colliding = s["photons_colliding"].get<std::uint64_t>(),
             collisions = s["photon_collisions"].get<std::uint64_t>();
  EXPECT_GT(traced, 3000u) << s.dump();  // three bands of 3000 launches each
  EXPECT_GT(colliding, 0u) << s.dump();
  EXPECT_LE(colliding, traced) << s.dump();
  EXPECT_GE(collisions, colliding) << s.dump();
}

}  // namespace
}  // namespace obscura
