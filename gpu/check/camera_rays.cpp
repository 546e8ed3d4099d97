#include "camera_rays.h"

#include <cmath>
#include <limits>
#include <numbers>

namespace obscura::gpu_check {

std::vector<MarchRay> camera_rays(const Camera& c) {
  const Vec3 forward = normalize(c.look_at_m - c.position_m);
  const Vec3 right = normalize(cross(forward, c.up));
  const Vec3 up = cross(right, forward);
  const double half_w = std::tan(0.5 * c.horizontal_fov_deg * std::numbers::pi / 180.0);
  const double half_h = half_w * c.height / c.width;
  std::vector<MarchRay> rays;
  rays.reserve(static_cast<std::size_t>(c.width) * c.height);
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const double u = (2.0 * (x + 0.5) / c.width - 1.0) * half_w;
      const double v = (1.0 - 2.0 * (y + 0.5) / c.height) * half_h;
      const Vec3 d = normalize(forward + right * u + up * v);
      double t_end = std::numeric_limits<double>::infinity();
      if (c.ground && d.z < 0.0) t_end = (c.ground_m - c.position_m.z) / d.z;
      rays.push_back({c.position_m, d, t_end});
    }
  return rays;
}

}  // namespace obscura::gpu_check
