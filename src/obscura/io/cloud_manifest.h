#pragma once
// The manifest of a time-varying cloud (JSON): its keyframe files with their
// times, the lifecycle that plays them and the trajectory that moves them
// (docs/time-varying-clouds.md, "Manifest"). Reading it checks that every
// keyframe file exists but opens none: keyframes are read on demand.
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "obscura/medium/lifecycle.h"
#include "obscura/medium/trajectory.h"

namespace obscura {

struct ManifestKeyframe {
  std::filesystem::path file;  // resolved relative to the manifest's folder
  double time_s = 0;           // seconds after the cloud's activation
};

struct CloudManifest {
  std::filesystem::path source;  // the manifest file
  std::vector<ManifestKeyframe> keyframes;
  Lifecycle lifecycle;
  Trajectory trajectory;
};

// Reads, parses and validates a manifest; throws InputError naming the file
// and the JSON path ("/lifecycle/loop_end", "/keyframes/2/file", ...).
CloudManifest read_cloud_manifest(const std::filesystem::path& path);

// Parses an already-read document; `path` names it in errors and its folder is
// the base of relative keyframe paths.
CloudManifest parse_cloud_manifest(const nlohmann::json& doc, const std::filesystem::path& path);

}  // namespace obscura
