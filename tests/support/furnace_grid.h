#pragma once
// A white furnace as a scene: a conservative (σa = 0) random grid cloud of
// dims³ voxels centred near the origin, under a uniform 300 K blackbody sky,
// seen from 8 m by a 30° camera of `pixels`² in the LWIR band. Every pixel's
// radiance is the sky's, B(300 K), whatever the cloud.
#include <memory>

#include "medium/test_grids.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/scene/scene.h"

namespace obscura::testing {

// `scattering_per_absorption`: σs becomes σs + this × σa of the random grid.
inline Scene furnace_grid_scene(int dims, float scattering_per_absorption, int pixels) {
  Scene scene;
  Sensor sensor;
  sensor.name = "cam";
  sensor.camera = PinholeCamera({0, -8, 0}, {0, 0, 0}, {0, 0, 1}, 30.0, pixels, pixels);
  sensor.bands = {Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  auto grid = random_grid({dims, dims, dims}, 1, 3);
  for (std::size_t v = 0; v < grid->dims().count(); ++v) {
    grid->sigma_s(0)[v] += scattering_per_absorption * grid->sigma_a(0)[v];
    grid->sigma_a(0)[v] = 0.0f;
  }
  GridPlacement p = grid->placement();
  p.origin_m = {-1.5, -1.5, -1.5};
  grid->set_placement(p);
  scene.medium = std::make_shared<GridMedium>(grid);
  scene.sky = Sky::blackbody(300.0, true);
  return scene;
}

}  // namespace obscura::testing
