// `obscura cloud-state`: the lifecycle state and pose of a manifest at a time,
// as JSON and text, and a bad manifest's error naming its field.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "support/cli_runner.h"
#include "support/example_manifest.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class CloudStateTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    manifest_ = testing::write_example_manifest_keyframes(dir_);
    manifest_["trajectory"]["drift_velocity"] = {0, 0, 1};
  }
  testing::CliResult run(const std::string& args) { return testing::run_cli(args, dir_); }
  std::string write_manifest() {
    const auto p = dir_ / "cloud.json";
    std::ofstream(p) << manifest_.dump(2);
    return p.string();
  }
  nlohmann::json state(const std::string& args) {
    const testing::CliResult r = run("cloud-state " + write_manifest() + " " + args + " --json");
    EXPECT_EQ(r.status, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }
  nlohmann::json manifest_;
};

TEST_F(CloudStateTest, JsonDuringTheLoopWrap) {
  const auto j = state("--at 7.25");
  EXPECT_EQ(j["phase"], "evolution");
  EXPECT_EQ(j["keyframes"], nlohmann::json({7, 4}));
  EXPECT_EQ(j["weight"], 0.25);
  EXPECT_EQ(j["local_time_s"], 7.25);
  EXPECT_EQ(j["position_m"], nlohmann::json({72.5, 0.0, 7.25}));
  EXPECT_EQ(j["heading_deg"], 65.25);
  EXPECT_EQ(j.size(), 6u);
}

TEST_F(CloudStateTest, JsonWithActivationAndDeactivation) {
  auto j = state("--at 9 --activate 10");
  EXPECT_EQ(j["phase"], "absent");
  EXPECT_EQ(j["keyframes"], nlohmann::json({-1, -1}));
  EXPECT_EQ(j["local_time_s"], -1.0);

  j = state("--at 12.5 --activate 10");
  EXPECT_EQ(j["phase"], "initialisation");
  EXPECT_EQ(j["keyframes"], nlohmann::json({2, 3}));
  EXPECT_EQ(j["weight"], 0.5);

  // Deactivated mid K5 → K6 at local 5.5 s: K6 at 6 s, then K6 → K8 over 1 s.
  j = state("--at 16.5 --activate 10 --deactivate 15.5");
  EXPECT_EQ(j["phase"], "extinction");
  EXPECT_EQ(j["keyframes"], nlohmann::json({6, 8}));
  EXPECT_EQ(j["weight"], 0.5);

  j = state("--at 19 --activate 10 --deactivate 15.5");
  EXPECT_EQ(j["phase"], "extinct");
  EXPECT_EQ(j["keyframes"], nlohmann::json({-1, -1}));
}

TEST_F(CloudStateTest, TextOutputHasUnits) {
  const testing::CliResult r = run("cloud-state " + write_manifest() + " --at 3.5");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("evolution"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3.5 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("35 0 3.5 m"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("31.5 deg"), std::string::npos) << r.out;
}

TEST_F(CloudStateTest, BadManifestNamesTheField) {
  manifest_["lifecycle"]["loop_end"] = 2;
  const std::string path = write_manifest();
  const testing::CliResult r = run("cloud-state " + path + " --at 1 --json");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.out, "");
  EXPECT_NE(r.err.find(path), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("/lifecycle/loop_end"), std::string::npos) << r.err;
}

TEST_F(CloudStateTest, MissingKeyframeFileNamesTheField) {
  fs::remove(dir_ / testing::example_keyframe_name(2));
  const testing::CliResult r = run("cloud-state " + write_manifest() + " --at 1");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("/keyframes/2/file"), std::string::npos) << r.err;
}

TEST_F(CloudStateTest, AtIsRequired) {
  const testing::CliResult r = run("cloud-state " + write_manifest());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("--at"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace obscura
