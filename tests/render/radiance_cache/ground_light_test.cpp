// The cloud's light on flat ground (render/radiance_cache/ground_light.h)
// and the surface deposits it is made of (photon_tracing.h): the map keeps
// the power deposited on the ground inside its square and nothing else; a
// cloud that only absorbs takes sky light off the ground (every deposit
// negative); a sunlit cloud under a black sky only adds light (every
// deposit positive). Against the path tracer: the study scenes'
// test (radiance_cache_study_test.cpp), which the ground light brings within
// the 2 %.
#include "obscura/render/radiance_cache/ground_light.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <utility>

#include "obscura/core/rng.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/photon_map/photon_tracing.h"
#include "obscura/render/spectral_nodes.h"

namespace obscura {
namespace {

Scene cloud_over_ground(double sigma_a, double sigma_s) {
  Scene scene;
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-2, -2, 3}, {2, 2, 5}), std::vector<double>{0.5}, std::vector<double>{sigma_a},
      std::vector<double>{sigma_s}, std::vector<double>{0.5}, 0.0);
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", SurfaceMaterial{0.0, 0.5}, 0.0));
  scene.surfaces.push_back(
      std::make_unique<BoxSurface>("box", SurfaceMaterial{0.0, 0.5}, BBox3({5, 5, 0}, {6, 6, 1})));
  return scene;
}

TEST(GroundLight, KeepsThePowerDepositedOnTheGroundInsideItsSquare) {
  const Scene scene = cloud_over_ground(0.1, 0.5);
  std::vector<SurfaceDeposit> deposits;
  Rng rng(5, 0);
  double inside = 0.0;
  for (int i = 0; i < 2000; ++i) {
    const float x = static_cast<float>(-12.0 + 24.0 * rng.uniform()),
                y = static_cast<float>(-12.0 + 24.0 * rng.uniform());
    const float power = static_cast<float>(rng.uniform() - 0.3);
    const int surface = i % 5 == 0 ? 1 : 0;  // some on the box, which is not ground
    deposits.push_back(SurfaceDeposit{{x, y, 0.0f}, power, surface});
    if (surface == 0 && std::abs(x) < 10.0 && std::abs(y) < 10.0) inside += power;
  }
  const GroundLight ground(scene, deposits, Vec3(0, 0, 4), 10.0);
  EXPECT_TRUE(ground.covers(0));
  EXPECT_FALSE(ground.covers(1));
  EXPECT_NEAR(ground.total_power_w_um(), inside, 1e-5 * std::abs(inside) + 1e-9);
  EXPECT_EQ(ground.irradiance(Vec3(11, 0, 0)), 0.0);  // outside the square
  // One deposit on a node reads power / cell area there.
  const double cell = 20.0 / GroundLight::kCells;
  const GroundLight one(scene, {SurfaceDeposit{{0.0f, 0.0f, 0.0f}, 2.0f, 0}}, Vec3(0, 0, 4), 10.0);
  EXPECT_NEAR(one.irradiance(Vec3(0, 0, 0)), 2.0 / (cell * cell), 1e-9);
  EXPECT_NEAR(one.irradiance(Vec3(0.5 * cell, 0, 0)), 1.0 / (cell * cell), 1e-9);
}

