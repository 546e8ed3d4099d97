// Runs that lose nothing (docs/errors.md): a sequence that fails part-way or
// is stopped by SIGTERM keeps its completed frames, exits with the documented
// status, leaves no temporary, and `render --resume` then ends with the
// outputs an uninterrupted run writes, bit for bit; a resume of another run
// is refused.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "support/cli_runner.h"
#include "support/puff_sequence.h"
#include "support/temp_dir_test.h"

namespace fs = std::filesystem;

namespace obscura {
namespace {

class RenderResumeTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    testing::write_growing_puff(dir_);
    scene_ = testing::growing_puff_scene({{"method", "path-tracer"},
                                          {"seed", 5},
                                          {"samples_per_pixel", 4},
                                          {"spectral_nodes_per_band", 2}},
                                         20, 13, {"mwir", "lwir"});
    write_scene();
  }
  void write_scene() const { std::ofstream(dir_ / "scene.json") << scene_.dump(2); }

  std::string render(const fs::path& out, const std::string& times, const std::string& more = "") {
    return "render " + (dir_ / "scene.json").string() + " -o " + out.string() + " --time " + times +
           " --threads 1 " + more;
  }

  static void expect_no_temporaries(const fs::path& out) {
    for (const auto& e : fs::directory_iterator(out))
      EXPECT_NE(e.path().filename().string()[0], '.') << "temporary left: " << e.path();
  }

  nlohmann::json scene_;
};

TEST_F(RenderResumeTest, AFailedSequenceResumesFromItsFirstMissingFrameButNotAfterAnInputChanged) {
  // The keyframe at 2 s cut short: frame 0 completes, frame 1 fails.
  fs::copy_file(dir_ / "k1.vdb", dir_ / "k1.good");
  fs::resize_file(dir_ / "k1.vdb", 100);
  const auto failed = testing::run_cli(render(dir_ / "out", "0:3:1.5"), dir_);
  ASSERT_EQ(failed.status, 1) << failed.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "ir_f0000.exr"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "ir_f0001.exr"));
  // Resumed as it is: frame 0 is read back, frame 1 fails again, frame 0 stays.
  const auto again = testing::run_cli(render(dir_ / "out", "0:3:1.5", "--resume"), dir_);
  EXPECT_EQ(again.status, 1) << again.err;
  EXPECT_NE(again.err.find("obscura: resuming: 1 of 3 frames are complete"), std::string::npos)
      << again.err;
  EXPECT_NE(again.err.find("k1.vdb"), std::string::npos) << again.err;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "ir_f0000.exr"));
  expect_no_temporaries(dir_ / "out");
  // Repaired, the inputs differ from the ones frame 0 was made from: refused,
  // naming the file (a completed frame may depend on it).
  fs::remove(dir_ / "k1.vdb");
  fs::copy_file(dir_ / "k1.good", dir_ / "k1.vdb");
  const auto other = testing::run_cli(render(dir_ / "out", "0:3:1.5", "--resume"), dir_);
  EXPECT_EQ(other.status, 1) << other.err;
  EXPECT_NE(other.err.find("summary.json: /provenance/inputs: made from input files with other "
                           "contents ("),
            std::string::npos)
      << other.err;
  EXPECT_NE(other.err.find("k1.vdb)"), std::string::npos) << other.err;
}

TEST_F(RenderResumeTest, ASequenceStoppedBySigtermResumesToTheUninterruptedOutputs) {
  // Frames that take long enough (about a second each) to stop one part-way.
  scene_["sensors"][0]["width"] = 64;
  scene_["sensors"][0]["height"] = 48;
  scene_["render"]["samples_per_pixel"] = 24;
  write_scene();
  const fs::path out = dir_ / "out";
  const std::string args = render(out, "0:4:1");
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::string cmd = testing::cli_path() + " " + args + " >" +
                            (dir_ / "stdout.txt").string() + " 2>" + (dir_ / "stderr.txt").string();
    execl("/bin/sh", "sh", "-c", ("exec " + cmd).c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  // Stop it once its first frame is on disk.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!fs::exists(out / "ir_f0000.exr") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  kill(child, SIGTERM);
  int raw = 0;
  waitpid(child, &raw, 0);
  const std::string err = testing::read_text_file(dir_ / "stderr.txt");
  ASSERT_TRUE(WIFEXITED(raw)) << "ended by the signal itself, not cleanly: " << err;
  ASSERT_EQ(WEXITSTATUS(raw), 143) << err;
  EXPECT_NE(err.find("obscura: terminated (SIGTERM) (kept the"), std::string::npos) << err;
  const auto summary = nlohmann::json::parse(testing::read_text_file(out / "summary.json"));
  const std::size_t kept = summary["failed"]["frames_completed"].size();
  EXPECT_GE(kept, 1u);
  EXPECT_LT(kept, 5u) << "the run was not stopped part-way";
  expect_no_temporaries(out);

  const auto resumed = testing::run_cli(render(out, "0:4:1", "--resume"), dir_);
  ASSERT_EQ(resumed.status, 0) << resumed.err;
  EXPECT_NE(resumed.err.find("obscura: resuming: " + std::to_string(kept) + " of 5 frames"),
            std::string::npos)
      << resumed.err;
  const auto after = nlohmann::json::parse(testing::read_text_file(out / "summary.json"));
  EXPECT_FALSE(after.contains("failed"));
  EXPECT_EQ(after["resumed_frames"].size(), kept);
  ASSERT_EQ(testing::run_cli(render(dir_ / "whole", "0:4:1"), dir_).status, 0);
  testing::expect_same_render_outputs(dir_ / "whole", out);
}

TEST_F(RenderResumeTest, AResumeOfAnotherRunIsRefused) {
  ASSERT_EQ(testing::run_cli(render(dir_ / "out", "0:3:1.5"), dir_).status, 0);
  auto r = testing::run_cli(render(dir_ / "out", "0:3:1", "--resume"), dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("summary.json: /times_s: other frame times"), std::string::npos) << r.err;
  scene_["render"]["seed"] = 6;
  write_scene();
  r = testing::run_cli(render(dir_ / "out", "0:3:1.5", "--resume"), dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("summary.json: /scene: made from another scene"), std::string::npos)
      << r.err;
  r = testing::run_cli(
      "render " + (dir_ / "scene.json").string() + " -o " + (dir_ / "x").string() + " --resume",
      dir_);
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_NE(r.err.find("--resume: continues a --time sequence"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace obscura
