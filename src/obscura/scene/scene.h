#pragma once
// Everything a render needs, loaded from a scene file (docs/formats.md).
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "obscura/medium/medium.h"
#include "obscura/scene/animated_cloud.h"
#include "obscura/scene/atmosphere.h"
#include "obscura/scene/metrics_settings.h"
#include "obscura/scene/output_formats.h"
#include "obscura/scene/render_settings.h"
#include "obscura/scene/sensor.h"
#include "obscura/scene/sky.h"
#include "obscura/scene/sun.h"
#include "obscura/scene/surface.h"

namespace obscura {

// A rectangle of a sensor's pixels, [x0, x1) × [y0, y1), whose mean values are
// reported over time (regions of interest).
struct PixelRegion {
  std::string name;
  std::string sensor;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct Scene {
  std::vector<Sensor> sensors;
  // What the renderer sees: every cloud present at `time_s`, as one medium
  // (null when none is). Set by stage_scene.
  std::shared_ptr<const Medium> medium;
  double time_s = 0.0;
  std::vector<std::shared_ptr<const Medium>> static_clouds;     // present at all times
  std::vector<std::shared_ptr<AnimatedCloud>> animated_clouds;  // keyframed, with lifecycles
  std::vector<PixelRegion> regions;
  std::vector<std::unique_ptr<Surface>> surfaces;
  Sky sky;
  Sun sun;  // used by the path tracer and the photon map; the emission-absorption method refuses it
  Atmosphere atmosphere;  // between the sensor and the scene; off unless the file has one
  MetricsSettings metrics;
  RenderSettings settings;
  // Optional render outputs (the scene file's "outputs"; --format adds to them).
  std::vector<OutputFormat> outputs;
  std::vector<std::filesystem::path> input_files;  // the scene file and the files it references
  // What loading found worth saying but not refusing (a material's band with
  // extinction only, taken as absorption); render_sequence gives each once.
  std::vector<std::string> warnings;
  nlohmann::json source;  // the scene as read, for provenance
};

// Sets scene.medium to the clouds present at scene time t (s): the static
// ones and each animated cloud's interpolated state, combined when several.
void stage_scene(Scene& scene, double t);

// A surface's material from its JSON object: "temperature" (K) and
// "emissivity", a number in [0, 1] (default 1) or a table of
// [wavelength_um, emissivity] points. Throws InputError naming the JSON path.
class JsonObject;
SurfaceMaterial parse_surface_material(JsonObject& o);

// Loads and validates a scene file, staged at time 0; relative paths inside it are relative to
// the file's folder. Throws InputError naming the file and JSON path.
Scene load_scene(const std::filesystem::path& path);
// The same from an already-parsed document (`file` names it in errors).
Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& file);

}  // namespace obscura
