#include "obscura/scene/animated_cloud.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/keyframe_interpolation.h"
#include "support/temp_dir_test.h"

namespace obscura {
namespace {

class AnimatedCloudTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    nlohmann::json frames = nlohmann::json::array();
    for (int k = 0; k < 3; ++k) {
      GaussianPuffSpec spec;
      spec.resolution = 8;
      spec.wavelengths_um = {10.0};
      spec.peak_sigma_a = {0.2 + 0.1 * k};
      spec.peak_sigma_s = {0.05};
      spec.g = {0.4};
      spec.temperature_excess_k = 5.0 * k;
      grids_.push_back(make_gaussian_puff(spec));
      const std::string name = "k" + std::to_string(k) + ".vdb";
      write_cloud_keyframe(dir_ / name, grids_.back(), 1.0 * k);
      frames.push_back({{"file", name}, {"time", 1.0 * k}});
    }
    std::ofstream(dir_ / "cloud.json") << nlohmann::json{
        {"keyframes", frames},
        {"lifecycle",
         {{"init_end", 0},
          {"loop_start", 0},
          {"loop_end", 1},
          {"loop_wrap", 1.0},
          {"extinction_start", 2}}},
        {"trajectory",
         {{"keys", {{{"time", 0.0}, {"position", {10, 0, 0}}, {"heading_deg", 0}}}},
          {"drift_velocity", {0, 2, 0}}}}}.dump();
  }
  static bool same_values(const VoxelGrid& a, const VoxelGrid& b) {
    if (!(a.dims() == b.dims())) return false;
    for (int c = 0; c < a.channel_count(); ++c)
      if (std::memcmp(a.channel(c), b.channel(c), a.dims().count() * sizeof(float))) return false;
    return true;
  }
  std::vector<VoxelGrid> grids_;
};

TEST_F(AnimatedCloudTest, StagesKeyframesExactlyAndInterpolatesBetween) {
  AnimatedCloud cloud("c", read_cloud_manifest(dir_ / "cloud.json"), 5.0, 8.0, 2);
  EXPECT_EQ(cloud.stage(4.9), nullptr);  // before activation
  // At activation + 1 s: keyframe 1, bit for bit, moved by the trajectory.
  const auto at_key = cloud.stage_grid(6.0);
  ASSERT_TRUE(at_key);
  EXPECT_TRUE(same_values(*at_key, grids_[1]));
  const Vec3 expected_origin = grids_[1].placement().origin_m + Vec3(10, 2.0 * 1.0, 0);
  EXPECT_NEAR(length(at_key->placement().origin_m - expected_origin), 0.0, 1e-12);
  // Midway between keyframes 0 and 1 (local 0.5 s): the per-voxel average.
  const auto mid = cloud.stage_grid(5.5);
  EXPECT_TRUE(same_values(*mid, interpolate_keyframes(grids_[0], grids_[1], 0.5)));
  // Deactivated at 8 s: interval in progress completes, then heads to keyframe 2,
  // and after it the cloud is gone.
  EXPECT_EQ(cloud.stage(20.0), nullptr);
  EXPECT_LE(cloud.cache().resident(), 2u);
}

}  // namespace
}  // namespace obscura
