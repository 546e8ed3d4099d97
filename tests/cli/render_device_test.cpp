// `obscura render --device gpu` and "device": "gpu" (docs/gpu.md): where the
// GPU cannot run (a build without CUDA, or no usable device, as on the CI
// machines) a clear error and no output, never a render on the CPU; where it
// can, the render. A method the GPU does not do is refused either way.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "obscura/gpu/gpu_device.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "support/cli_runner.h"
#include "support/temp_dir_test.h"
#include "support/test_puff.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class RenderDeviceTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    testing::TempDirTest::SetUp();
    write_cloud_keyframe(dir_ / "puff.vdb", make_gaussian_puff(testing::small_puff_spec()), 0.0);
  }
  fs::path scene(const nlohmann::json& render) {
    const nlohmann::json doc = {{"sensors",
                                 {{{"name", "ir"},
                                   {"position", {0, -30, 3}},
                                   {"look_at", {0, 0, 3}},
                                   {"fov_deg", 30},
                                   {"width", 16},
                                   {"height", 12},
                                   {"bands", {"lwir"}}}}},
                                {"clouds", {{{"type", "vdb"}, {"file", "puff.vdb"}}}},
                                {"sky", {{"temperature", 250}}},
                                {"render", render}};
    const fs::path p = dir_ / "scene.json";
    std::ofstream(p) << doc.dump(2);
    return p;
  }
  testing::CliResult render(const fs::path& scene_file, const std::string& options) {
    return testing::run_cli(
        "render " + scene_file.string() + " -o " + (dir_ / "out").string() + " " + options, dir_);
  }
};

TEST_F(RenderDeviceTest, TheGpuRendersOrSaysWhyItCannot) {
  std::string why;
  const bool gpu = gpu_device_count(why) > 0;
  EXPECT_EQ(why.empty(), gpu);
  if (!built_with_cuda()) {
    EXPECT_NE(why.find("built without CUDA"), std::string::npos) << why;
  }
  for (const auto& [render_settings, option] :
       {std::pair{nlohmann::json::object(), std::string("--device gpu")},
        std::pair{nlohmann::json{{"device", "gpu"}}, std::string()}}) {
    fs::remove_all(dir_ / "out");
    const testing::CliResult r = render(scene(render_settings), option);
    if (gpu) {
      EXPECT_EQ(r.status, 0) << r.err;
      EXPECT_TRUE(fs::exists(dir_ / "out" / "summary.json"));
    } else {
      EXPECT_EQ(r.status, 1);
      EXPECT_EQ(r.err, "obscura: error: \"device\": \"gpu\" cannot run: " + why +
                           "; render with \"device\": \"cpu\" (docs/gpu.md)\n");
      EXPECT_FALSE(fs::exists(dir_ / "out"));  // nothing written, nothing rendered on the CPU
    }
  }
}

TEST_F(RenderDeviceTest, AMethodTheGpuDoesNotDoIsRefused) {
  const testing::CliResult r = render(scene({{"method", "photonmap"}}), "--device gpu");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("obscura: error: --device: \"gpu\" renders \"method\": "
                       "\"emission-absorption\" and \"radiance-cache\" only (not \"photonmap\")"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
  // --device cpu over a scene's "gpu" renders on the CPU, as asked.
  const testing::CliResult cpu = render(scene({{"device", "gpu"}}), "--device cpu");
  EXPECT_EQ(cpu.status, 0) << cpu.err;
}

}  // namespace
}  // namespace obscura
