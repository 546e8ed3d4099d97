// Cloud trajectories: linear and Catmull-Rom interpolation of position and
// heading, holds outside the keys, drift, and rejected keys.
#include "obscura/medium/trajectory.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/error.h"

namespace obscura {
namespace {

using I = TrajectoryInterpolation;

void expect_near(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

std::vector<TrajectoryKey> three_keys() {
  return {{0, {0, 0, 0}, 0}, {2, {2, 4, 0}, 90}, {4, {2, 4, 6}, 450}};
}

TEST(Trajectory, DefaultStaysAtTheOrigin) {
  const Trajectory t;
  const TrajectoryPose p = t.at(123);
  EXPECT_EQ(p.position_m, Vec3(0, 0, 0));
  EXPECT_EQ(p.heading_deg, 0);
}

TEST(Trajectory, LinearInterpolatesPositionAndUnwrappedHeading) {
  const Trajectory t(three_keys(), I::kLinear, {0, 0, 0});
  expect_near(t.at(1).position_m, {1, 2, 0});
  EXPECT_DOUBLE_EQ(t.at(1).heading_deg, 45);
  expect_near(t.at(3).position_m, {2, 4, 3});
  EXPECT_DOUBLE_EQ(t.at(3).heading_deg, 270);  // 90 → 450 passes 270, no wrapping
  EXPECT_EQ(t.at(2).position_m, Vec3(2, 4, 0));
  EXPECT_EQ(t.at(2).heading_deg, 90);
}

TEST(Trajectory, HeldBeforeTheFirstAndAfterTheLastKey) {
  for (I mode : {I::kLinear, I::kCatmullRom}) {
    const Trajectory t(three_keys(), mode, {0, 0, 0});
    EXPECT_EQ(t.at(-5).position_m, Vec3(0, 0, 0));
    EXPECT_EQ(t.at(-5).heading_deg, 0);
    EXPECT_EQ(t.at(100).position_m, Vec3(2, 4, 6));
    EXPECT_EQ(t.at(100).heading_deg, 450);
  }
  const Trajectory one({{3, {1, 2, 3}, 30}}, I::kCatmullRom, {0, 0, 0});
  EXPECT_EQ(one.at(0).position_m, Vec3(1, 2, 3));
  EXPECT_EQ(one.at(10).heading_deg, 30);
}

TEST(Trajectory, DriftIsAddedAtEveryLocalTime) {
  const Trajectory t(three_keys(), I::kLinear, {1, 0, 0.5});
  expect_near(t.at(3).position_m, {2 + 3, 4, 3 + 1.5});
  expect_near(t.at(10).position_m, {2 + 10, 4, 6 + 5});
  EXPECT_DOUBLE_EQ(t.at(3).heading_deg, 270);  // drift does not turn the cloud
  const Trajectory drift_only({}, I::kLinear, {2, -1, 0});
  expect_near(drift_only.at(1.5).position_m, {3, -1.5, 0});
}

TEST(Trajectory, CatmullRomHandComputed) {
  // x: 0, 1, 0 at t = 0, 1, 2: tangents 1, 0, −1. At t = 0.5 the Hermite basis
  // is h00 = h01 = 0.5, h10 = 0.125, h11 = −0.125: x = 0.125·1 + 0.5·1 = 0.625.
  const Trajectory t({{0, {0, 0, 0}, 0}, {1, {1, 0, 0}, 10}, {2, {0, 0, 0}, 0}}, I::kCatmullRom,
                     {0, 0, 0});
  EXPECT_DOUBLE_EQ(t.at(0.5).position_m.x, 0.625);
  EXPECT_DOUBLE_EQ(t.at(0.5).heading_deg, 6.25);
  EXPECT_DOUBLE_EQ(t.at(1.5).position_m.x, 0.625);
}

TEST(Trajectory, CatmullRomReproducesUniformMotion) {
  // Keys on a straight line at constant speed, at uneven times: every tangent
  // is the velocity, so the spline is that motion exactly.
  const Vec3 v{1.5, -2, 0.25};
  std::vector<TrajectoryKey> keys;
  for (double time : {0.0, 0.5, 2.0, 2.25, 5.0}) keys.push_back({time, v * time, 10 * time});
  const Trajectory t(keys, I::kCatmullRom, {0, 0, 0});
  for (double u = 0; u <= 5; u += 0.1) {
    expect_near(t.at(u).position_m, v * u, 1e-12);
    EXPECT_NEAR(t.at(u).heading_deg, 10 * u, 1e-12);
  }
}

TEST(Trajectory, CatmullRomPassesThroughKeysAndIsC1) {
  const std::vector<TrajectoryKey> keys = {{0, {0, 0, 0}, 0},
                                           {1, {3, 1, 0}, 40},
                                           {3.5, {4, -2, 2}, -30},
                                           {4, {7, 0, 1}, 200},
                                           {6, {6, 5, 3}, 180}};
  const Trajectory t(keys, I::kCatmullRom, {0, 0, 0});
  for (const auto& k : keys) {
    expect_near(t.at(k.time_s).position_m, k.position_m, 1e-12);
    EXPECT_NEAR(t.at(k.time_s).heading_deg, k.heading_deg, 1e-12);
  }
  // One-sided derivatives by second-order differences (error O(h²), so the
  // heading's large curvature does not swamp the comparison).
  const double h = 1e-5;
  const auto left_derivative = [&](double tk) {
    const TrajectoryPose a = t.at(tk), b = t.at(tk - h), c = t.at(tk - 2 * h);
    return TrajectoryPose{(a.position_m * 3 - b.position_m * 4 + c.position_m) / (2 * h),
                          (3 * a.heading_deg - 4 * b.heading_deg + c.heading_deg) / (2 * h)};
  };
  const auto right_derivative = [&](double tk) {
    const TrajectoryPose a = t.at(tk), b = t.at(tk + h), c = t.at(tk + 2 * h);
    return TrajectoryPose{(b.position_m * 4 - a.position_m * 3 - c.position_m) / (2 * h),
                          (4 * b.heading_deg - 3 * a.heading_deg - c.heading_deg) / (2 * h)};
  };
  for (std::size_t i = 1; i + 1 < keys.size(); ++i) {
    const double tk = keys[i].time_s;
    const TrajectoryPose at = t.at(tk);
    // Continuous.
    expect_near(t.at(tk - h).position_m, at.position_m, 1e-3);
    expect_near(t.at(tk + h).position_m, at.position_m, 1e-3);
    // C1: one-sided derivatives agree, and equal the centred key difference.
    const TrajectoryPose left = left_derivative(tk), right = right_derivative(tk);
    const double dt = keys[i + 1].time_s - keys[i - 1].time_s;
    const Vec3 m = (keys[i + 1].position_m - keys[i - 1].position_m) / dt;
    expect_near(left.position_m, right.position_m, 1e-5);
    expect_near(left.position_m, m, 1e-5);
    EXPECT_NEAR(left.heading_deg, right.heading_deg, 1e-4);
    EXPECT_NEAR(left.heading_deg, (keys[i + 1].heading_deg - keys[i - 1].heading_deg) / dt, 1e-4);
  }
  // Linear interpolation is not C1 at the same keys (the test can fail).
  const Trajectory lin(keys, I::kLinear, {0, 0, 0});
  const double left = (lin.at(1).position_m.x - lin.at(1 - h).position_m.x) / h;
  const double right = (lin.at(1 + h).position_m.x - lin.at(1).position_m.x) / h;
  EXPECT_GT(std::abs(left - right), 1);
}

std::string field_of(std::vector<TrajectoryKey> keys, Vec3 drift = {0, 0, 0}) {
  try {
    Trajectory t(std::move(keys), I::kLinear, drift, "cloud.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "cloud.json");
    return e.field();
  }
  return "";
}

TEST(Trajectory, BadKeysNameTheField) {
  EXPECT_EQ(field_of(three_keys()), "");
  EXPECT_EQ(field_of({{0, {0, 0, 0}, 0}, {0, {1, 0, 0}, 0}}), "trajectory/keys/1/time");
  EXPECT_EQ(field_of({{0, {0, 0, 0}, 0}, {2, {1, 0, 0}, 0}, {1, {1, 0, 0}, 0}}),
            "trajectory/keys/2/time");
  EXPECT_EQ(field_of({{NAN, {0, 0, 0}, 0}}), "trajectory/keys/0/time");
  EXPECT_EQ(field_of({{0, {0, INFINITY, 0}, 0}}), "trajectory/keys/0/position");
  EXPECT_EQ(field_of({{0, {0, 0, 0}, NAN}}), "trajectory/keys/0/heading_deg");
  EXPECT_EQ(field_of({}, {NAN, 0, 0}), "trajectory/drift_velocity");
}

}  // namespace
}  // namespace obscura
