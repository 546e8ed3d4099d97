#pragma once
// Where a time-varying cloud is: its keyframe grids, authored about the
// manifest's local origin, are rotated by a heading about +z and translated,
//   world = Rz(heading_deg) · local + position_m,
// with position and heading interpolated between keys and a constant drift
// (wind) added (docs/time-varying-clouds.md, "Trajectory").
#include <string>
#include <vector>

#include "obscura/core/vec3.h"

namespace obscura {

struct TrajectoryKey {
  double time_s = 0;       // local time: seconds after the cloud's activation
  Vec3 position_m;         // world position of the manifest's origin, m
  double heading_deg = 0;  // rotation about +z, counter-clockwise seen from above (x towards y)
};

enum class TrajectoryInterpolation { kLinear, kCatmullRom };

struct TrajectoryPose {
  Vec3 position_m;
  double heading_deg = 0;
};

class Trajectory {
 public:
  // No keys: stays at the origin, heading 0, no drift.
  Trajectory();
  // keys: strictly increasing in time, finite (times may be negative or
  // positive; before the first and after the last key the pose is held).
  // Headings are interpolated as given, without wrapping, so that a cloud can
  // turn by more than 180° between keys: give unwrapped angles (350 → 370, not
  // 350 → 10). Throws InputError(source, "trajectory/keys/<i>/time", ...) etc.
  // Zero keys means the origin and heading 0, plus the drift.
  Trajectory(std::vector<TrajectoryKey> keys, TrajectoryInterpolation interpolation,
             Vec3 drift_velocity_m_s, const std::string& source = "");

  // Pose at local time u (s after activation): the interpolated keys plus
  // drift_velocity · u.
  TrajectoryPose at(double local_time_s) const;

  const std::vector<TrajectoryKey>& keys() const { return keys_; }
  TrajectoryInterpolation interpolation() const { return interpolation_; }
  const Vec3& drift_velocity_m_s() const { return drift_m_s_; }

 private:
  std::vector<TrajectoryKey> keys_;
  TrajectoryInterpolation interpolation_ = TrajectoryInterpolation::kLinear;
  Vec3 drift_m_s_;
};

}  // namespace obscura
