#include "obscura/prep/dispersion/dispersion_model.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace obscura {
namespace {

// Class D, 3 m/s at 10 m from the west (blowing towards +x), rural D exponent.
DispersionConfig single_device(double burn_time_s = 0.0) {
  DispersionConfig c;
  c.stability = StabilityClass::kD;
  c.wind.speed_m_s = 3.0;
  c.wind.from_deg = 270.0;
  c.wind.reference_height_m = 10.0;
  c.wind.power_law_exponent = 0.15;
  c.wind.minimum_height_m = 1.0;
  c.ambient_temperature_k = 290.0;
  SmokeDevice d;
  d.x_m = 12.0;
  d.y_m = -7.0;
  d.start_s = 1.5;
  d.burn_time_s = burn_time_s;
  d.agent_mass_g = 500.0;
  d.yield_factor = 1.0;
  d.initial_sigma_m = 2.0;
  c.devices.push_back(d);
  return c;
}

// docs/domain.md §3.4 puff σ for class D, with σ0 in quadrature (§3.1).
double sigma_y_class_d(double x, double s0) {
  return std::sqrt(s0 * s0 + std::pow(0.06 * std::pow(x, 0.92), 2));
}
double sigma_z_class_d(double x, double s0) {
  return std::sqrt(s0 * s0 + std::pow(0.15 * std::pow(x, 0.70), 2));
}

TEST(PuffTrain, BurstIsOnePuffAtStartCarryingAgentTimesYield) {
  SmokeDevice d = single_device().devices[0];
  d.yield_factor = 3.5;
  const std::vector<Puff> puffs = puff_train(d, Wind{});
  ASSERT_EQ(puffs.size(), 1u);
  EXPECT_EQ(puffs[0].release_time_s, 1.5);
  EXPECT_DOUBLE_EQ(puffs[0].mass_g, 500.0 * 3.5);
  EXPECT_EQ(puffs[0].release_point_m, Vec3(12, -7, 0));
}

TEST(PuffTrain, BurningDeviceReleasesEqualPuffsAtIntervalMidpoints) {
  SmokeDevice d = single_device(2.0).devices[0];
  d.puffs_per_second = 10;
  d.yield_factor = 2;
  std::vector<Puff> puffs = puff_train(d, Wind{});
  ASSERT_EQ(puffs.size(), 20u);
  double total = 0;
  for (std::size_t i = 0; i < puffs.size(); ++i) {
    EXPECT_NEAR(puffs[i].release_time_s, 1.5 + 0.1 * (i + 0.5), 1e-12) << i;
    EXPECT_DOUBLE_EQ(puffs[i].mass_g, 1000.0 / 20);
    total += puffs[i].mass_g;
  }
  EXPECT_NEAR(total, 1000.0, 1e-9);
  // A rate that does not divide the burn rounds the count up and keeps the
  // puffs evenly spread over the whole burn.
  d.puffs_per_second = 2.5;
  d.burn_time_s = 1.0;
  puffs = puff_train(d, Wind{});
  ASSERT_EQ(puffs.size(), 3u);
  EXPECT_NEAR(puffs[2].release_time_s, 1.5 + 2.5 / 3.0, 1e-12);
}

TEST(PuffTrain, PuffMovesWithTheWindAtReleaseHeightTowardsDownwind) {
  DispersionConfig c = single_device();
  c.devices[0].release_height_m = 4.0;
  c.wind.from_deg = 0.0;  // from the north: the puff goes south (−y)
  const double u = 3.0 * std::pow(0.4, 0.15);
  const double t = 11.5;  // 10 s after release
  auto states = DispersionModel(c).puffs_at(t);
  ASSERT_EQ(states.size(), 1u);
  EXPECT_NEAR(states[0].centre_m.x, 12.0, 1e-9);
  EXPECT_NEAR(states[0].centre_m.y, -7.0 - 10.0 * u, 1e-9);
  EXPECT_NEAR(states[0].centre_m.z, 4.0, 1e-12);
  c.wind.from_deg = 270.0;  // from the west: towards +x
  states = DispersionModel(c).puffs_at(t);
  EXPECT_NEAR(states[0].centre_m.x, 12.0 + 10.0 * u, 1e-9);
  EXPECT_NEAR(states[0].centre_m.y, -7.0, 1e-9);
  // A ground release moves with the wind at the floor height (1 m).
  c.devices[0].release_height_m = 0.0;
  states = DispersionModel(c).puffs_at(t);
  EXPECT_NEAR(states[0].centre_m.x, 12.0 + 10.0 * 3.0 * std::pow(0.1, 0.15), 1e-9);
}

TEST(PuffTrain, SigmaGrowsWithTravelDistanceWithInitialSizeInQuadrature) {
  const DispersionConfig c = single_device();
  const double u = 3.0 * std::pow(0.1, 0.15);
  for (double age : {0.0, 5.0, 30.0, 120.0}) {
    const PuffState s = DispersionModel(c).puffs_at(1.5 + age)[0];
    EXPECT_NEAR(s.sigma_horizontal_m, sigma_y_class_d(u * age, 2.0), 1e-12) << age;
    EXPECT_NEAR(s.sigma_vertical_m, sigma_z_class_d(u * age, 2.0), 1e-12) << age;
  }
}

TEST(DispersionModel, GroundCentrelineMatchesTheClosedForm) {
  // docs/domain.md §3.1 at z = 0, y = 0 on the centre, H = 0:
  //   C = 2 Q / ((2π)^{3/2} σx σy σz).
  const DispersionConfig c = single_device();
  const DispersionModel model(c);
  const double u = 3.0 * std::pow(0.1, 0.15);
  for (double age : {2.0, 20.0, 60.0}) {
    const double x = u * age;
    const double sy = sigma_y_class_d(x, 2.0), sz = sigma_z_class_d(x, 2.0);
    const double expected = 2 * 500.0 / (std::pow(2 * std::numbers::pi, 1.5) * sy * sy * sz);
    const Vec3 centre(12.0 + x, -7.0, 0.0);
    EXPECT_NEAR(model.concentration_g_m3(centre, 1.5 + age), expected, 1e-12 * expected) << age;
    // One σ across the wind: e^{−½} of it; one σ along: the same.
    EXPECT_NEAR(model.concentration_g_m3(centre + Vec3(0, sy, 0), 1.5 + age),
                expected * std::exp(-0.5), 1e-12 * expected);
    EXPECT_NEAR(model.concentration_g_m3(centre + Vec3(-sy, 0, 0), 1.5 + age),
                expected * std::exp(-0.5), 1e-12 * expected);
  }
}

TEST(DispersionModel, ElevatedReleaseMatchesTheClosedFormWithItsImage) {
  DispersionConfig c = single_device();
  c.devices[0].release_height_m = 6.0;
  c.wind.power_law_exponent = 0.0;  // 3 m/s at every height
  const DispersionModel model(c);
  const double age = 15.0, x = 3.0 * age, h = 6.0;
  const double sy = sigma_y_class_d(x, 2.0), sz = sigma_z_class_d(x, 2.0);
  const double q = 500.0 / (std::pow(2 * std::numbers::pi, 1.5) * sy * sy * sz);
  const Vec3 ground(12.0 + x, -7.0, 0.0);
  EXPECT_NEAR(model.concentration_g_m3(ground, 1.5 + age), 2 * q * std::exp(-h * h / (2 * sz * sz)),
              1e-12 * q);
  EXPECT_NEAR(model.concentration_g_m3(ground + Vec3(0, 0, h), 1.5 + age),
              q * (1 + std::exp(-4 * h * h / (2 * sz * sz))), 1e-12 * q);
}

TEST(DispersionModel, GroundReflectionDoublesGroundConcentrationOfAGroundRelease) {
  // Without the image the ground value of a puff centred on the ground would
  // be Q/((2π)^{3/2} σ²σz); the reflected mass exactly doubles it, and a point
  // just above the ground sees two equal contributions.
  const DispersionModel model(single_device());
  const PuffState s = model.puffs_at(10.0)[0];
  const double single = s.mass_g / (std::pow(2 * std::numbers::pi, 1.5) * s.sigma_horizontal_m *
                                    s.sigma_horizontal_m * s.sigma_vertical_m);
  const Vec3 p(s.centre_m.x, s.centre_m.y, 0.0);
  EXPECT_NEAR(model.concentration_g_m3(p, 10.0) / single, 2.0, 1e-12);
  EXPECT_EQ(model.concentration_g_m3(p + Vec3(0, 0, -0.1), 10.0), 0.0);  // below the ground
}

TEST(DispersionModel, NothingBeforeTheReleaseAndReleasedMassGrowsWithTheBurn) {
  const DispersionModel model(single_device(4.0));  // 40 puffs over 4 s from t = 1.5 s
  EXPECT_EQ(model.released_mass_g(1.0), 0.0);
  EXPECT_EQ(model.concentration_g_m3({12, -7, 0}, 1.0), 0.0);
  EXPECT_TRUE(model.puffs_at(1.0).empty());
  EXPECT_NEAR(model.released_mass_g(3.5), 250.0, 1e-9);  // half the burn: 20 puffs
  EXPECT_EQ(model.puffs_at(3.5).size(), 20u);
  EXPECT_NEAR(model.released_mass_g(100.0), 500.0, 1e-9);
}

TEST(DispersionModel, TemperatureIsAmbientWithoutExcess) {
  const DispersionModel model(single_device(3.0));
  for (const Vec3& p : {Vec3(12, -7, 0), Vec3(20, -7, 1), Vec3(500, 0, 0)})
    EXPECT_EQ(model.temperature_k(p, 3.0), 290.0);
  EXPECT_EQ(model.temperature_k({12, -7, 0}, 0.0), 290.0);  // before any smoke
}

TEST(DispersionModel, FreshPuffIsAtAmbientPlusExcessAndDecaysWithAge) {
  DispersionConfig c = single_device();
  c.devices[0].source_temperature_excess_k = 40.0;
  c.devices[0].temperature_decay_time_s = 8.0;
  const DispersionModel model(c);
  // At its release instant the only puff has its full excess everywhere it is.
  EXPECT_NEAR(model.temperature_k({12, -7, 0}, 1.5), 330.0, 1e-9);
  EXPECT_NEAR(model.temperature_k({13, -6, 2}, 1.5), 330.0, 1e-9);
  // One decay time later: ambient + excess / e.
  const PuffState s = model.puffs_at(9.5)[0];
  EXPECT_NEAR(model.temperature_k(s.centre_m, 9.5), 290.0 + 40.0 / std::numbers::e, 1e-9);
}

TEST(DispersionModel, TemperatureMixesPuffsByConcentrationShare) {
  // Two co-located bursts with excesses 10 K and 30 K and masses 1 : 3 have
  // identical shapes, so everywhere the mix is (1·10 + 3·30) / 4 = 25 K.
  DispersionConfig c = single_device();
  c.devices[0].source_temperature_excess_k = 10.0;
  c.devices[0].temperature_decay_time_s = 1e9;
  c.devices.push_back(c.devices[0]);
  c.devices[1].agent_mass_g = 1500.0;
  c.devices[1].source_temperature_excess_k = 30.0;
  const DispersionModel model(c);
  for (const Vec3& p : {Vec3(20, -7, 0), Vec3(25, -3, 4)})
    EXPECT_NEAR(model.temperature_k(p, 5.0), 315.0, 1e-6);
}

TEST(DispersionModel, InvalidConfigurationIsRefusedNamingTheField) {
  DispersionConfig c = single_device();
  c.devices.push_back(c.devices[0]);
  c.devices[1].initial_sigma_m = 0.0;
  c.source = "scenario.json";
  try {
    DispersionModel model(c);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scenario.json");
    EXPECT_EQ(e.field(), "/dispersion/devices/1/initial_sigma_m");
  }
}

}  // namespace
}  // namespace obscura
