#pragma once
// The small animated cloud the sequence-sharing, MPI and resume tests render:
// three keyframes (0, 2, 4 s) of a 10³-voxel puff growing denser and warmer,
// with a lifecycle, in front of a warm target box on a ground; and a check
// that two render folders hold the same images and tables, bit for bit.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "obscura/io/exr_writer.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "support/cli_runner.h"

namespace obscura::testing {

// k0.vdb, k1.vdb, k2.vdb and cloud.json in `dir`.
inline void write_growing_puff(const std::filesystem::path& dir) {
  nlohmann::json frames = nlohmann::json::array();
  for (int k = 0; k < 3; ++k) {
    GaussianPuffSpec spec;
    spec.center_m = {0, 0, 3};
    spec.radius_m = 2;
    spec.resolution = 10;
    spec.wavelengths_um = {4, 10};
    spec.peak_sigma_a = {0.2 + 0.3 * k, 0.3 + 0.3 * k};
    spec.peak_sigma_s = {0.3, 0.2};
    spec.g = {0.5, 0.3};
    spec.temperature_excess_k = 10.0 * k;
    const std::string name = "k" + std::to_string(k) + ".vdb";
    write_cloud_keyframe(dir / name, make_gaussian_puff(spec), 2.0 * k);
    frames.push_back({{"file", name}, {"time", 2.0 * k}});
  }
  const nlohmann::json lifecycle = {{"init_end", 0},
                                    {"loop_start", 0},
                                    {"loop_end", 1},
                                    {"loop_wrap", 2.0},
                                    {"extinction_start", 2}};
  std::ofstream(dir / "cloud.json")
      << nlohmann::json({{"keyframes", frames}, {"lifecycle", lifecycle}}).dump();
}

// A scene of that cloud (cloud.json beside it) seen by sensor "ir".
inline nlohmann::json growing_puff_scene(const nlohmann::json& render, int width, int height,
                                         const nlohmann::json& bands) {
  return {{"sensors",
           {{{"name", "ir"},
             {"position", {0, -25, 3}},
             {"look_at", {0, 0, 3}},
             {"fov_deg", 30},
             {"width", width},
             {"height", height},
             {"bands", bands}}}},
          {"clouds", {{{"type", "animated"}, {"manifest", "cloud.json"}}}},
          {"surfaces",
           {{{"type", "ground"}, {"temperature", 290}},
            {{"type", "box"},
             {"name", "target"},
             {"min", {-1, 4, 0}},
             {"max", {1, 6, 3}},
             {"temperature", 320},
             {"target", true}}}},
          {"sky", {{"temperature", 250}}},
          {"render", render}};
}

// Every channel of every EXR in `a` equals `b`'s, and the time series and
// metrics tables are the same bytes.
inline void expect_same_render_outputs(const std::filesystem::path& a,
                                       const std::filesystem::path& b) {
  int exr = 0;
  for (const auto& entry : std::filesystem::directory_iterator(a)) {
    if (entry.path().extension() != ".exr") continue;
    ++exr;
    const ExrImage x = read_exr(entry.path()), y = read_exr(b / entry.path().filename());
    ASSERT_EQ(x.channels.size(), y.channels.size());
    for (const auto& [name, pixels] : x.channels) {
      ASSERT_TRUE(y.channels.count(name)) << name;
      EXPECT_EQ(
          0, std::memcmp(pixels.data(), y.channels.at(name).data(), pixels.size() * sizeof(float)))
          << entry.path().filename() << " " << name;
    }
  }
  EXPECT_GT(exr, 0);
  for (const char* table : {"time_series.csv", "metrics.csv"})
    EXPECT_EQ(read_text_file(a / table), read_text_file(b / table)) << table;
}

}  // namespace obscura::testing
