#pragma once
// Axis-aligned bounding box with the slab ray test (Kay & Kajiya 1986).
#include <limits>
#include <utility>

#include "obscura/core/host_device.h"
#include "obscura/core/ray.h"

namespace obscura {

struct BBox3 {
  Vec3 lo{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
          std::numeric_limits<double>::infinity()};
  Vec3 hi{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
          -std::numeric_limits<double>::infinity()};

  constexpr BBox3() = default;
  constexpr BBox3(const Vec3& a, const Vec3& b)
      : lo(component_min(a, b)), hi(component_max(a, b)) {}

  bool empty() const { return lo.x > hi.x || lo.y > hi.y || lo.z > hi.z; }
  Vec3 extent() const { return hi - lo; }
  Vec3 center() const { return (lo + hi) * 0.5; }
  void expand(const Vec3& p) {
    lo = component_min(lo, p);
    hi = component_max(hi, p);
  }
  void expand(const BBox3& b) {
    lo = component_min(lo, b.lo);
    hi = component_max(hi, b.hi);
  }
  bool contains(const Vec3& p) const {
    return p.x >= lo.x && p.x <= hi.x && p.y >= lo.y && p.y <= hi.y && p.z >= lo.z && p.z <= hi.z;
  }

  // Clips [t_min, t_max] to the part of the ray inside the box; false if none is.
  OBSCURA_HOST_DEVICE bool intersect(const Ray& ray, double& t_min, double& t_max) const {
    for (int a = 0; a < 3; ++a) {
      const double inv = 1.0 / ray.direction[a];  // +-inf for axis-parallel rays is intended
      double t0 = (lo[a] - ray.origin[a]) * inv;
      double t1 = (hi[a] - ray.origin[a]) * inv;
      if (inv < 0) std::swap(t0, t1);
      // NaN (0 * inf on a slab plane) compares false and leaves the interval unchanged.
      if (t0 > t_min) t_min = t0;
      if (t1 < t_max) t_max = t1;
      if (t_min > t_max) return false;
    }
    return true;
  }
};

}  // namespace obscura
