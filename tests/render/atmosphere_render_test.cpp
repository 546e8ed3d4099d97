// The atmosphere between sensor and scene (scene/atmosphere.h) against its
// closed form, L = τ L_scene + (1 − τ) B_band(T_air) with τ = exp(−β d), where
// band radiances come from an independent fine Simpson integral of Planck's
// law, not from the renderer's quadrature.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "obscura/core/planck.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/renderer.h"

namespace obscura {
namespace {

// ∫ B_λ(T) dλ over [lo, hi] µm by Simpson's rule on 4000 intervals.
double band_planck(double lo, double hi, double t) {
  const int n = 4000;
  const double h = (hi - lo) / n;
  double s = planck_radiance(lo, t) + planck_radiance(hi, t);
  for (int i = 1; i < n; ++i) s += (i % 2 ? 4.0 : 2.0) * planck_radiance(lo + i * h, t);
  return s * h / 3.0;
}

// A camera 400 m up looking straight down at a blackbody ground (3×3 pixels over 1°).
Scene ground_scene(double ground_k) {
  Scene scene;
  Sensor sensor;
  sensor.name = "cam";
  sensor.camera = PinholeCamera({0, 0, 400}, {0, 0, 0}, {0, 1, 0}, 1.0, 3, 3);
  sensor.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{ground_k, 1.0}, 0.0));
  scene.sky = Sky::blackbody(0.0, true);
  scene.settings.spectral_nodes_per_band = 8;
  scene.atmosphere.enabled = true;
  scene.atmosphere.temperature_k = 288.0;
  scene.atmosphere.extinction_per_m = {{"mwir", 0.4e-3}, {"lwir", 0.15e-3}};
  return scene;
}

TEST(AtmosphereRender, GroundThroughAirMatchesClosedForm) {
  const Scene scene = ground_scene(320.0);
  const SensorImage img = render_sensor(scene, scene.sensors[0], {});
  const int centre = 4;  // the pixel looking straight down: d = 400 m
  const double betas[2] = {0.4e-3, 0.15e-3};
  for (int b = 0; b < 2; ++b) {
    const Band& band = scene.sensors[0].bands[b];
    const double tau = std::exp(-betas[b] * 400.0);
    const double expected = tau * band_planck(band.lo_um(), band.hi_um(), 320.0) +
                            (1.0 - tau) * band_planck(band.lo_um(), band.hi_um(), 288.0);
    EXPECT_NEAR(img.bands[b].radiance[centre], expected, 2e-6 * expected) << band.name();
    // The transmittance image is the clouds' alone: there are none.
    EXPECT_EQ(img.bands[b].transmittance[centre], 1.0f);
  }
}

// Air at the ground's temperature is invisible (Kirchhoff): the ground keeps
// its apparent temperature at any range.
TEST(AtmosphereRender, AirAtGroundTemperatureChangesNothing) {
  Scene scene = ground_scene(288.0);
  scene.atmosphere.extinction_per_m = {{"*", 5e-3}};
  const SensorImage img = render_sensor(scene, scene.sensors[0], {});
  for (const BandImage& b : img.bands)
    for (float t : b.apparent_temperature) EXPECT_NEAR(t, 288.0, 1e-3);
}

// A ray that meets no surface crosses the air only up to where it leaves the
// clouds' box; one that meets neither sees the sky as given.
TEST(AtmosphereRender, RaysWithoutSurfaceUseTheCloudsExtent) {
  Scene scene;
  Sensor sensor;
  sensor.name = "cam";
  // Level camera, 2 pixels: the left looks through a cloud box 100–110 m
  // away, the right past it, at the sky.
  sensor.camera = PinholeCamera({0, 0, 0}, {0, 100, 0}, {0, 0, 1}, 20.0, 2, 1);
  sensor.bands = {Band::preset("lwir")};
  scene.sensors.push_back(sensor);
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-30, 100, -5}, {-0.01, 110, 5}), std::vector<double>{10.0}, std::vector<double>{0.0},
      std::vector<double>{0.0}, std::vector<double>{0.0}, 300.0);  // σ = 0: empty air box
  scene.sky = Sky::blackbody(220.0, true);
  scene.settings.spectral_nodes_per_band = 8;
  scene.atmosphere.enabled = true;
  scene.atmosphere.temperature_k = 290.0;
  scene.atmosphere.extinction_per_m = {{"lwir", 1e-3}};
  const SensorImage img = render_sensor(scene, scene.sensors[0], {});
  const double sky = band_planck(8, 12, 220.0), air = band_planck(8, 12, 290.0);
  // Left pixel centre: 10° towards −x (half the 20° vertical field times the
  // aspect ratio 2, through tan); it leaves the box at y = 110.
  const double d = 110.0 / std::cos(10.0 * std::acos(-1.0) / 180.0);
  const double tau = std::exp(-1e-3 * d);
  EXPECT_NEAR(img.bands[0].radiance[0], tau * sky + (1 - tau) * air, 1e-5 * air);
  EXPECT_NEAR(img.bands[0].radiance[1], sky, 1e-5 * sky);
}

