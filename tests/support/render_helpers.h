#pragma once
// Renders a scene's first sensor with a given thread count and seed: the
// settings live in scene.settings (scene/render_settings.h), so a test that
// compares thread counts sets them there.
#include <cstdint>

#include "obscura/render/renderer.h"

namespace obscura::testing {

inline SensorImage render_first_sensor(Scene& scene, int threads, std::uint64_t seed = 1) {
  scene.settings.threads = threads;
  scene.settings.seed = seed;
  return render_sensor(scene, scene.sensors[0]);
}

}  // namespace obscura::testing
