// Screening metrics (analysis/screening_metrics.h): percentiles, the time to
// screen and screening duration on hand-made series, and rendered scenes with
// known answers (no cloud; an opaque cloud).
#include "obscura/analysis/screening_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "obscura/core/error.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/render/renderer.h"

namespace obscura {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

TEST(Percentile, LinearInterpolationBetweenOrderStatistics) {
  const std::vector<double> v = {3, 1, 2, 4};  // sorted: 1 2 3 4, h = 3p
  EXPECT_DOUBLE_EQ(percentile(v, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(percentile(v, 1.0), 4.0);
  EXPECT_DOUBLE_EQ(percentile(v, 0.5), 2.5);
  EXPECT_DOUBLE_EQ(percentile(v, 0.1), 1.3);
  EXPECT_DOUBLE_EQ(percentile(v, 0.9), 3.7);
  EXPECT_DOUBLE_EQ(percentile({7.0}, 0.1), 7.0);
  EXPECT_TRUE(std::isnan(percentile({}, 0.5)));
  EXPECT_THROW(percentile(v, 1.5), Error);
  EXPECT_THROW(percentile(v, -0.1), Error);
}

TEST(ScreeningTimes, CrossingIsInterpolatedBetweenFrames) {
  // 0.5 at 1 s, 1.0 at 2 s: 0.9 is reached at 1.8 s and held to the end.
  const auto s = screening_times({0, 1, 2, 3}, {0, 0.5, 1.0, 1.0}, 0.9, 0.5);
  ASSERT_EQ(s.intervals.size(), 1u);
  EXPECT_DOUBLE_EQ(*s.screened_from_s, 1.8);
  EXPECT_DOUBLE_EQ(*s.screened_until_s, 3.0);
  EXPECT_DOUBLE_EQ(*s.time_to_screen_s, 1.3);  // from the reference time 0.5 s
  EXPECT_DOUBLE_EQ(*s.screening_duration_s, 1.2);
}

TEST(ScreeningTimes, NeverScreened) {
  const auto s = screening_times({0, 1, 2}, {0, 0.2, 0.3}, 0.9, 0.0);
  EXPECT_TRUE(s.intervals.empty());
  EXPECT_FALSE(s.time_to_screen_s);
  EXPECT_FALSE(s.screened_from_s);
  EXPECT_FALSE(s.screened_until_s);
  ASSERT_TRUE(s.screening_duration_s);
  EXPECT_EQ(*s.screening_duration_s, 0.0);
}

TEST(ScreeningTimes, ScreenedAtTheStartCountsFromTheFirstFrame) {
  // Falls from 1 at 2 s to 0.5 at 4 s: 0.9 is crossed at 2.4 s.
  const auto s = screening_times({0, 2, 4}, {1, 1, 0.5}, 0.9, 0.0);
  ASSERT_EQ(s.intervals.size(), 1u);
  EXPECT_DOUBLE_EQ(*s.screened_from_s, 0.0);
  EXPECT_DOUBLE_EQ(*s.screened_until_s, 2.4);
  EXPECT_DOUBLE_EQ(*s.time_to_screen_s, 0.0);
  EXPECT_DOUBLE_EQ(*s.screening_duration_s, 2.4);
  // Before the reference (a static cloud, clouds activated later): negative.
  EXPECT_DOUBLE_EQ(*screening_times({0, 2, 4}, {1, 1, 0.5}, 0.9, 1.5).time_to_screen_s, -1.5);
}

TEST(ScreeningTimes, TwoIntervalsAddUp) {
  const auto s = screening_times({0, 1, 2, 3, 4, 5}, {0, 1, 0, 0, 1, 1}, 0.5, 0.0);
  ASSERT_EQ(s.intervals.size(), 2u);
  EXPECT_DOUBLE_EQ(s.intervals[0].from_s, 0.5);
  EXPECT_DOUBLE_EQ(s.intervals[0].until_s, 1.5);
  EXPECT_DOUBLE_EQ(s.intervals[1].from_s, 3.5);
  EXPECT_DOUBLE_EQ(s.intervals[1].until_s, 5.0);
  EXPECT_DOUBLE_EQ(*s.screened_from_s, 0.5);
  EXPECT_DOUBLE_EQ(*s.screened_until_s, 1.5);
  EXPECT_DOUBLE_EQ(*s.time_to_screen_s, 0.5);
  EXPECT_DOUBLE_EQ(*s.screening_duration_s, 2.5);
}

TEST(ScreeningTimes, TouchingTheCriterionAtOneFrameReachesItForNoTime) {
  const auto s = screening_times({0, 1, 2}, {0, 0.9, 0}, 0.9, 0.0);
  ASSERT_EQ(s.intervals.size(), 1u);
  EXPECT_DOUBLE_EQ(*s.time_to_screen_s, 1.0);
  EXPECT_DOUBLE_EQ(*s.screening_duration_s, 0.0);
  // One frame: screened or not, for no time.
  const auto one = screening_times({3}, {1}, 0.9, 0.0);
  EXPECT_DOUBLE_EQ(*one.screened_from_s, 3.0);
  EXPECT_DOUBLE_EQ(*one.screening_duration_s, 0.0);
}

TEST(ScreeningTimes, UndefinedFractionsAndBadTimes) {
  const auto s = screening_times({0, 1}, {kNaN, kNaN}, 0.9, 0.0);
  EXPECT_FALSE(s.time_to_screen_s);
  EXPECT_FALSE(s.screening_duration_s);
  EXPECT_THROW(screening_times({0, 1, 1}, {0, 0, 0}, 0.9, 0.0), Error);
  EXPECT_THROW(screening_times({0, 1}, {0}, 0.9, 0.0), Error);
}

ScreeningMetrics row(double t, const std::string& band, double fraction, double mean_t) {
  ScreeningMetrics m;
  m.time_s = t;
  m.sensor = "ir";
  m.band = Band::preset(band);
  m.target_pixels = 10;
  m.screened_fraction = fraction;
  m.transmittance_mean = mean_t;
  return m;
}

TEST(SummarizeScreening, GroupsBySensorAndBandInTimeOrder) {
  // Frames out of order, two bands interleaved.
  const std::vector<ScreeningMetrics> rows = {row(2, "mwir", 1.0, 0.01), row(0, "mwir", 0.0, 1.0),
                                              row(0, "lwir", 0.0, 1.0),  row(1, "mwir", 0.5, 0.4),
                                              row(2, "lwir", 0.2, 0.6),  row(1, "lwir", 0.1, 0.5)};
  const auto s = summarize_screening(rows, MetricsSettings{}, 0.25);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].band.name(), "mwir");
  EXPECT_EQ(s[0].times_s, (std::vector<double>{0, 1, 2}));
  EXPECT_DOUBLE_EQ(*s[0].screening.screened_from_s, 1.8);  // 0.5 → 1.0 crosses 0.9 at 1.8 s
  EXPECT_DOUBLE_EQ(*s[0].screening.time_to_screen_s, 1.55);
  EXPECT_DOUBLE_EQ(s[0].max_screened_fraction, 1.0);
  EXPECT_DOUBLE_EQ(s[0].min_transmittance_mean, 0.01);
  EXPECT_DOUBLE_EQ(s[0].min_transmittance_mean_time_s, 2.0);
  EXPECT_EQ(s[1].band.name(), "lwir");
  EXPECT_FALSE(s[1].screening.time_to_screen_s);
  EXPECT_DOUBLE_EQ(s[1].max_screened_fraction, 0.2);
}

// Band radiance of a blackbody from the high-accuracy quadrature (relative
// error < 1e-9), not the renderer's 8-node one.
double band_planck(const Band& band, double t) {
  return BandQuadrature::accurate(band).blackbody_radiance(t);
}

// A blackbody box target at 330 K on a blackbody ground at 290 K, black sky,
// seen from above at 45° (every pixel sees the ground or the box).
constexpr double kTargetK = 330.0, kGroundK = 290.0;
Scene target_scene() {
  Scene scene;
  Sensor s;
  s.name = "ir";
  s.camera = PinholeCamera({0, -20, 20}, {0, 0, 1}, {0, 0, 1}, 20, 48, 36);
  s.bands = {Band::preset("mwir"), Band::preset("lwir")};
  scene.sensors.push_back(s);
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{kGroundK, 1.0}, 0.0));
  auto box = std::make_unique<BoxSurface>("tank", SurfaceMaterial{kTargetK, 1.0},
                                          BBox3({-2, -2, 0}, {2, 2, 2}));
  box->set_target(true);
  scene.surfaces.push_back(std::move(box));
  scene.settings.spectral_nodes_per_band = 8;
  return scene;
}

