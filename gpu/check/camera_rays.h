#pragma once
// A pinhole camera's rays through its pixel centres, row by row from the top,
// as the renderer hands them to the march (obscura/gpu/march_job.h's
// MarchRay): each ends on a ground plane when it meets one, else runs on.
#include <vector>

#include "obscura/core/vec3.h"
#include "obscura/gpu/march_job.h"

namespace obscura::gpu_check {

struct Camera {
  Vec3 position_m, look_at_m;
  Vec3 up{0, 0, 1};
  double horizontal_fov_deg = 30.0;
  int width = 64, height = 64;
  bool ground = false;  // rays end on the plane z = ground_m
  double ground_m = 0.0;
};

std::vector<MarchRay> camera_rays(const Camera& camera);

}  // namespace obscura::gpu_check
