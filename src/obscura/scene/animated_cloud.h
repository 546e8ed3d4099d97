#pragma once
// A cloud instance in a scene: a manifest (keyframes, lifecycle, trajectory)
// activated at one time and optionally deactivated at another. Staging it at a
// scene time gives the medium the renderer sees then: the two bracketing
// keyframes interpolated per voxel, placed by the trajectory; or nothing while
// the cloud is absent or extinct.
#include <memory>
#include <optional>
#include <string>

#include "obscura/io/cloud_manifest.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/keyframe_cache.h"

namespace obscura {

// The keys of a scene's animated cloud, of either type ("animated",
// "vdb-density" with a sequence; docs/formats.md): "name" (default
// "cloud<index>"), "activation" (s, default 0), "deactivation" (s, optional:
// never), "cache_keyframes" (2…64, default 3).
struct AnimatedCloudKeys {
  std::string name;
  double activation_s = 0;
  std::optional<double> deactivation_s;
  std::size_t cache_keyframes = 3;
};
class JsonObject;
// Reads them from the cloud's object; errors name the JSON path.
AnimatedCloudKeys read_animated_cloud_keys(JsonObject& o, int index);

class AnimatedCloud {
 public:
  // Keyframes are read on demand through a cache of `cache_capacity` grids,
  // by `loader` (default: read_cloud_keyframe; a vdb-density sequence reads
  // another tool's files, scene/vdb_density_cloud.h).
  AnimatedCloud(std::string name, CloudManifest manifest, double activation_s,
                std::optional<double> deactivation_s, std::size_t cache_capacity = 3,
                KeyframeCache::Loader loader = {});

  const std::string& name() const { return name_; }
  const CloudManifest& manifest() const { return manifest_; }
  double activation_s() const { return activation_s_; }
  const std::optional<double>& deactivation_s() const { return deactivation_s_; }

  LifecycleState state(double t) const;
  TrajectoryPose pose(double t) const;
  // The cloud's medium at scene time t (s), or null when it is not present.
  // Not thread-safe (it reads files through the cache): stage between frames.
  std::shared_ptr<const GridMedium> stage(double t);
  // The interpolated, placed grid at time t (null when not present).
  std::shared_ptr<const VoxelGrid> stage_grid(double t);

  const KeyframeCache& cache() const { return cache_; }

 private:
  std::string name_;
  CloudManifest manifest_;
  double activation_s_;
  std::optional<double> deactivation_s_;
  KeyframeCache cache_;
};

}  // namespace obscura