std::vector<ScreeningMetrics> render_metrics(Scene& scene) {
  scene.settings.threads = 2;
  const SensorImage image = render_sensor(scene, scene.sensors[0]);
  const TargetMask mask =
      compute_target_mask(scene, scene.sensors[0], scene.metrics.background_margin_px);
  return screening_metrics(image, mask, scene.metrics, scene.settings, 1.5);
}

TEST(ScreeningMetrics, NoCloudTargetFullyVisibleAndDeltaTFromPlanck) {
  Scene scene = target_scene();
  const auto rows = render_metrics(scene);
  ASSERT_EQ(rows.size(), 2u);
  for (const ScreeningMetrics& m : rows) {
    SCOPED_TRACE(m.band.name());
    EXPECT_EQ(m.time_s, 1.5);
    EXPECT_EQ(m.sensor, "ir");
    EXPECT_GT(m.target_pixels, 50);
    EXPECT_GT(m.background_pixels, 50);
    EXPECT_DOUBLE_EQ(m.transmittance_mean, 1.0);
    EXPECT_DOUBLE_EQ(m.transmittance_p10, 1.0);
    EXPECT_DOUBLE_EQ(m.transmittance_p90, 1.0);
    EXPECT_EQ(m.screened_fraction, 0.0);
    const double lt = band_planck(m.band, kTargetK);
    const double lb = band_planck(m.band, kGroundK);
    EXPECT_NEAR(m.target_radiance, lt, 1e-5 * lt);
    EXPECT_NEAR(m.background_radiance, lb, 1e-5 * lb);
    EXPECT_NEAR(m.contrast, (lt - lb) / lb, 1e-4 * (lt - lb) / lb);
    EXPECT_NEAR(m.target_apparent_temperature_k, kTargetK, 2e-3);
    EXPECT_NEAR(m.background_apparent_temperature_k, kGroundK, 2e-3);
    EXPECT_NEAR(m.delta_t_k, kTargetK - kGroundK, 3e-3);
  }
}

