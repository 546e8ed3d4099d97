#include "obscura/analysis/target_mask.h"

#include <fmt/format.h>

#include <algorithm>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/core/parallel.h"

namespace obscura {

bool scene_has_target(const Scene& scene) {
  return std::any_of(scene.surfaces.begin(), scene.surfaces.end(),
                     [](const auto& s) { return s->is_target(); });
}

TargetMask compute_target_mask(const Scene& scene, const Sensor& sensor, int background_margin_px,
                               int threads) {
  TargetMask mask;
  mask.sensor = sensor.name;
  mask.width = sensor.camera.width();
  mask.height = sensor.camera.height();
  mask.labels.assign(static_cast<std::size_t>(mask.width) * mask.height, MaskLabel::kOther);
  parallel_for(static_cast<std::size_t>(mask.height), threads, [&](std::size_t row) {
    const int y = static_cast<int>(row);
    for (int x = 0; x < mask.width; ++x) {
      // The pixel centre, as the renderer's single-sample ray.
      const Ray ray = sensor.camera.generate_ray(x + 0.5, y + 0.5);
      SurfaceHit hit;
      if (intersect_surfaces(scene.surfaces, ray, 0.0, std::numeric_limits<double>::infinity(),
                             hit) &&
          scene.surfaces[hit.surface]->is_target())
        mask.labels[row * mask.width + x] = MaskLabel::kTarget;
    }
  });
  finish_target_mask(mask, background_margin_px);
  return mask;
}

void finish_target_mask(TargetMask& mask, int background_margin_px) {
  if (background_margin_px < 0)
    throw InputError("", "background_margin_px",
                     fmt::format("must be >= 0 pixels, got {}", background_margin_px));
  if (mask.labels.size() != static_cast<std::size_t>(mask.width) * mask.height)
    throw Error(fmt::format("target mask of {}: {} labels for {}x{} pixels", mask.sensor,
                            mask.labels.size(), mask.width, mask.height));
  int x0 = mask.width, y0 = mask.height, x1 = 0, y1 = 0, count = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      MaskLabel& l = mask.labels[static_cast<std::size_t>(y) * mask.width + x];
      if (l != MaskLabel::kTarget) {
        l = MaskLabel::kOther;
        continue;
      }
      ++count;
      x0 = std::min(x0, x);
      y0 = std::min(y0, y);
      x1 = std::max(x1, x + 1);
      y1 = std::max(y1, y + 1);
    }
  mask.target_pixels = count;
  mask.background_pixels = 0;
  if (count == 0) {
    mask.x0 = mask.y0 = mask.x1 = mask.y1 = 0;
    return;
  }
  mask.x0 = x0, mask.y0 = y0, mask.x1 = x1, mask.y1 = y1;
  // The box grown by the margin, clipped to the image; every non-target pixel
  // in it is background.
  const int m = background_margin_px;
  const int bx0 = std::max(0, x0 - m), by0 = std::max(0, y0 - m);
  const int bx1 = std::min(mask.width, x1 + m), by1 = std::min(mask.height, y1 + m);
  for (int y = by0; y < by1; ++y)
    for (int x = bx0; x < bx1; ++x) {
      MaskLabel& l = mask.labels[static_cast<std::size_t>(y) * mask.width + x];
      if (l == MaskLabel::kOther) {
        l = MaskLabel::kBackground;
        ++mask.background_pixels;
      }
    }
}

}  // namespace obscura
