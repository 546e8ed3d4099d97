// Scene files: JSON documents described in docs/formats.md. Every value is
// checked where it is read, errors name the file and the JSON path, and a key
// that nothing reads is an error (a typo must not pass silently).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>
#include <set>

#include "obscura/core/memory_limit.h"
#include "obscura/io/cloud_manifest.h"
#include "obscura/io/json_reader.h"
#include "obscura/io/obj_mesh.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/composite_medium.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/scene/environment_loader.h"
#include "obscura/scene/heightfield.h"
#include "obscura/scene/mesh_surface.h"
#include "obscura/scene/scene.h"
#include "obscura/scene/vdb_density_cloud.h"

namespace obscura {

SurfaceMaterial parse_surface_material(JsonObject& o) {
  SurfaceMaterial m;
  m.temperature_k = o.number("temperature");
  if (!(m.temperature_k >= 0)) throw o.error("temperature", "must be >= 0 K");
  if (o.has("emissivity") && o.raw("emissivity").is_array()) {
    // A table of [wavelength_um, emissivity] points.
    const auto& arr = o.array("emissivity");
    if (arr.empty())
      throw o.error("emissivity",
                    "the table is empty (expected [[wavelength_um, emissivity], ...])");
    std::vector<double> wavelengths, values;
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const auto& p = arr[i];
      const std::string at = fmt::format("emissivity/{}", i);
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw o.error(at, "expected [wavelength_um, emissivity]");
      const double wl = p[0].get<double>(), e = p[1].get<double>();
      if (!(wl > 0 && std::isfinite(wl))) throw o.error(at, "the wavelength must be > 0 µm");
      if (!wavelengths.empty() && !(wl > wavelengths.back()))
        throw o.error(at, "wavelengths must increase strictly");
      if (!(e >= 0 && e <= 1)) throw o.error(at, "the emissivity must lie in [0, 1]");
      wavelengths.push_back(wl);
      values.push_back(e);
    }
    m.emissivity_table = TabulatedSpectrum(std::move(wavelengths), std::move(values));
  } else {
    m.emissivity = o.number_or("emissivity", 1.0);
    if (!(m.emissivity >= 0 && m.emissivity <= 1))
      throw o.error("emissivity", "must lie in [0, 1]");
  }
  return m;
}

namespace {

// A file named by `key`, relative to the scene's folder unless absolute; it
// must exist, and is recorded among the scene's inputs (provenance).
std::filesystem::path input_file(JsonObject& o, const std::string& key,
                                 const std::filesystem::path& base, const char* what,
                                 Scene& scene) {
  std::filesystem::path file = o.string(key);
  if (file.is_relative()) file = base / file;
  if (std::filesystem::is_directory(file))
    throw o.error(key, fmt::format("'{}' is a folder, expected a {} file", file.string(), what));
  if (!std::filesystem::is_regular_file(file))
    throw o.error(key, fmt::format("cannot open {} '{}': no such file", what, file.string()));
  scene.input_files.push_back(file);
  return file;
}

// A MeshSurface, with Embree's rare failures (out of memory) named at the surface.
std::unique_ptr<Surface> mesh_surface(JsonObject& o, const std::string& name,
                                      const SurfaceMaterial& m, const TriangleMesh& mesh,
                                      bool target) {
  try {
    auto s = std::make_unique<MeshSurface>(name, m, mesh);
    s->set_target(target);
    return s;
  } catch (const Error& e) {
    throw o.error("file", e.what());
  }
}

// {"type": "mesh", "file": OBJ, "position", "heading_deg", "scale", "target",
//  default "temperature"/"emissivity", "parts": {name: material}}: one
// MeshSurface per part of the OBJ, named "<name>/<part>".
void parse_mesh(JsonObject& o, const std::string& name, const std::filesystem::path& base,
                Scene& scene) {
  const std::filesystem::path file = input_file(o, "file", base, "mesh", scene);
  TriangleMesh mesh = read_obj_mesh(file);
  mesh.scale(o.positive_or("scale", 1.0));
  mesh.rotate_heading_deg(o.number_or("heading_deg", 0.0));
  mesh.translate(o.vec3_or("position", Vec3(0, 0, 0)));
  const bool target = o.boolean_or("target", false);
  std::optional<SurfaceMaterial> defaults;
  if (o.has("temperature"))
    defaults = parse_surface_material(o);
  else if (o.has("emissivity"))
    throw o.error("emissivity",
                  "give \"temperature\" with it (the default material of every part)");
  std::vector<std::optional<SurfaceMaterial>> materials(mesh.part_names.size(), defaults);
  if (o.has("parts")) {
    const auto& entries = o.raw("parts");
    JsonObject parts = o.object("parts");
    for (const auto& [part, value] : entries.items()) {
      const int index = mesh.find_part(part);
      if (index < 0)
        throw parts.error(part, fmt::format("no part '{}' in {} (its parts: {})", part,
                                            file.string(), fmt::join(mesh.part_names, ", ")));
      JsonObject entry = parts.object(part);
      materials[index] = parse_surface_material(entry);
      entry.finish();
    }
  }
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p)
    if (!materials[p])
      throw o.error("temperature",
                    fmt::format("part '{}' has no material: give a default \"temperature\" or "
                                "an entry for it under \"parts\"",
                                mesh.part_names[p]));
  o.finish();
  for (std::size_t p = 0; p < mesh.part_names.size(); ++p)
    scene.surfaces.push_back(
        mesh_surface(o, name + "/" + mesh.part_names[p], *materials[p], mesh.part(p), target));
}

