#pragma once
// A sunlit random grid cloud with a ground through it (the nodes below the
// ground shaded from the sun), for the radiance cache's tests.
#include <memory>

#include "medium/test_grids.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/scene/scene.h"

namespace obscura::testing {

inline Scene sunlit_grid_scene(int sh_degree, long long photons = 2000) {
  Scene scene;
  auto grid = random_grid({10, 8, 6}, 3, 9, rotation_from_euler_deg({10, 0, 30}));
  scene.medium = std::make_shared<GridMedium>(grid);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{290, 0.7}, 2.6));
  scene.sky = Sky::blackbody(240, true);
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 40.0;
  scene.sun.azimuth_deg = 120.0;
  scene.settings.radiance_cache.photons_per_node = photons;
  scene.settings.radiance_cache.sh_degree = sh_degree;
  scene.settings.threads = 2;
  return scene;
}

}  // namespace obscura::testing
