#pragma once
// 3x3 matrices for rotations, and orthonormal frames.
#include <array>
#include <cmath>
#include <numbers>

#include "obscura/core/vec3.h"

namespace obscura {

struct Mat3 {
  std::array<std::array<double, 3>, 3> m{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};

  static constexpr Mat3 identity() { return Mat3{}; }
  static constexpr Mat3 from_rows(const Vec3& r0, const Vec3& r1, const Vec3& r2) {
    Mat3 a;
    a.m = {{{r0.x, r0.y, r0.z}, {r1.x, r1.y, r1.z}, {r2.x, r2.y, r2.z}}};
    return a;
  }
  constexpr Vec3 operator*(const Vec3& v) const {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  constexpr Mat3 operator*(const Mat3& b) const {
    Mat3 c;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        c.m[i][j] = m[i][0] * b.m[0][j] + m[i][1] * b.m[1][j] + m[i][2] * b.m[2][j];
    return c;
  }
  constexpr Mat3 transposed() const {
    Mat3 t;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) t.m[i][j] = m[j][i];
    return t;
  }
  constexpr bool operator==(const Mat3&) const = default;
};

// Rotation by Euler angles in degrees, applied about x first, then y, then z
// (R = Rz * Ry * Rx), all about the fixed world axes, right-handed.
inline Mat3 rotation_from_euler_deg(const Vec3& deg) {
  const double k = std::numbers::pi / 180.0;
  const double cx = std::cos(deg.x * k), sx = std::sin(deg.x * k);
  const double cy = std::cos(deg.y * k), sy = std::sin(deg.y * k);
  const double cz = std::cos(deg.z * k), sz = std::sin(deg.z * k);
  const Mat3 rx = Mat3::from_rows({1, 0, 0}, {0, cx, -sx}, {0, sx, cx});
  const Mat3 ry = Mat3::from_rows({cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy});
  const Mat3 rz = Mat3::from_rows({cz, -sz, 0}, {sz, cz, 0}, {0, 0, 1});
  return rz * ry * rx;
}

// Orthonormal frame around a unit normal n (Duff et al. 2017, "Building an
// Orthonormal Basis, Revisited"): no branch on a threshold, no singularity.
struct Frame {
  Vec3 s, t, n;
  static Frame from_normal(const Vec3& n) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double b = n.x * n.y * a;
    return {
        {1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
  }
  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace obscura