// {"type": "heightfield", "file": CSV, "origin": [x0, y0], "spacing_m", material, "target"}.
void parse_heightfield(JsonObject& o, const std::string& name, const std::filesystem::path& base,
                       Scene& scene) {
  const std::filesystem::path file = input_file(o, "file", base, "heightfield", scene);
  const std::vector<double> origin = o.numbers("origin");
  if (origin.size() != 2)
    throw o.error("origin", "expected [x0, y0] (m): where the first sample of the first row lies");
  const double spacing = o.positive("spacing_m");
  const SurfaceMaterial m = parse_surface_material(o);
  const bool target = o.boolean_or("target", false);
  o.finish();
  const Heightfield h = read_heightfield_csv(file);
  std::unique_ptr<Surface> s =
      mesh_surface(o, name, m, heightfield_mesh(h, origin[0], origin[1], spacing, name), target);
  s->set_terrain(true);
  scene.surfaces.push_back(std::move(s));
}

// One entry of "/surfaces": one Surface, or one per part of a mesh.
void parse_surfaces(JsonObject o, int index, const std::filesystem::path& base, Scene& scene) {
  const std::string type = o.string("type");
  const std::string name = o.string_or("name", fmt::format("{}{}", type, index));
  if (type == "mesh") return parse_mesh(o, name, base, scene);
  if (type == "heightfield") return parse_heightfield(o, name, base, scene);
  const SurfaceMaterial m = parse_surface_material(o);
  const bool target = o.boolean_or("target", false);
  std::unique_ptr<Surface> s;
  if (type == "ground") {
    s = std::make_unique<GroundPlane>(name, m, o.number_or("height", 0.0));
  } else if (type == "box") {
    const Vec3 lo = o.vec3("min"), hi = o.vec3("max");
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
      throw o.error("max", "every component must exceed the corresponding one of min");
    s = std::make_unique<BoxSurface>(name, m, BBox3(lo, hi));
  } else {
    throw o.error("type", fmt::format("unknown surface type '{}' (expected ground, box, mesh or "
                                      "heightfield)",
                                      type));
  }
  s->set_target(target);
  o.finish();
  scene.surfaces.push_back(std::move(s));
}

Band parse_band(const nlohmann::json& v, const std::string& file, const std::string& path) {
  if (v.is_string()) {
    try {
      return Band::parse(v.get<std::string>(), path);
    } catch (const InputError& e) {
      throw InputError(file, path, e.detail());
    }
  }
  JsonObject o(v, file, path);
  const std::string name = o.string("name");
  std::vector<ResponsePoint> table;
  if (o.has("response")) {
    const auto& arr = o.array("response");
    for (std::size_t i = 0; i < arr.size(); ++i) {
      const auto& p = arr[i];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
        throw InputError(file, fmt::format("{}/response/{}", path, i),
                         "expected [wavelength_um, response]");
      table.push_back({p[0].get<double>(), p[1].get<double>()});
    }
  } else {
    const double lo = o.positive("min_um"), hi = o.positive("max_um");
    if (!(hi > lo)) throw o.error("max_um", "must exceed min_um");
    table = {{lo, 1.0}, {hi, 1.0}};
  }
  o.finish();
  try {
    return Band::tabulated(name, std::move(table));
  } catch (const InputError& e) {
    throw InputError(file, path + "/response", e.detail());
  }
}

