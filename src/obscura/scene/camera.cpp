#include "obscura/scene/camera.h"

#include <cmath>
#include <numbers>

#include "obscura/core/error.h"

namespace obscura {

PinholeCamera::PinholeCamera(Vec3 position_m, Vec3 look_at_m, Vec3 up, double vertical_fov_deg,
                             int width, int height)
    : position_(position_m), fov_deg_(vertical_fov_deg), width_(width), height_(height) {
  const Vec3 f = look_at_m - position_m;
  if (!(length(f) > 0)) throw Error("camera: look_at equals position");
  forward_ = normalize(f);
  const Vec3 r = cross(forward_, up);
  if (!(length(r) > 1e-9 * length(up))) throw Error("camera: up is parallel to the view direction");
  right_ = normalize(r);
  up_ = cross(right_, forward_);
  tan_half_ = std::tan(0.5 * vertical_fov_deg * std::numbers::pi / 180.0);
}

Ray PinholeCamera::generate_ray(double x, double y) const {
  const double aspect = static_cast<double>(width_) / height_;
  const double sx = (2.0 * x / width_ - 1.0) * tan_half_ * aspect;
  const double sy = (1.0 - 2.0 * y / height_) * tan_half_;
  return Ray{position_, normalize(forward_ + right_ * sx + up_ * sy)};
}

}  // namespace obscura
