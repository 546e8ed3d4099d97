#include "obscura/medium/keyframe_cache.h"

#include "obscura/core/error.h"

namespace obscura {

KeyframeCache::KeyframeCache(std::size_t capacity, Loader loader)
    : capacity_(capacity), loader_(std::move(loader)) {
  if (capacity_ < 1) throw Error("KeyframeCache: capacity must be >= 1");
}

std::shared_ptr<const VoxelGrid> KeyframeCache::get(const std::filesystem::path& file) {
  for (auto it = entries_.begin(); it != entries_.end(); ++it) {
    if (it->first == file) {
      ++hits_;
      entries_.splice(entries_.begin(), entries_, it);
      return entries_.front().second;
    }
  }
  // Evict before loading, so at most `capacity` keyframes are ever resident.
  while (entries_.size() >= capacity_) entries_.pop_back();
  ++loads_;
  entries_.emplace_front(file, loader_(file));
  return entries_.front().second;
}

}  // namespace obscura