// An emissivity table: ε = 0.2 below 6 µm, 0.9 above (step between 5.99 and
// 6.01 µm). Over a black sky the ground is seen at ε B(T) in each band.
TEST(AtmosphereRender, SpectralEmissivityPerBand) {
  Scene scene = ground_scene(300.0);
  scene.atmosphere = Atmosphere{};
  SurfaceMaterial m{300.0, 1.0, {{5.99, 0.2}, {6.01, 0.9}}};
  scene.surfaces.clear();
  scene.surfaces.push_back(std::make_unique<GroundPlane>("ground", m, 0.0));
  const SensorImage img = render_sensor(scene, scene.sensors[0], {});
  EXPECT_NEAR(img.bands[0].radiance[4], 0.2 * band_planck(3, 5, 300.0),
              1e-6 * band_planck(3, 5, 300.0));
  EXPECT_NEAR(img.bands[1].radiance[4], 0.9 * band_planck(8, 12, 300.0),
              1e-6 * band_planck(8, 12, 300.0));
}

}  // namespace
}  // namespace obscura

namespace obscura {
namespace {

// Kirchhoff with a spectral emissivity: a ground whose ε varies across the
// band, under a sky at its own temperature, looks like a blackbody to every
// method (ε B + (1 − ε) B at each wavelength).
TEST(AtmosphereRender, SpectralEmissivityInEquilibriumLooksBlackToEveryMethod) {
  for (const RenderMethod method : kRenderMethods) {
    Scene scene = ground_scene(300.0);
    scene.atmosphere = Atmosphere{};
    scene.sky = Sky::blackbody(300.0, true);
    scene.surfaces.clear();
    scene.surfaces.push_back(std::make_unique<GroundPlane>(
        "ground", SurfaceMaterial{300.0, 1.0, {{3.0, 0.1}, {5.0, 0.8}, {8.0, 0.3}, {12.0, 0.95}}},
        0.0));
    // A thin scattering box (the photon map needs a medium to work on); the
    // emission–absorption method treats scattering as loss, so it sees none.
    if (method != RenderMethod::kEmissionAbsorption)
      scene.medium = std::make_shared<HomogeneousMedium>(
          BBox3({-5, -5, 0}, {5, 5, 1}), std::vector<double>{4.0}, std::vector<double>{0.0},
          std::vector<double>{0.01}, std::vector<double>{0.0}, 300.0);
    scene.settings.method = method;
    scene.settings.samples_per_pixel = 16;
    scene.settings.photon_map.photons_per_node = 2000;
    const SensorImage img = render_sensor(scene, scene.sensors[0], {});
    // The photon map's in-scattering estimate from 2000 photons is noisy at
    // the 0.2 % level: 0.3 K (0.4 % of LWIR radiance) for it, 0.05 K for the
    // others. (The radiance cache read 0.05–0.16 K low here until each
    // environment line launched a photon per piece between the surfaces it
    // crosses and the kernel integrals were clipped to the box; it now reads
    // within 0.035 K: docs/validation.md.)
    const double tolerance_k = method == RenderMethod::kPhotonMap ? 0.3 : 0.05;
    for (const BandImage& b : img.bands)
      for (float t : b.apparent_temperature)
        EXPECT_NEAR(t, 300.0, tolerance_k) << render_method_name(method) << " " << b.band.name();
  }
}

}  // namespace
}  // namespace obscura
