#pragma once
// A pinhole camera: position, look-at point, up vector and vertical field of
// view; pixel (0, 0) is the top-left corner of the image.
#include "obscura/core/ray.h"

namespace obscura {

class PinholeCamera {
 public:
  PinholeCamera() = default;
  PinholeCamera(Vec3 position_m, Vec3 look_at_m, Vec3 up, double vertical_fov_deg, int width,
                int height);

  // Ray through image-plane position (x, y) in pixels, (0, 0) the top-left corner
  // of the image and (width, height) the bottom-right; unit direction.
  Ray generate_ray(double x, double y) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const Vec3& position() const { return position_; }
  double vertical_fov_deg() const { return fov_deg_; }

 private:
  Vec3 position_, forward_, right_, up_;
  double fov_deg_ = 0, tan_half_ = 0;
  int width_ = 0, height_ = 0;
};

}  // namespace obscura
