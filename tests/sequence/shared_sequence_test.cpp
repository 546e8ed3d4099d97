// A sequence shared among processes (sequence_runner.h, "Shared among
// processes"): by frames and by tiles (rows and photon chunks), on 2 and 3
// ranks, rank 0 gets every frame in order, bit for bit what one process
// renders, and the same time series and screening metrics. The ranks are
// threads here (support/thread_process_group.h); the mpirun CLI tests run the
// same paths over MPI.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <mutex>
#include <nlohmann/json.hpp>

#include "obscura/sequence/sequence_runner.h"
#include "support/puff_sequence.h"
#include "support/temp_dir_test.h"
#include "support/thread_process_group.h"

namespace obscura {
namespace {

class SharedSequenceTest : public testing::TempDirTest {
 protected:
  void SetUp() override {
    TempDirTest::SetUp();
    testing::write_growing_puff(dir_);
  }

  // The scene, one per rank (each process loads its own).
  Scene scene(const std::string& method) const {
    nlohmann::json render = {
        {"method", method}, {"seed", 7}, {"threads", 1}, {"spectral_nodes_per_band", 2}};
    if (method == "radiance-cache") render["radiance_cache"] = {{"photons", 4000}};
    if (method == "photonmap") render["photon_map"] = {{"photons", 3000}};
    if (method == "path-tracer") render["samples_per_pixel"] = 2;
    nlohmann::json doc = testing::growing_puff_scene(render, 16, 11, {"lwir"});
    // A sun for the methods that take one: its shadow through the cloud is
    // shared by lattice block in the radiance cache.
    if (method != "emission-absorption") doc["sun"] = {{"azimuth_deg", 225}, {"elevation_deg", 35}};
    return parse_scene(doc, dir_ / "scene.json");
  }

  struct Run {
    std::vector<RenderedFrame> frames;
    SequenceResult result;
  };

  Run run(const std::string& method, const ProcessGroup& group, WorkSharing sharing) const {
    Run out;
    Scene s = scene(method);
    SequenceOptions options;
    options.processes = &group;
    options.sharing = sharing;
    options.on_frame = [&](const RenderedFrame& f) { out.frames.push_back(f); };
    out.result = render_sequence(s, times_, options);
    return out;
  }

  static void expect_same_images(const Run& a, const Run& b, const std::string& what) {
    ASSERT_EQ(a.frames.size(), b.frames.size()) << what;
    for (std::size_t f = 0; f < a.frames.size(); ++f) {
      EXPECT_EQ(a.frames[f].index, f) << what;
      const SensorImage &x = a.frames[f].images.at(0), &y = b.frames[f].images.at(0);
      for (std::size_t b2 = 0; b2 < x.bands.size(); ++b2) {
        const auto same = [](const std::vector<float>& p, const std::vector<float>& q) {
          return p.size() == q.size() &&
                 std::memcmp(p.data(), q.data(), p.size() * sizeof(float)) == 0;
        };
        EXPECT_TRUE(same(x.bands[b2].radiance, y.bands[b2].radiance)) << what << " frame " << f;
        EXPECT_TRUE(same(x.bands[b2].transmittance, y.bands[b2].transmittance)) << what;
        EXPECT_TRUE(same(x.bands[b2].apparent_temperature, y.bands[b2].apparent_temperature))
            << what;
        EXPECT_TRUE(same(x.bands[b2].radiance_stderr, y.bands[b2].radiance_stderr)) << what;
      }
      EXPECT_EQ(x.samples_per_pixel, y.samples_per_pixel) << what;
      EXPECT_EQ(x.stats.rays, y.stats.rays) << what << ": rays summed over ranks";
    }
    ASSERT_EQ(a.result.metrics.size(), b.result.metrics.size()) << what;
    for (std::size_t i = 0; i < a.result.metrics.size(); ++i)
      EXPECT_EQ(a.result.metrics[i].transmittance_mean, b.result.metrics[i].transmittance_mean)
          << what;
    ASSERT_EQ(a.result.time_series.size(), b.result.time_series.size()) << what;
    for (std::size_t i = 0; i < a.result.time_series.size(); ++i)
      EXPECT_EQ(a.result.time_series[i].stats.mean_radiance,
                b.result.time_series[i].stats.mean_radiance)
          << what;
  }

  void check(const std::string& method, int ranks, WorkSharing sharing) const {
    const Run alone = run(method, single_process(), WorkSharing::kAuto);
    ASSERT_EQ(alone.frames.size(), times_.size());
    std::mutex m;
    Run root;
    std::size_t frames_elsewhere = 0;
    testing::run_ranks(ranks, [&](const ProcessGroup& g) {
      Run r = run(method, g, sharing);
      std::lock_guard lock(m);
      if (g.is_root())
        root = std::move(r);
      else
        frames_elsewhere += r.frames.size() + r.result.metrics.size();
    });
    EXPECT_EQ(frames_elsewhere, 0u) << "only rank 0 gets frames and measures them";
    expect_same_images(
        alone, root,
        method + " on " + std::to_string(ranks) + " ranks by " + work_sharing_name(sharing));
  }

  std::vector<double> times_{0.0, 1.5, 3.0};
};

TEST_F(SharedSequenceTest, FramesSharedAmongRanksAreTheSingleProcessFrames) {
  check("emission-absorption", 2, WorkSharing::kFrames);
  check("emission-absorption", 3, WorkSharing::kFrames);
  check("radiance-cache", 2, WorkSharing::kFrames);
}

TEST_F(SharedSequenceTest, TilesAndPhotonsSharedAmongRanksAreTheSingleProcessFrames) {
  check("emission-absorption", 2, WorkSharing::kTiles);
  check("radiance-cache", 3, WorkSharing::kTiles);
  check("photonmap", 2, WorkSharing::kTiles);
  check("path-tracer", 3, WorkSharing::kTiles);
}

TEST_F(SharedSequenceTest, AutoSharesByTilesWhenThereAreFewerFramesThanRanks) {
  times_ = {1.5};
  check("radiance-cache", 2, WorkSharing::kAuto);
}

TEST_F(SharedSequenceTest, AFrameFailingOnOneRankEndsTheRunAfterTheFramesBeforeIt) {
  // The second keyframe is cut short: frames at 1.5 s and 3 s cannot be staged.
  std::filesystem::resize_file(dir_ / "k1.vdb", 100);
  std::mutex m;
  std::vector<std::size_t> root_frames;
  int root_errors = 0, peer_failures = 0;
  testing::run_ranks(2, [&](const ProcessGroup& g) {
    Scene s = scene("emission-absorption");
    SequenceOptions options;
    options.processes = &g;
    options.sharing = WorkSharing::kFrames;
    options.on_frame = [&](const RenderedFrame& f) {
      std::lock_guard lock(m);
      root_frames.push_back(f.index);
    };
    try {
      render_sequence(s, times_, options);
    } catch (const PeerFailure&) {
      std::lock_guard lock(m);
      ++peer_failures;
    } catch (const InputError& e) {
      std::lock_guard lock(m);
      EXPECT_NE(std::string(e.what()).find("k1.vdb"), std::string::npos) << e.what();
      // Whichever rank drew frame 1 met it; another rank's error says which.
      ++root_errors;
    }
  });
  EXPECT_EQ(root_frames, std::vector<std::size_t>{0}) << "frame 0 (t = 0 s) came before";
  EXPECT_EQ(root_errors, 1);
  EXPECT_EQ(peer_failures, 1);
}

}  // namespace
}  // namespace obscura
