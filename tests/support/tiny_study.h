#pragma once
// The small parameter study the study tests run: the smoke-screen example cut
// down to two grenades, 2 m voxels, two wavelengths and 8 s, seen by the
// seeker at 48 × 24 px in the LWIR with the tank a target; axes wind
// direction (250°, 290°) and stability (B, F). Writes prepare.json and
// scene.json into `dir` and returns the study document (not yet written).
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "obscura/io/json_reader.h"

namespace obscura::testing {

inline nlohmann::json write_tiny_study(const std::filesystem::path& dir) {
  const std::string examples = std::string(OBSCURA_SOURCE_DIR) + "/examples/smoke-screen/";
  nlohmann::json prepare = read_json_file(examples + "prepare.json");
  auto& devices = prepare["dispersion"]["devices"];
  devices = nlohmann::json::array({devices[3], devices[4]});
  prepare["times_s"] = {{"start", 0}, {"end", 8}, {"step", 2}};
  prepare["voxel_size_m"] = 2.0;
  prepare["wavelengths_um"] = {4.0, 10.0};
  std::ofstream(dir / "prepare.json") << prepare.dump(2);
  nlohmann::json scene = read_json_file(examples + "scene.json");
  scene["sensors"][0]["width"] = 48;
  scene["sensors"][0]["height"] = 24;
  scene["sensors"][0]["bands"] = {"lwir"};
  scene["surfaces"][1]["target"] = true;
  scene.erase("regions");
  std::ofstream(dir / "scene.json") << scene.dump(2);
  return {{"prepare", "prepare.json"},
          {"scene", "scene.json"},
          {"times_s", {{"start", 0}, {"end", 8}, {"step", 2}}},
          {"axes",
           {{{"name", "wind_from_deg"},
             {"file", "prepare"},
             {"path", "/dispersion/wind/from_deg"},
             {"values", {250, 290}}},
            {{"name", "stability"},
             {"file", "prepare"},
             {"path", "/dispersion/stability"},
             {"values", {"B", "F"}}}}}};
}

}  // namespace obscura::testing