Sensor parse_sensor(JsonObject o, int index) {
  Sensor s;
  s.name = o.string_or("name", fmt::format("sensor{}", index));
  if (s.name.empty() || s.name.find_first_of("/\\ ") != std::string::npos)
    throw o.error("name", "must be non-empty without spaces or slashes (it names output files)");
  const Vec3 position = o.vec3("position");
  const Vec3 look_at = o.vec3("look_at");
  const Vec3 up = o.vec3_or("up", Vec3(0, 0, 1));
  const double fov = o.number("fov_deg");
  if (!(fov > 0 && fov < 180)) throw o.error("fov_deg", "must lie in (0, 180) degrees");
  const long long w = o.integer("width"), h = o.integer("height");
  if (w < 1 || w > kMaxImageSide)
    throw o.error("width", fmt::format("must lie in [1, {}]", kMaxImageSide));
  if (h < 1 || h > kMaxImageSide)
    throw o.error("height", fmt::format("must lie in [1, {}]", kMaxImageSide));
  try {
    s.camera = PinholeCamera(position, look_at, up, fov, static_cast<int>(w), static_cast<int>(h));
  } catch (const Error& e) {
    throw o.error("look_at", e.what());
  }
  const auto& bands = o.array("bands");
  if (bands.empty()) throw o.error("bands", "needs at least one band");
  std::set<std::string> names;
  for (std::size_t i = 0; i < bands.size(); ++i) {
    const std::string path = fmt::format("{}/{}", o.path_of("bands"), i);
    s.bands.push_back(parse_band(bands[i], o.file(), path));
    if (!names.insert(s.bands.back().name()).second)
      throw InputError(o.file(), path,
                       fmt::format("duplicate band name '{}'", s.bands.back().name()));
  }
  // The images the render fills (film/sensor_image.h): per band radiance,
  // transmittance, apparent temperature and standard error, and the samples
  // per pixel; 16384² × 64 bands took 7.4 GB before failing in bad_alloc.
  const auto bytes = checked_product({static_cast<std::uint64_t>(w), static_cast<std::uint64_t>(h),
                                      4 * sizeof(float) * s.bands.size() + sizeof(std::uint32_t)});
  check_memory(bytes.value_or(UINT64_MAX), o.file(), o.path_of("bands"),
               fmt::format("a {}x{} image with {} bands", w, h, s.bands.size()));
  o.finish();
  return s;
}

void parse_cloud(JsonObject o, const std::filesystem::path& base, Scene& scene, int index) {
  std::vector<std::filesystem::path>& inputs = scene.input_files;
  const std::string type = o.string("type");
  std::shared_ptr<const Medium> m;
  if (type == "animated") {
    const std::filesystem::path file = input_file(o, "manifest", base, "cloud manifest", scene);
    CloudManifest manifest = read_cloud_manifest(file);
    for (const auto& k : manifest.keyframes) inputs.push_back(k.file);
    const AnimatedCloudKeys keys = read_animated_cloud_keys(o, index);
    o.finish();
    scene.animated_clouds.push_back(
        std::make_shared<AnimatedCloud>(keys.name, std::move(manifest), keys.activation_s,
                                        keys.deactivation_s, keys.cache_keyframes));
    return;
  }
  if (type == "vdb-density") return parse_vdb_density_cloud(o, base, scene, index);
  if (type == "vdb") {
    const std::filesystem::path file = input_file(o, "file", base, "cloud keyframe", scene);
    CloudKeyframe kf = read_cloud_keyframe(file);
    m = std::make_shared<GridMedium>(kf.grid);
  } else if (type == "homogeneous") {
    const Vec3 lo = o.vec3("min"), hi = o.vec3("max");
    if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
      throw o.error("max", "every component must exceed the corresponding one of min");
    auto wl = o.numbers("wavelengths_um");
    auto sa = o.numbers("sigma_a");
    auto ss = o.numbers("sigma_s");
    auto g = o.has("g") ? o.numbers("g") : std::vector<double>(wl.size(), 0.0);
    const double t = o.number("temperature");
    try {
      m = std::make_shared<HomogeneousMedium>(BBox3(lo, hi), wl, sa, ss, g, t, "");
    } catch (const InputError& e) {
      throw o.error(e.field(), e.detail());
    }
  } else {
    throw o.error(
        "type",
        fmt::format("unknown cloud type '{}' (expected vdb, vdb-density, homogeneous or animated)",
                    type));
  }
  o.finish();
  scene.static_clouds.push_back(std::move(m));
}