TEST(GroundLight, AnAbsorbingCloudTakesSkyLightAndASunlitOneAddsLight) {
  const SpectralNodes nodes(BandQuadrature(Band::flat("b", 0.499, 0.501), 1, 0.0), {0.5});
  PhotonTracingSettings settings;
  settings.photons = 20000;
  settings.surface_deposits = true;
  {
    Scene scene = cloud_over_ground(1.0, 0.0);  // absorbs only, under a bright sky
    scene.sky = Sky::blackbody(5000.0, false);
    const TracedPhotons traced = trace_photons(scene, nodes.nodes()[0], 1ull << 40, settings);
    ASSERT_GT(traced.deposits.size(), 500u);
    int on_ground = 0;
    for (const SurfaceDeposit& d : traced.deposits) {
      ASSERT_LT(d.power, 0.0f);
      on_ground += d.surface == 0;
    }
    EXPECT_GT(on_ground, 500);
  }
  {
    Scene scene = cloud_over_ground(0.0, 1.0);  // scatters the sun, no sky
    scene.sky = Sky::blackbody(0.0, false);
    scene.sun.enabled = true;
    scene.sun.elevation_deg = 70.0;
    const TracedPhotons traced = trace_photons(scene, nodes.nodes()[0], 1ull << 40, settings);
    ASSERT_GT(traced.deposits.size(), 500u);
    for (const SurfaceDeposit& d : traced.deposits) ASSERT_GT(d.power, 0.0f);
  }
  {
    PhotonTracingSettings off = settings;
    off.surface_deposits = false;
    Scene scene = cloud_over_ground(1.0, 0.0);
    scene.sky = Sky::blackbody(5000.0, false);
    EXPECT_TRUE(trace_photons(scene, nodes.nodes()[0], 1ull << 40, off).deposits.empty());
  }
}

// In a cloud that does not scatter the sun's photons and the environment's
// from surfaces deposit nothing (the radiance cache then launches none:
// sun_photons and surface_photons false), so leaving them out gives the
// sky's their share and the same ground light in expectation: the deposits'
// sums with and without agree within 4 standard errors (each photon
// deposits once at most, so a sum's variance is Σ d² − (Σ d)²/n).
TEST(GroundLight, WithoutScatteringOnlyTheSkysPhotonsAddToIt) {
  const SpectralNodes nodes(BandQuadrature(Band::flat("b", 0.499, 0.501), 1, 0.0), {0.5});
  Scene scene = cloud_over_ground(1.0, 0.0);
  scene.sky = Sky::blackbody(1700.0, false);  // about the sun's power at 0.5 µm
  scene.sun.enabled = true;
  scene.sun.elevation_deg = 60.0;
  PhotonTracingSettings with_sun;
  with_sun.photons = 40000;
  with_sun.surface_deposits = true;
  with_sun.absorb_by_weight = true;
  PhotonTracingSettings without = with_sun;
  without.sun_photons = false;
  without.surface_photons = false;
  const TracedPhotons a = trace_photons(scene, nodes.nodes()[0], 1ull << 40, with_sun);
  const TracedPhotons b = trace_photons(scene, nodes.nodes()[0], 1ull << 40, without);
  EXPECT_GT(a.launched_count[0], 10000);  // the sun takes a good share…
  EXPECT_EQ(b.launched_count[0], 0);      // … or none
  // The environment's power without the ground's and the box's light (the
  // grey ground reflects the sky).
  EXPECT_LT(b.estimated.environment_w_um, 0.9 * a.estimated.environment_w_um);
  EXPECT_GT(b.estimated.environment_w_um, 0.3 * a.estimated.environment_w_um);
  EXPECT_EQ(b.launched_count[1] + b.launched_count[2], without.photons);
  const auto sum_and_variance = [](const TracedPhotons& t) {
    const double n =
        static_cast<double>(t.launched_count[0] + t.launched_count[1] + t.launched_count[2]);
    double sum = 0.0, sum_sq = 0.0;
    for (const SurfaceDeposit& d : t.deposits) {
      sum += d.power;
      sum_sq += static_cast<double>(d.power) * d.power;
    }
    return std::pair{sum, sum_sq - sum * sum / n};
  };
  const auto [sa, va] = sum_and_variance(a);
  const auto [sb, vb] = sum_and_variance(b);
  ASSERT_LT(sa, 0.0);  // the cloud's shadow on the sky's light
  EXPECT_NEAR(sa, sb, 4.0 * std::sqrt(va + vb));
  // The sky's photons, more of them: less variance.
  const double share = static_cast<double>(a.launched_count[1] + a.launched_count[2]) /
                       static_cast<double>(without.photons);
  EXPECT_LT(vb, (share + 0.1) * va) << "share " << share;
}

}  // namespace
}  // namespace obscura