// A band rendered at its own node count (RenderSettings::spectral_nodes_by_band,
// one node here, whose band radiance is far from the exact band integral in
// a 4 µm band) is inverted with that count's quadrature, so the surfaces'
// apparent temperatures stay exact; with the other bands' 8 nodes the LWIR
// would be off by far more.
TEST(ScreeningMetrics, ABandsOwnNodeCountInvertsItsRadiance) {
  Scene scene = target_scene();
  scene.settings.spectral_nodes_by_band = {{"lwir", 1}};
  const auto rows = render_metrics(scene);
  ASSERT_EQ(rows.size(), 2u);
  for (const ScreeningMetrics& m : rows) {
    SCOPED_TRACE(m.band.name());
    EXPECT_NEAR(m.target_apparent_temperature_k, kTargetK, 2e-3);
    EXPECT_NEAR(m.background_apparent_temperature_k, kGroundK, 2e-3);
    if (m.band.name() != "lwir") continue;
    // What the other bands' count would have made of the same radiance.
    const double wrong =
        BandQuadrature(m.band, 8, 0.0).apparent_temperature(m.target_radiance) - kTargetK;
    EXPECT_GT(std::abs(wrong), 0.05);
  }
}

// The same scene through air at 270 K with β = 5e-3 /m (τ ≈ 0.87
// over the ~28 m range): no cloud still means transmittance 1, and the target
// and background radiances are the means over their pixels of
// τ_i B(T_surface) + (1 − τ_i) B(T_air), with each pixel's own range d_i
// (from the geometry) and band radiances from the accurate quadrature; ΔT is
// the difference of their apparent temperatures.
TEST(ScreeningMetrics, NoCloudThroughTheAtmosphereGivesTheSurfacesApparentDifference) {
  Scene scene = target_scene();
  scene.atmosphere.enabled = true;
  scene.atmosphere.temperature_k = 270.0;
  scene.atmosphere.extinction_per_m = {{"*", 5e-3}};
  const auto rows = render_metrics(scene);
  const TargetMask mask =
      compute_target_mask(scene, scene.sensors[0], scene.metrics.background_margin_px);
  const PinholeCamera& cam = scene.sensors[0].camera;
  ASSERT_EQ(rows.size(), 2u);
  for (const ScreeningMetrics& m : rows) {
    SCOPED_TRACE(m.band.name());
    const BandQuadrature q = BandQuadrature::accurate(m.band);
    const double air = q.blackbody_radiance(270.0);
    double sum_t = 0, sum_b = 0;
    int n_t = 0, n_b = 0;
    for (int y = 0; y < cam.height(); ++y)
      for (int x = 0; x < cam.width(); ++x) {
        const MaskLabel label = mask.labels[static_cast<std::size_t>(y) * cam.width() + x];
        if (label == MaskLabel::kOther) continue;
        SurfaceHit hit;
        ASSERT_TRUE(intersect_surfaces(scene.surfaces, cam.generate_ray(x + 0.5, y + 0.5), 0.0,
                                       std::numeric_limits<double>::infinity(), hit));
        const double tau = std::exp(-5e-3 * hit.t);
        const double surface =
            q.blackbody_radiance(label == MaskLabel::kTarget ? kTargetK : kGroundK);
        const double l = tau * surface + (1.0 - tau) * air;
        (label == MaskLabel::kTarget ? sum_t : sum_b) += l;
        ++(label == MaskLabel::kTarget ? n_t : n_b);
      }
    const double lt = sum_t / n_t, lb = sum_b / n_b;
    EXPECT_DOUBLE_EQ(m.transmittance_mean, 1.0);
    EXPECT_EQ(m.screened_fraction, 0.0);
    EXPECT_NEAR(m.target_radiance, lt, 1e-5 * lt);
    EXPECT_NEAR(m.background_radiance, lb, 1e-5 * lb);
    const double dt = q.apparent_temperature(lt) - q.apparent_temperature(lb);
    EXPECT_NEAR(m.delta_t_k, dt, 3e-3);
    // The air pulls both towards 270 K: the apparent difference is more than
    // 1 K below the surfaces' 40 K (38.2 K in the MWIR).
    EXPECT_LT(m.delta_t_k, kTargetK - kGroundK - 1.0);
  }
}