PixelRegion parse_region(JsonObject o, const Scene& scene) {
  PixelRegion r;
  r.name = o.string("name");
  r.sensor = o.string("sensor");
  const Sensor* sensor = nullptr;
  for (const auto& s : scene.sensors)
    if (s.name == r.sensor) sensor = &s;
  if (!sensor) throw o.error("sensor", fmt::format("no sensor named '{}'", r.sensor));
  const auto px = o.numbers("pixels");
  if (px.size() != 4)
    throw o.error("pixels", "expected [x0, y0, x1, y1] (pixels, x1 and y1 excluded)");
  for (double v : px)
    if (v != std::floor(v)) throw o.error("pixels", "pixel coordinates must be whole numbers");
  r.x0 = static_cast<int>(px[0]);
  r.y0 = static_cast<int>(px[1]);
  r.x1 = static_cast<int>(px[2]);
  r.y1 = static_cast<int>(px[3]);
  if (!(0 <= r.x0 && r.x0 < r.x1 && r.x1 <= sensor->camera.width() && 0 <= r.y0 && r.y0 < r.y1 &&
        r.y1 <= sensor->camera.height()))
    throw o.error("pixels", fmt::format("[{}, {}, {}, {}] is not a non-empty rectangle inside the "
                                        "{}x{} image",
                                        r.x0, r.y0, r.x1, r.y1, sensor->camera.width(),
                                        sensor->camera.height()));
  o.finish();
  return r;
}

// A photon map stores at least one photon per launched photon that meets the
// cloud, 28 bytes each (render/photon_map/photon.h), for every spectral node
// of every band of every sensor: refuse a count that cannot fit before tracing.
void check_photon_memory(const Scene& scene, const JsonObject& root) {
  if (scene.settings.method != RenderMethod::kPhotonMap) return;
  constexpr std::uint64_t kPhotonBytes = 28;
  std::uint64_t bands = 0, nodes = 0;
  for (const Sensor& s : scene.sensors)
    for (const Band& band : s.bands) {
      ++bands;
      nodes += static_cast<std::uint64_t>(scene.settings.spectral_nodes(band));
    }
  const auto bytes =
      checked_product({static_cast<std::uint64_t>(scene.settings.photon_map.photons_per_node),
                       nodes, kPhotonBytes});
  check_memory(bytes.value_or(UINT64_MAX), root.file(), "/render/photon_map/photons",
               fmt::format("{} photons per node over {} spectral nodes in {} bands (28 bytes per "
                           "stored photon)",
                           scene.settings.photon_map.photons_per_node, nodes, bands));
}

// Every band that /render/radiance_cache/photons or
// /render/spectral_nodes_per_band names is a band of some sensor: a setting
// for a band nobody renders is a typo or a stale scene.
void check_bands_named(const Scene& scene, const std::string& file) {
  std::vector<std::string> names;  // the sensors' bands, in order, once each
  for (const Sensor& s : scene.sensors)
    for (const Band& b : s.bands)
      if (std::find(names.begin(), names.end(), b.name()) == names.end()) names.push_back(b.name());
  auto check = [&](const auto& by_band, const std::string& field) {
    for (const auto& [band, value] : by_band)
      if (std::find(names.begin(), names.end(), band) == names.end())
        throw InputError(file, field + "/" + band,
                         fmt::format("no sensor renders a band '{}' (the sensors' bands: {}; "
                                     "\"*\" for all others)",
                                     band, fmt::join(names, ", ")));
  };
  check(scene.settings.radiance_cache.photons_by_band, "/render/radiance_cache/photons");
  check(scene.settings.spectral_nodes_by_band, "/render/spectral_nodes_per_band");
}

}  // namespace

