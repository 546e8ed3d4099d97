#pragma once
// Keyframes loaded on demand with a small least-recently-used cache, so a
// sequence longer than memory renders with only a few keyframes resident per
// cloud (the two that bracket the current time, and the next one).
#include <cstddef>
#include <filesystem>
#include <functional>
#include <list>
#include <memory>
#include <utility>

#include "obscura/medium/voxel_grid.h"

namespace obscura {

class KeyframeCache {
 public:
  using Loader = std::function<std::shared_ptr<const VoxelGrid>(const std::filesystem::path&)>;

  // `capacity` >= 1 keyframes kept; `loader` reads one (default: read_cloud_keyframe).
  explicit KeyframeCache(std::size_t capacity, Loader loader);

  std::shared_ptr<const VoxelGrid> get(const std::filesystem::path& file);

  std::size_t loads() const { return loads_; }
  std::size_t hits() const { return hits_; }
  std::size_t resident() const { return entries_.size(); }
  std::size_t capacity() const { return capacity_; }

 private:
  std::size_t capacity_;
  Loader loader_;
  std::list<std::pair<std::filesystem::path, std::shared_ptr<const VoxelGrid>>>
      entries_;  // MRU first
  std::size_t loads_ = 0, hits_ = 0;
};

}  // namespace obscura