TEST(ScreeningMetrics, OpaqueCloudScreensEveryTargetPixel) {
  Scene scene = target_scene();
  // σa = 10 /m over a box that holds the target with 3 m to spare above it:
  // every line of sight to the target crosses τ > 30.
  scene.medium = std::make_shared<HomogeneousMedium>(
      BBox3({-5, -5, 0}, {5, 5, 5}), std::vector<double>{3, 13}, std::vector<double>{10, 10},
      std::vector<double>{0, 0}, std::vector<double>{0, 0}, 280.0);
  for (const ScreeningMetrics& m : render_metrics(scene)) {
    SCOPED_TRACE(m.band.name());
    EXPECT_EQ(m.screened_fraction, 1.0);
    EXPECT_LT(m.transmittance_mean, 1e-6);
    EXPECT_LT(m.transmittance_p90, 1e-6);
    // The target is seen as the cloud: a blackbody at the cloud's 280 K.
    EXPECT_NEAR(m.target_apparent_temperature_k, 280.0, 1e-2);
  }
}

TEST(ScreeningMetrics, EmptyMaskGivesUndefinedMetricsAndSizeMismatchThrows) {
  const Scene scene = target_scene();
  const SensorImage image = render_sensor(scene, scene.sensors[0], {});
  TargetMask empty;
  empty.width = image.width;
  empty.height = image.height;
  empty.labels.assign(static_cast<std::size_t>(image.width) * image.height, MaskLabel::kOther);
  finish_target_mask(empty, 8);
  const auto rows = screening_metrics(image, empty, scene.metrics, RenderSettings{}, 0.0);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].target_pixels, 0);
  EXPECT_TRUE(std::isnan(rows[0].transmittance_mean));
  EXPECT_TRUE(std::isnan(rows[0].transmittance_p50));
  EXPECT_TRUE(std::isnan(rows[0].screened_fraction));
  EXPECT_TRUE(std::isnan(rows[0].contrast));
  EXPECT_TRUE(std::isnan(rows[0].delta_t_k));

  TargetMask small = empty;
  small.width = 3;
  EXPECT_THROW(screening_metrics(image, small, scene.metrics, RenderSettings{}, 0.0), Error);
}

TEST(ScreeningMetrics, BandClassesAndReferenceTime) {
  EXPECT_TRUE(is_reflective_band(Band::preset("visible")));
  EXPECT_TRUE(is_reflective_band(Band::flat("swir", 1.5, 2.5)));
  EXPECT_FALSE(is_thermal_band(Band::preset("laser1064")));
  EXPECT_TRUE(is_thermal_band(Band::preset("mwir")));
  EXPECT_TRUE(is_thermal_band(Band::flat("edge", 2.5, 3.0)));
  const Band straddling = Band::flat("wide", 2.0, 3.0);
  EXPECT_FALSE(is_reflective_band(straddling));
  EXPECT_FALSE(is_thermal_band(straddling));
  EXPECT_EQ(screening_reference_time_s(Scene{}), 0.0);
}

}  // namespace
}  // namespace obscura