Scene parse_scene(const nlohmann::json& doc, const std::filesystem::path& file) {
  const std::string fname = file.string();
  const std::filesystem::path base = file.has_parent_path() ? file.parent_path() : ".";
  JsonObject root(doc, fname, "");
  Scene scene;
  scene.source = doc;
  // First: every size below is checked against it. --max-memory, set before
  // the scene is read, wins (core/memory_limit.h).
  if (root.has("max_memory")) {
    const std::string text = root.string("max_memory");
    const auto bytes = parse_memory_size(text);
    if (!bytes)
      throw root.error("max_memory",
                       fmt::format("'{}' is not a memory size (expected e.g. \"4GiB\" or "
                                   "\"500MB\")",
                                   text));
    set_memory_limit(*bytes, MemoryLimitSource::kScene);
  }

  const auto& sensors = root.array("sensors");
  if (sensors.empty()) throw root.error("sensors", "needs at least one sensor");
  std::set<std::string> sensor_names;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    scene.sensors.push_back(parse_sensor(
        JsonObject(sensors[i], fname, fmt::format("/sensors/{}", i)), static_cast<int>(i)));
    if (!sensor_names.insert(scene.sensors.back().name).second)
      throw InputError(fname, fmt::format("/sensors/{}/name", i), "duplicate sensor name");
  }

  if (root.has("clouds")) {
    const auto& clouds = root.array("clouds");
    for (std::size_t i = 0; i < clouds.size(); ++i)
      parse_cloud(JsonObject(clouds[i], fname, fmt::format("/clouds/{}", i)), base, scene,
                  static_cast<int>(i));
    // Static clouds must share their wavelengths: check now, naming the scene
    // (animated clouds are checked when staged, as their keyframes are read then).
    if (scene.static_clouds.size() > 1) CompositeMedium check(scene.static_clouds, fname);
  }

  if (root.has("regions")) {
    const auto& regions = root.array("regions");
    for (std::size_t i = 0; i < regions.size(); ++i)
      scene.regions.push_back(
          parse_region(JsonObject(regions[i], fname, fmt::format("/regions/{}", i)), scene));
  }

  if (root.has("surfaces")) {
    const auto& surfaces = root.array("surfaces");
    for (std::size_t i = 0; i < surfaces.size(); ++i)
      parse_surfaces(JsonObject(surfaces[i], fname, fmt::format("/surfaces/{}", i)),
                     static_cast<int>(i), base, scene);
  }

  if (auto sky = root.optional_object("sky")) scene.sky = parse_sky(*sky);

  if (auto atm = root.optional_object("atmosphere"))
    scene.atmosphere = parse_atmosphere(*atm, scene.sensors);
  if (auto m = root.optional_object("metrics")) scene.metrics = parse_metrics_settings(*m);
  if (auto sun = root.optional_object("sun")) scene.sun = parse_sun(*sun);
  if (auto r = root.optional_object("render")) scene.settings = parse_render_settings(*r);
  check_bands_named(scene, fname);
  scene.outputs = parse_output_formats(root);
  check_photon_memory(scene, root);
  if (scene.sun.enabled && !method_scatters(scene.settings.method))
    throw root.error(
        "sun",
        "the sun lights clouds through scattering: set /render/method to "
        "\"path-tracer\" or \"photonmap\" (emission-absorption has no scattering source)");
  root.string_or("description", "");
  root.finish();
  stage_scene(scene, 0.0);
  return scene;
}

void stage_scene(Scene& scene, double t) {
  std::vector<std::shared_ptr<const Medium>> present = scene.static_clouds;
  for (auto& cloud : scene.animated_clouds)
    if (auto m = cloud->stage(t)) present.push_back(std::move(m));
  scene.time_s = t;
  if (present.empty())
    scene.medium = nullptr;
  else if (present.size() == 1)
    scene.medium = present.front();
  else
    scene.medium = std::make_shared<CompositeMedium>(std::move(present));
}

Scene load_scene(const std::filesystem::path& path) {
  const nlohmann::json doc = read_json_file(path.string());
  Scene scene = parse_scene(doc, path);
  scene.input_files.insert(scene.input_files.begin(), path);
  return scene;
}

}  // namespace obscura
