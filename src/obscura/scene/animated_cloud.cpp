#include "obscura/scene/animated_cloud.h"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "obscura/io/json_reader.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/keyframe_interpolation.h"

namespace obscura {

AnimatedCloudKeys read_animated_cloud_keys(JsonObject& o, int index) {
  AnimatedCloudKeys k;
  k.activation_s = o.number_or("activation", 0.0);
  k.deactivation_s = o.optional_number("deactivation");
  k.name = o.string_or("name", fmt::format("cloud{}", index));
  const long long cache = o.integer_or("cache_keyframes", 3);
  if (cache < 2 || cache > 64) throw o.error("cache_keyframes", "must lie in [2, 64]");
  k.cache_keyframes = static_cast<std::size_t>(cache);
  return k;
}

AnimatedCloud::AnimatedCloud(std::string name, CloudManifest manifest, double activation_s,
                             std::optional<double> deactivation_s, std::size_t cache_capacity,
                             KeyframeCache::Loader loader)
    : name_(std::move(name)),
      manifest_(std::move(manifest)),
      activation_s_(activation_s),
      deactivation_s_(deactivation_s),
      cache_(
          cache_capacity,
          loader ? std::move(loader) : KeyframeCache::Loader([](const std::filesystem::path& file) {
            return std::shared_ptr<const VoxelGrid>(read_cloud_keyframe(file).grid);
          })) {}

LifecycleState AnimatedCloud::state(double t) const {
  return manifest_.lifecycle.at(t, activation_s_, deactivation_s_);
}

TrajectoryPose AnimatedCloud::pose(double t) const {
  return manifest_.trajectory.at(t - activation_s_);
}

std::shared_ptr<const VoxelGrid> AnimatedCloud::stage_grid(double t) {
  const LifecycleState s = state(t);
  if (!s.present()) return nullptr;
  const auto& frames = manifest_.keyframes;
  const std::string source = manifest_.source.string();
  auto a = cache_.get(frames[s.keyframe0].file);
  std::shared_ptr<VoxelGrid> grid;
  if (s.weight == 0.0 || s.keyframe1 == s.keyframe0) {
    grid = std::make_shared<VoxelGrid>(*a);
  } else {
    auto b = cache_.get(frames[s.keyframe1].file);
    grid = std::make_shared<VoxelGrid>(interpolate_keyframes(*a, *b, s.weight, source));
  }
  // Place the manifest-frame grid in the world: rotate by the heading about +z
  // through the manifest's origin, then translate (docs/formats.md).
  const TrajectoryPose p = pose(t);
  GridPlacement placement = grid->placement();
  const Mat3 rz = rotation_from_euler_deg({0.0, 0.0, p.heading_deg});
  placement.origin_m = rz * placement.origin_m + p.position_m;
  placement.rotation = rz * placement.rotation;
  grid->set_placement(placement);
  return grid;
}

std::shared_ptr<const GridMedium> AnimatedCloud::stage(double t) {
  auto grid = stage_grid(t);
  if (!grid) return nullptr;
  return std::make_shared<GridMedium>(std::move(grid));
}

}  // namespace obscura
