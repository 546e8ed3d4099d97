#include "obscura/medium/trajectory.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "obscura/core/error.h"

namespace obscura {

namespace {

// Position and heading as one 4-vector, so both are interpolated by one rule.
struct Pose4 {
  Vec3 p;
  double h = 0;
  Pose4 operator+(const Pose4& o) const { return {p + o.p, h + o.h}; }
  Pose4 operator-(const Pose4& o) const { return {p - o.p, h - o.h}; }
  Pose4 operator*(double s) const { return {p * s, h * s}; }
};

Pose4 pose_of(const TrajectoryKey& k) { return {k.position_m, k.heading_deg}; }

}  // namespace

Trajectory::Trajectory() = default;

Trajectory::Trajectory(std::vector<TrajectoryKey> keys, TrajectoryInterpolation interpolation,
                       Vec3 drift_velocity_m_s, const std::string& source)
    : keys_(std::move(keys)), interpolation_(interpolation), drift_m_s_(drift_velocity_m_s) {
  for (std::size_t i = 0; i < keys_.size(); ++i) {
    const auto field = [&](const char* name) {
      return fmt::format("trajectory/keys/{}/{}", i, name);
    };
    const TrajectoryKey& k = keys_[i];
    if (!std::isfinite(k.time_s))
      throw InputError(source, field("time"), "must be a finite time, s");
    if (i > 0 && !(k.time_s > keys_[i - 1].time_s))
      throw InputError(source, field("time"),
                       fmt::format("key times must increase strictly: {} s follows {} s", k.time_s,
                                   keys_[i - 1].time_s));
    if (!is_finite(k.position_m)) throw InputError(source, field("position"), "must be finite, m");
    if (!std::isfinite(k.heading_deg))
      throw InputError(source, field("heading_deg"), "must be finite, degrees");
  }
  if (!is_finite(drift_m_s_))
    throw InputError(source, "trajectory/drift_velocity", "must be finite, m/s");
}

TrajectoryPose Trajectory::at(double u) const {
  Pose4 pose;
  const std::size_t n = keys_.size();
  if (n == 1 || (n > 1 && u <= keys_.front().time_s)) {
    pose = pose_of(keys_.front());
  } else if (n > 1 && u >= keys_.back().time_s) {
    pose = pose_of(keys_.back());
  } else if (n > 1) {
    // Interval k: t_k <= u < t_{k+1}.
    const auto it = std::upper_bound(keys_.begin(), keys_.end(), u,
                                     [](double t, const TrajectoryKey& k) { return t < k.time_s; });
    const std::size_t k = static_cast<std::size_t>(it - keys_.begin()) - 1;
    const double t0 = keys_[k].time_s, t1 = keys_[k + 1].time_s, h = t1 - t0;
    const double s = (u - t0) / h;
    const Pose4 p0 = pose_of(keys_[k]), p1 = pose_of(keys_[k + 1]);
    if (interpolation_ == TrajectoryInterpolation::kLinear) {
      pose = p0 * (1 - s) + p1 * s;
    } else {
      // Catmull-Rom on non-uniform times: cubic Hermite with the tangent at a
      // key the centred difference over its neighbours (one-sided at the
      // ends), so the path passes through every key and is C1.
      const auto tangent = [&](std::size_t i) {
        const std::size_t lo = i == 0 ? 0 : i - 1, hi = std::min(i + 1, n - 1);
        return (pose_of(keys_[hi]) - pose_of(keys_[lo])) *
               (1.0 / (keys_[hi].time_s - keys_[lo].time_s));
      };
      const Pose4 m0 = tangent(k), m1 = tangent(k + 1);
      const double s2 = s * s, s3 = s2 * s;
      const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s;
      const double h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
      pose = p0 * h00 + m0 * (h10 * h) + p1 * h01 + m1 * (h11 * h);
    }
  }
  return {pose.p + drift_m_s_ * u, pose.h};
}

}  // namespace obscura
