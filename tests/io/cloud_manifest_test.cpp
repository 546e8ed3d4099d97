// Cloud manifests: a good one parses with paths resolved against its folder;
// every bad one is an InputError naming the file and the JSON path.
#include "obscura/io/cloud_manifest.h"

#include <gtest/gtest.h>

#include <fstream>

#include "obscura/core/error.h"
#include "support/example_manifest.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class CloudManifestTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    example_ = testing::write_example_manifest_keyframes(dir_);
    example_["trajectory"]["drift_velocity"] = {0, 1, 0};
  }
  static std::string file_name(int k) { return testing::example_keyframe_name(k); }
  // The example of docs/time-varying-clouds.md: 11 keyframes 1 s apart.
  nlohmann::json example() const { return example_; }
  nlohmann::json example_;
  fs::path write(const nlohmann::json& doc, const std::string& name = "cloud.json") {
    const fs::path p = dir_ / name;
    std::ofstream(p) << doc.dump(2);
    return p;
  }
  // The error message of reading `doc` ("" if it parsed); checks it names the file.
  std::string error_of(const nlohmann::json& doc) {
    const fs::path p = write(doc);
    try {
      read_cloud_manifest(p);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), p.string());
      EXPECT_NE(std::string(e.what()).find(p.string()), std::string::npos) << e.what();
      return e.what();
    }
    return "";
  }
  // Expects reading `doc` to fail with a message containing `path`.
  void expect_error(const nlohmann::json& doc, const std::string& path,
                    const std::string& what = "") {
    const std::string m = error_of(doc);
    EXPECT_NE(m.find(path + ":"), std::string::npos) << "expected " << path << " in: " << m;
    EXPECT_NE(m.find(what), std::string::npos) << "expected '" << what << "' in: " << m;
  }
};

TEST_F(CloudManifestTest, ParsesTheExample) {
  const CloudManifest m = read_cloud_manifest(write(example()));
  EXPECT_EQ(m.source, dir_ / "cloud.json");
  ASSERT_EQ(m.keyframes.size(), 11u);
  EXPECT_EQ(m.keyframes[2].file, dir_ / "k002.vdb");
  EXPECT_EQ(m.keyframes[2].time_s, 2.0);
  EXPECT_EQ(m.lifecycle.keyframe_times_s().size(), 11u);
  EXPECT_EQ(m.lifecycle.spec().init_end, 3);
  EXPECT_EQ(m.lifecycle.spec().loop_start, 4);
  EXPECT_EQ(m.lifecycle.spec().loop_end, 7);
  EXPECT_EQ(m.lifecycle.spec().loop_wrap_s, 1.0);
  EXPECT_EQ(m.lifecycle.spec().extinction_start, 8);
  EXPECT_EQ(m.lifecycle.loop_period_s(), 4.0);
  const LifecycleState s = m.lifecycle.at(7.25, 0, std::nullopt);
  EXPECT_EQ(s.keyframe0, 7);
  EXPECT_EQ(s.keyframe1, 4);
  EXPECT_EQ(s.weight, 0.25);
  const TrajectoryPose p = m.trajectory.at(5);
  EXPECT_EQ(p.position_m, Vec3(50, 5, 0));
  EXPECT_EQ(p.heading_deg, 45);
}

TEST_F(CloudManifestTest, TrajectoryAndItsFieldsAreOptional) {
  auto doc = example();
  doc.erase("trajectory");
  const CloudManifest m = read_cloud_manifest(write(doc));
  EXPECT_EQ(m.trajectory.at(5).position_m, Vec3(0, 0, 0));
  EXPECT_EQ(m.trajectory.at(5).heading_deg, 0);

  doc = example();
  doc["trajectory"].erase("interpolation");
  doc["trajectory"].erase("drift_velocity");
  doc["trajectory"]["keys"][1].erase("heading_deg");
  const CloudManifest n = read_cloud_manifest(write(doc));
  EXPECT_EQ(n.trajectory.interpolation(), TrajectoryInterpolation::kLinear);
  EXPECT_EQ(n.trajectory.at(5).position_m, Vec3(50, 0, 0));
  EXPECT_EQ(n.trajectory.at(5).heading_deg, 0);

  doc = example();
  doc["trajectory"]["interpolation"] = "catmull-rom";
  EXPECT_EQ(read_cloud_manifest(write(doc)).trajectory.interpolation(),
            TrajectoryInterpolation::kCatmullRom);
}

TEST_F(CloudManifestTest, KeyframeFilesResolveAgainstTheManifestFolder) {
  fs::create_directories(dir_ / "sub" / "frames");
  auto doc = example();
  for (int k = 0; k <= 10; ++k) {
    std::ofstream(dir_ / "sub" / "frames" / file_name(k));
    doc["keyframes"][k]["file"] = "frames/" + file_name(k);
  }
  doc["keyframes"][0]["file"] = (dir_ / file_name(0)).string();  // absolute stays as is
  const CloudManifest m = read_cloud_manifest(write(doc, "sub/cloud.json"));
  EXPECT_EQ(m.keyframes[0].file, dir_ / file_name(0));
  EXPECT_EQ(m.keyframes[1].file, dir_ / "sub" / "frames" / file_name(1));
}

