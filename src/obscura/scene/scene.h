#pragma once
// Everything a render needs, loaded from a scene file (docs/formats.md).
#include <filesystem>
#include <memory>
#include <vector>

#include <nlohmann/json.hpp>

#include "obscura/medium/medium.h"
#include "obscura/scene/render_settings.h"
#include "obscura/scene/sensor.h"
#include "obscura/scene/sky.h"
#include "obscura/scene/surface.h"

namespace obscura {

struct Scene {
  std::vector<Sensor> sensors;
  std::shared_ptr<const Medium> medium;  // null when the scene has no cloud
  std::vector<std::unique_ptr<Surface>> surfaces;
  UniformSky sky;
  RenderSettings settings;
  std::vector<std::filesystem::path> input_files;  // the scene file and the files it references
  nlohmann::json source;                           // the scene as read, for provenance
};

// Loads and validates a scene file; relative paths inside it are relative to
// the file's folder. Throws InputError naming the file and JSON path.
Scene load_scene(const std::filesystem::path& path);
// The same from an already-parsed document (`file` names it in errors).
Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& file);

}  // namespace obscura
