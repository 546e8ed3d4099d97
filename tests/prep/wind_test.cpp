#include "obscura/prep/dispersion/wind.h"

#include <gtest/gtest.h>

#include <cmath>

namespace obscura {
namespace {

TEST(Wind, PowerLawProfileFromTheReferenceHeight) {
  Wind w;
  w.speed_m_s = 4.0;
  w.reference_height_m = 10.0;
  w.power_law_exponent = 0.35;
  w.minimum_height_m = 1.0;
  EXPECT_DOUBLE_EQ(w.speed_at_m_s(10.0), 4.0);
  EXPECT_NEAR(w.speed_at_m_s(2.0), 4.0 * std::pow(0.2, 0.35), 1e-12);
  EXPECT_NEAR(w.speed_at_m_s(40.0), 4.0 * std::pow(4.0, 0.35), 1e-12);
  EXPECT_LT(w.speed_at_m_s(2.0), w.speed_at_m_s(5.0));
  // Below the floor the speed at the floor: a ground release still moves.
  EXPECT_DOUBLE_EQ(w.speed_at_m_s(0.0), w.speed_at_m_s(1.0));
  EXPECT_DOUBLE_EQ(w.speed_at_m_s(0.3), 4.0 * std::pow(0.1, 0.35));
  w.power_law_exponent = 0.0;  // uniform
  EXPECT_DOUBLE_EQ(w.speed_at_m_s(0.0), 4.0);
  EXPECT_DOUBLE_EQ(w.speed_at_m_s(100.0), 4.0);
}

TEST(Wind, FromDirectionIsMeteorological) {
  // World x east, y north: a wind from the north blows towards −y, from the
  // east towards −x, from the west towards +x, from the south-west to the NE.
  Wind w;
  struct Case {
    double from_deg, dx, dy;
  };
  const double r = std::sqrt(0.5);
  for (const Case& c : {Case{0, 0, -1}, Case{90, -1, 0}, Case{180, 0, 1}, Case{270, 1, 0},
                        Case{225, r, r}, Case{-90, 1, 0}}) {
    w.from_deg = c.from_deg;
    const Vec3 d = w.downwind_direction();
    EXPECT_NEAR(d.x, c.dx, 1e-12) << c.from_deg;
    EXPECT_NEAR(d.y, c.dy, 1e-12) << c.from_deg;
    EXPECT_EQ(d.z, 0.0);
  }
}

TEST(Wind, VelocityIsSpeedAtHeightAlongTheDownwindDirection) {
  Wind w;
  w.speed_m_s = 3;
  w.from_deg = 270;
  w.power_law_exponent = 0.15;
  const Vec3 v = w.velocity_at_m_s(5.0);
  EXPECT_NEAR(v.x, 3 * std::pow(0.5, 0.15), 1e-12);
  EXPECT_NEAR(v.y, 0, 1e-12);
}

}  // namespace
}  // namespace obscura