TEST_F(CloudManifestTest, IndexesOutOfRangeOrOutOfOrder) {
  auto doc = example();
  doc["lifecycle"]["loop_end"] = 11;
  expect_error(doc, "/lifecycle/loop_end", "out of range");
  doc = example();
  doc["lifecycle"]["loop_end"] = 3;
  expect_error(doc, "/lifecycle/loop_end", ">= loop_start");
  doc = example();
  doc["lifecycle"]["init_end"] = 5;
  expect_error(doc, "/lifecycle/loop_start", ">= init_end");
  doc = example();
  doc["lifecycle"]["init_end"] = -1;
  expect_error(doc, "/lifecycle/init_end", "out of range");
  doc = example();
  doc["lifecycle"]["extinction_start"] = 7;
  expect_error(doc, "/lifecycle/extinction_start");
  doc = example();
  doc["lifecycle"]["extinction_start"] = 11;
  expect_error(doc, "/lifecycle/extinction_start");
}

TEST_F(CloudManifestTest, NonIntegerIndexes) {
  auto doc = example();
  doc["lifecycle"]["init_end"] = 3.5;
  expect_error(doc, "/lifecycle/init_end", "integer");
  doc = example();
  doc["lifecycle"]["loop_start"] = "4";
  expect_error(doc, "/lifecycle/loop_start", "integer");
  doc = example();
  doc["lifecycle"]["loop_end"] = 1e30;
  expect_error(doc, "/lifecycle/loop_end");
}

TEST_F(CloudManifestTest, NegativeOrZeroWrap) {
  auto doc = example();
  doc["lifecycle"]["loop_wrap"] = -1.0;
  expect_error(doc, "/lifecycle/loop_wrap", ">= 0");
  doc["lifecycle"]["loop_wrap"] = 0;
  expect_error(doc, "/lifecycle/loop_wrap", "> 0");
}

TEST_F(CloudManifestTest, KeyframeTimes) {
  auto doc = example();
  doc["keyframes"][3]["time"] = 1.5;
  expect_error(doc, "/keyframes/3/time", "increase");
  doc["keyframes"][3]["time"] = 2.0;
  expect_error(doc, "/keyframes/3/time", "increase");
  doc = example();
  doc["keyframes"][0]["time"] = -0.5;
  expect_error(doc, "/keyframes/0/time", ">= 0");
  doc = example();
  doc["keyframes"][4].erase("time");
  expect_error(doc, "/keyframes/4/time", "missing");
}

TEST_F(CloudManifestTest, MissingKeyframeFile) {
  fs::remove(dir_ / file_name(2));
  expect_error(example(), "/keyframes/2/file", "does not exist");
  auto doc = example();
  doc["keyframes"][5]["file"] = "frames";  // a folder is not a keyframe
  fs::create_directories(dir_ / "frames");
  const std::string m = error_of(doc);
  EXPECT_NE(m.find("/keyframes/2/file"), std::string::npos) << m;  // the first one
}

TEST_F(CloudManifestTest, FolderAsKeyframeFile) {
  fs::create_directories(dir_ / "frames");
  auto doc = example();
  doc["keyframes"][5]["file"] = "frames";
  expect_error(doc, "/keyframes/5/file");
}

TEST_F(CloudManifestTest, UnknownKeysAreErrors) {
  auto doc = example();
  doc["lifecycle"]["loop_wrp"] = 1;
  expect_error(doc, "/lifecycle/loop_wrp", "unknown field");
  doc = example();
  doc["keyframes"][1]["weight"] = 1;
  expect_error(doc, "/keyframes/1/weight", "unknown field");
  doc = example();
  doc["trajectory"]["keys"][0]["heading"] = 1;
  expect_error(doc, "/trajectory/keys/0/heading", "unknown field");
  doc = example();
  doc["trajectory"]["drift"] = {0, 0, 0};
  expect_error(doc, "/trajectory/drift", "unknown field");
  doc = example();
  doc["lifecyle"] = doc["lifecycle"];
  expect_error(doc, "/lifecyle", "unknown field");
}

TEST_F(CloudManifestTest, MissingOrMistypedSections) {
  auto doc = example();
  doc.erase("lifecycle");
  expect_error(doc, "/lifecycle", "missing");
  doc = example();
  doc["lifecycle"].erase("extinction_start");
  expect_error(doc, "/lifecycle/extinction_start", "missing");
  doc = example();
  doc["keyframes"] = nlohmann::json::array();
  expect_error(doc, "/keyframes", "at least one");
  doc = example();
  doc["keyframes"] = "k000.vdb";
  expect_error(doc, "/keyframes", "array");
}

TEST_F(CloudManifestTest, BadTrajectory) {
  auto doc = example();
  doc["trajectory"]["interpolation"] = "cubic";
  expect_error(doc, "/trajectory/interpolation", "catmull-rom");
  doc = example();
  doc["trajectory"]["keys"][1]["time"] = 0.0;
  expect_error(doc, "/trajectory/keys/1/time", "increase");
  doc = example();
  doc["trajectory"]["keys"][0]["position"] = {0, 0};
  expect_error(doc, "/trajectory/keys/0/position", "3 numbers");
  doc = example();
  doc["trajectory"]["drift_velocity"] = {0, "x", 0};
  expect_error(doc, "/trajectory/drift_velocity/1", "number");
}

TEST_F(CloudManifestTest, InvalidJsonNamesTheFileAndLine) {
  const fs::path p = dir_ / "broken.json";
  std::ofstream(p) << "{\n  \"keyframes\": [\n";
  try {
    read_cloud_manifest(p);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), p.string());
    EXPECT_NE(e.field().find("line"), std::string::npos) << e.what();
  }
  EXPECT_THROW(read_cloud_manifest(dir_ / "nonexistent.json"), InputError);
}

}  // namespace
}  // namespace obscura
