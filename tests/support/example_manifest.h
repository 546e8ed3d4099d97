#pragma once
// The example cloud manifest of docs/time-varying-clouds.md: 11 keyframes 1 s
// apart (init_end 3, loop 4–7 with a 1 s wrap, extinction from 8) and a
// two-key trajectory. Its keyframe files are written empty: reading a manifest
// only checks that they exist, and the tests that use this fixture exercise
// the time logic, never the voxel data.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace obscura::testing {

inline std::string example_keyframe_name(int k) {
  char name[16];
  std::snprintf(name, sizeof name, "k%03d.vdb", k);
  return name;
}

// Writes the empty keyframe files into `dir` and returns the manifest (with
// zero drift; tests set their own).
inline nlohmann::json write_example_manifest_keyframes(const std::filesystem::path& dir) {
  nlohmann::json frames = nlohmann::json::array();
  for (int k = 0; k <= 10; ++k) {
    std::ofstream(dir / example_keyframe_name(k));  // exists, never read
    frames.push_back({{"file", example_keyframe_name(k)}, {"time", 1.0 * k}});
  }
  return {{"keyframes", frames},
          {"lifecycle",
           {{"init_end", 3},
            {"loop_start", 4},
            {"loop_end", 7},
            {"loop_wrap", 1.0},
            {"extinction_start", 8}}},
          {"trajectory",
           {{"keys",
             {{{"time", 0.0}, {"position", {0, 0, 0}}, {"heading_deg", 0}},
              {{"time", 10.0}, {"position", {100, 0, 0}}, {"heading_deg", 90}}}},
            {"interpolation", "linear"},
            {"drift_velocity", {0, 0, 0}}}}};
}

}  // namespace obscura::testing
