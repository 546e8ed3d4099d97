#include "obscura/io/cloud_manifest.h"

#include <fmt/format.h>

#include <limits>

#include "obscura/io/json_reader.h"

namespace obscura {

namespace {

// A keyframe index: an integer that fits in an int (range checks against the
// keyframe count are the Lifecycle's).
int keyframe_index(JsonObject& o, const std::string& key) {
  const long long v = o.integer(key);
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    throw o.error(key, fmt::format("keyframe index {} out of range", v));
  return static_cast<int>(v);
}

// Lifecycle and Trajectory name fields relative to the manifest's root
// ("lifecycle/loop_end"); errors from them become JSON paths.
template <typename F>
auto rooted(const std::string& file, F&& make) {
  try {
    return make();
  } catch (const InputError& e) {
    throw InputError(file, "/" + e.field(), e.detail());
  }
}

std::vector<ManifestKeyframe> parse_keyframes(JsonObject& root, const std::filesystem::path& base) {
  const std::string file = root.file();
  const auto& array = root.array("keyframes");
  if (array.empty()) throw root.error("keyframes", "a cloud needs at least one keyframe");
  std::vector<ManifestKeyframe> out;
  for (std::size_t i = 0; i < array.size(); ++i) {
    JsonObject k(array[i], file, fmt::format("{}/{}", root.path_of("keyframes"), i));
    ManifestKeyframe kf;
    const std::string name = k.string("file");
    if (name.empty()) throw k.error("file", "empty file name");
    kf.file = std::filesystem::path(name);
    if (kf.file.is_relative()) kf.file = base / kf.file;
    kf.time_s = k.number("time");
    if (kf.time_s < 0) throw k.error("time", fmt::format("must be >= 0 s, found {}", kf.time_s));
    if (!out.empty() && !(kf.time_s > out.back().time_s))
      throw k.error("time", fmt::format("keyframe times must increase strictly: {} s follows {} s",
                                        kf.time_s, out.back().time_s));
    k.finish();
    // Existence only: the file is opened when the keyframe is first needed.
    std::error_code ec;
    if (!std::filesystem::is_regular_file(kf.file, ec))
      throw k.error("file", fmt::format("keyframe file '{}' does not exist", kf.file.string()));
    out.push_back(std::move(kf));
  }
  return out;
}

LifecycleSpec parse_lifecycle(JsonObject o) {
  LifecycleSpec spec;
  spec.init_end = keyframe_index(o, "init_end");
  spec.loop_start = keyframe_index(o, "loop_start");
  spec.loop_end = keyframe_index(o, "loop_end");
  spec.loop_wrap_s = o.number("loop_wrap");
  spec.extinction_start = keyframe_index(o, "extinction_start");
  o.finish();
  return spec;
}

Trajectory parse_trajectory(JsonObject o) {
  std::vector<TrajectoryKey> keys;
  if (o.has("keys")) {
    const auto& array = o.array("keys");
    for (std::size_t i = 0; i < array.size(); ++i) {
      JsonObject k(array[i], o.file(), fmt::format("{}/{}", o.path_of("keys"), i));
      TrajectoryKey key;
      key.time_s = k.number("time");
      key.position_m = k.vec3("position");
      key.heading_deg = k.number_or("heading_deg", 0.0);
      k.finish();
      keys.push_back(key);
    }
  }
  const std::string mode = o.string_or("interpolation", "linear");
  TrajectoryInterpolation interpolation;
  if (mode == "linear") {
    interpolation = TrajectoryInterpolation::kLinear;
  } else if (mode == "catmull-rom") {
    interpolation = TrajectoryInterpolation::kCatmullRom;
  } else {
    throw o.error("interpolation",
                  fmt::format("unknown interpolation '{}' (expected linear or catmull-rom)", mode));
  }
  const Vec3 drift = o.vec3_or("drift_velocity", {0, 0, 0});
  o.finish();
  return rooted(o.file(),
                [&] { return Trajectory(std::move(keys), interpolation, drift, o.file()); });
}

}  // namespace

CloudManifest parse_cloud_manifest(const nlohmann::json& doc, const std::filesystem::path& path) {
  const std::string file = path.string();
  JsonObject root(doc, file, "");
  std::vector<ManifestKeyframe> keyframes = parse_keyframes(root, path.parent_path());
  const LifecycleSpec spec = parse_lifecycle(root.object("lifecycle"));
  Trajectory trajectory;
  if (auto t = root.optional_object("trajectory")) trajectory = parse_trajectory(std::move(*t));
  root.finish();

  std::vector<double> times;
  for (const auto& k : keyframes) times.push_back(k.time_s);
  Lifecycle lifecycle = rooted(file, [&] { return Lifecycle(std::move(times), spec, file); });
  return {path, std::move(keyframes), std::move(lifecycle), std::move(trajectory)};
}

CloudManifest read_cloud_manifest(const std::filesystem::path& path) {
  return parse_cloud_manifest(read_json_file(path.string()), path);
}

}  // namespace obscura
