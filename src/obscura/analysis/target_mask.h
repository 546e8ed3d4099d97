#pragma once
// Which pixels of a sensor show the target, and which are its background: the
// pixel sets that screening metrics average over (docs/metrics.md).
//
// Target pixel: the camera ray through the pixel centre (x + 0.5, y + 0.5)
// meets a surface marked "target" before any other surface. Clouds play no
// part: the mask is the target's silhouette, the same whatever hides it, so
// it is computed once per sensor (surfaces do not move).
// Background pixel: not a target pixel, inside the target pixels' bounding
// box grown by `background_margin_px` on every side and clipped to the image
// (a frame around the target, plus any non-target pixels inside the box).
#include <cstdint>
#include <string>
#include <vector>

#include "obscura/scene/scene.h"

namespace obscura {

enum class MaskLabel : std::uint8_t { kOther = 0, kTarget = 1, kBackground = 2 };

struct TargetMask {
  std::string sensor;
  int width = 0, height = 0;  // px, the sensor's image size
  // One label per pixel, row-major, top row first (as SensorImage).
  std::vector<MaskLabel> labels;
  int target_pixels = 0;
  int background_pixels = 0;
  // The target pixels' bounding box, [x0, x1) × [y0, y1); all 0 when empty.
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  // No target pixel: the sensor does not see the target, and its metrics are
  // NaN (null in JSON, empty in CSV).
  bool empty() const { return target_pixels == 0; }
  MaskLabel at(int x, int y) const { return labels[static_cast<std::size_t>(y) * width + x]; }
};

// True when some surface of the scene is marked as a target.
bool scene_has_target(const Scene& scene);

// The mask of `sensor` in `scene` (rows in parallel on `threads`, 0: all
// cores). Throws InputError if background_margin_px < 0.
TargetMask compute_target_mask(const Scene& scene, const Sensor& sensor, int background_margin_px,
                               int threads = 0);

// The mask's pixels from its labels (recounts and recomputes the bounding
// box and the background frame): for masks built by hand, e.g. in tests.
void finish_target_mask(TargetMask& mask, int background_margin_px);

}  // namespace obscura
