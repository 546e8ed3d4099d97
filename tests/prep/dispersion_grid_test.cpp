#include "obscura/prep/dispersion/dispersion_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "obscura/core/error.h"

namespace obscura {
namespace {

DispersionConfig base_config() {
  DispersionConfig c;
  c.stability = StabilityClass::kD;
  c.wind.speed_m_s = 3.0;
  c.wind.from_deg = 250.0;  // oblique to the grid axes on purpose
  c.wind.power_law_exponent = 0.15;
  c.ambient_temperature_k = 290.0;
  return c;
}

SmokeDevice device(double x, double y, double burn_s, double mass_g, double sigma0_m) {
  SmokeDevice d;
  d.x_m = x;
  d.y_m = y;
  d.burn_time_s = burn_s;
  d.agent_mass_g = mass_g;
  d.initial_sigma_m = sigma0_m;
  return d;
}

double grid_mass_g(const ScalarGrid& g) {
  double sum = 0;
  for (float v : g.values) sum += v;
  return sum * g.voxel_volume_m3();
}

TEST(DispersionGrid, MassIsConservedForABurningTrainAtEveryFrame) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 8.0, 360.0, 1.5));
  c.devices[0].yield_factor = 1.7;
  c.devices[0].release_height_m = 0.5;
  const DispersionModel model(c);
  const std::vector<double> times = {1.0, 4.0, 8.0, 15.0};
  const ConcentrationSeries s = dispersion_series(model, times, {});
  ASSERT_EQ(s.frames.size(), times.size());
  for (std::size_t f = 0; f < times.size(); ++f) {
    const double released = model.released_mass_g(times[f]);
    ASSERT_GT(released, 0);
    const double rel = std::abs(grid_mass_g(s.frames[f].concentration_g_m3) / released - 1);
    // The 4σ coverage leaves at most ~2·10⁻⁴ of the end puffs outside.
    EXPECT_LT(rel, 3e-4) << "t = " << times[f];
  }
  EXPECT_NEAR(model.released_mass_g(15.0), 360.0 * 1.7, 1e-9);
}

TEST(DispersionGrid, MassIsExactWhenTheCoverageHoldsEveryTail) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(3.3, -1.2, 5.0, 500.0, 1.0));
  c.devices.push_back(device(-10.0, 8.0, 0.0, 200.0, 3.0));
  c.devices[1].start_s = 2.0;
  c.devices[1].release_height_m = 2.5;
  const DispersionModel model(c);
  DispersionGridOptions o;
  o.voxel_size_m = 0.75;
  o.coverage_sigmas = 7.0;
  const std::vector<double> times = {3.0, 10.0};
  const ConcentrationSeries s = dispersion_series(model, times, o);
  for (std::size_t f = 0; f < times.size(); ++f)
    EXPECT_NEAR(grid_mass_g(s.frames[f].concentration_g_m3) / model.released_mass_g(times[f]), 1.0,
                1e-6);
}

TEST(DispersionGrid, PuffSmallerThanAVoxelKeepsItsMassAndSplitsItAcrossVoxels) {
  // σ = 0.1 m in 1 m voxels, centred near a voxel corner and 0.3 m up: a
  // point sample at voxel centres would see almost nothing of it.
  DispersionConfig c = base_config();
  c.devices.push_back(device(4.02, -2.97, 0.0, 50.0, 0.1));
  c.devices[0].release_height_m = 0.3;
  const DispersionModel model(c);
  const ConcentrationSeries s = dispersion_series(model, {0.0}, {});
  const ScalarGrid& g = s.frames[0].concentration_g_m3;
  EXPECT_NEAR(grid_mass_g(g), 50.0, 1e-6 * 50.0);
  int occupied = 0;
  for (float v : g.values) occupied += v > 1e-3f;
  EXPECT_EQ(occupied, 4);  // the four voxels meeting at (4, −3), ground layer
  // The voxel averages are the exact box integrals: the voxel [3,4]x[-3,-2]x[0,1]
  // holds Φ-fractions of (4 − 4.02)/0.1 in x and (−2.97 + 3)/0.1 in y.
  const auto phi = [](double t) { return 0.5 * std::erfc(-t / std::numbers::sqrt2); };
  const Vec3 idx = g.placement.world_to_index({3.5, -2.5, 0.5});
  const double fx = phi(-0.2), fy = 1 - phi(-0.3);
  const double fz = (phi(7.0) - phi(-3.0)) + (phi(13.0) - phi(3.0));
  EXPECT_NEAR(g.at(static_cast<int>(std::lround(idx.x)), static_cast<int>(std::lround(idx.y)), 0),
              50.0 * fx * fy * fz, 1e-5);
}

TEST(DispersionGrid, GroundCentreVoxelMatchesTheClosedForm) {
  // The ground voxel under the centre of a ground-released puff holds the
  // average over its cube of C = 2Q/((2π)^{3/2} σ² σz) · e^{−Δx²/2σ²} … (docs/domain.md
  // §3.1). Averaging a Gaussian over a centred width h multiplies it by
  // 1 − h²/(24σ²) + O(h⁴/σ⁴) per horizontal axis, and over [0, h] from its
  // centre by 1 − h²/(6σz²) + O(h⁴/σz⁴): an independent check of the erf sums.
  DispersionConfig c = base_config();
  c.wind.from_deg = 270.0;
  const double t = 20.0, h = 0.2;
  const double u = 3.0 * std::pow(0.1, 0.15), x = u * t;
  // Put the puff centre at t on a voxel centre: (0.1, 0.1) on the 0.2 m lattice.
  c.devices.push_back(device(0.1 - x, 0.1, 0.0, 500.0, 2.0));
  const DispersionModel model(c);
  DispersionGridOptions o;
  o.voxel_size_m = h;
  const ConcentrationSeries s = dispersion_series(model, {t}, o);
  const ScalarGrid& g = s.frames[0].concentration_g_m3;
  const double sy = std::sqrt(4 + std::pow(0.06 * std::pow(x, 0.92), 2));
  const double sz = std::sqrt(4 + std::pow(0.15 * std::pow(x, 0.70), 2));
  const double point = 2 * 500.0 / (std::pow(2 * std::numbers::pi, 1.5) * sy * sy * sz);
  const Vec3 idx = g.placement.world_to_index({0.1, 0.1, 0.1});
  const int i = static_cast<int>(std::lround(idx.x)), j = static_cast<int>(std::lround(idx.y));
  ASSERT_NEAR(idx.x - i, 0.0, 1e-9);
  ASSERT_NEAR(idx.y - j, 0.0, 1e-9);
  const double averaged =
      point * std::pow(1 - h * h / (24 * sy * sy), 2) * (1 - h * h / (6 * sz * sz));
  EXPECT_NEAR(g.at(i, j, 0), averaged, 2e-5 * point);
  EXPECT_NEAR(g.at(i, j, 0), point, 2e-3 * point);
  // One σ across the wind the closed form falls by e^{−½} (to within the voxel
  // averaging, which here also has a first-order slope term, hence the tolerance).
  const Vec3 side = g.placement.world_to_index({0.1, 0.1 + sy, 0.1});
  EXPECT_NEAR(g.at(i, static_cast<int>(std::lround(side.y)), 0), point * std::exp(-0.5),
              0.03 * point);
}

TEST(DispersionGrid, GridStartsAtTheGroundAndCoversTheCloudAtEveryTime) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 10.0, 300.0, 1.0));
  c.devices[0].release_height_m = 3.0;
  const DispersionModel model(c);
  const std::vector<double> times = {2.0, 6.0, 12.0};
  DispersionGridOptions o;
  o.voxel_size_m = 0.5;
  const DispersionGridLayout layout = dispersion_grid_layout(model, times, o);
  EXPECT_EQ(layout.placement.origin_m.z, 0.0);
  EXPECT_EQ(layout.placement.voxel_size_m, 0.5);
  // Origin on the voxel lattice anchored at the world origin.
  EXPECT_DOUBLE_EQ(std::remainder(layout.placement.origin_m.x, 0.5), 0.0);
  const Vec3 lo = layout.placement.origin_m;
  const Vec3 hi = lo + Vec3(layout.dims.nx, layout.dims.ny, layout.dims.nz) * 0.5;
  for (double t : times)
    for (const PuffState& p : model.puffs_at(t)) {
      const double rh = 4 * p.sigma_horizontal_m, rz = 4 * p.sigma_vertical_m;
      EXPECT_LE(lo.x, p.centre_m.x - rh);
      EXPECT_GE(hi.x, p.centre_m.x + rh);
      EXPECT_LE(lo.y, p.centre_m.y - rh);
      EXPECT_GE(hi.y, p.centre_m.y + rh);
      EXPECT_GE(hi.z, p.centre_m.z + rz);
    }
  // And not much more: each side within a voxel of some puff's 4σ box.
  double max_x = -1e9;
  for (double t : times)
    for (const PuffState& p : model.puffs_at(t))
      max_x = std::max(max_x, p.centre_m.x + 4 * p.sigma_horizontal_m);
  EXPECT_LT(hi.x - max_x, 0.5);
}

TEST(DispersionGrid, MassCentreMovesDownwindByWindSpeedTimesAge) {
  // Checks the grid's placement convention (origin = outer corner of voxel 0)
  // and the direction: from 250° the cloud moves towards 70° (ENE).
  DispersionConfig c = base_config();
  c.devices.push_back(device(5.0, 5.0, 0.0, 100.0, 2.0));
  c.devices[0].release_height_m = 2.0;
  const DispersionModel model(c);
  const double t = 12.0;
  const ConcentrationSeries s = dispersion_series(model, {t}, {});
  const ScalarGrid& g = s.frames[0].concentration_g_m3;
  Vec3 centroid;
  double total = 0;
  for (int k = 0; k < g.dims.nz; ++k)
    for (int j = 0; j < g.dims.ny; ++j)
      for (int i = 0; i < g.dims.nx; ++i) {
        const double v = g.at(i, j, k);
        centroid += g.placement.index_to_world(Vec3(i, j, k)) * v;
        total += v;
      }
  centroid = centroid / total;
  const double u = 3.0 * std::pow(0.2, 0.15);
  const double dir = 70.0 * std::numbers::pi / 180.0;  // bearing of the downwind direction
  EXPECT_NEAR(centroid.x, 5.0 + u * t * std::sin(dir), 1e-3);
  EXPECT_NEAR(centroid.y, 5.0 + u * t * std::cos(dir), 1e-3);
}

TEST(DispersionGrid, TemperatureGridFollowsTheMixingRule) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 0.0, 100.0, 1.5));
  c.devices.push_back(device(6, 0, 0.0, 100.0, 1.5));
  c.devices[1].source_temperature_excess_k = 50.0;
  c.devices[1].temperature_decay_time_s = 5.0;
  const DispersionModel model(c);
  const ConcentrationSeries s = dispersion_series(model, {0.0, 5.0}, {});
  for (const ConcentrationFrame& f : s.frames) {
    ASSERT_TRUE(f.temperature_k.has_value());
    const double excess_now = 50.0 * std::exp(-f.time_s / 5.0);
    float lo = 1e9f, hi = -1e9f;
    for (float v : f.temperature_k->values) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_GE(lo, 290.0f - 1e-3f);
    EXPECT_LE(hi, static_cast<float>(290.0 + excess_now) + 1e-3f);
    // Near the hot device's puff centre the mix is almost all hot smoke.
    const PuffState hot = model.puffs_at(f.time_s)[1];
    const Vec3 idx = f.temperature_k->placement.world_to_index(hot.centre_m + Vec3(1, 0, 0));
    const int i = static_cast<int>(std::lround(idx.x)), j = static_cast<int>(std::lround(idx.y));
    const ScalarGrid& cg = f.concentration_g_m3;
    EXPECT_GT(cg.at(i, j, 0), 0);
    // Voxel mixing rule against the point model at the voxel centre: close,
    // not identical (the grid mixes voxel averages).
    const Vec3 centre = cg.placement.index_to_world(Vec3(i, j, 0));
    EXPECT_NEAR(f.temperature_k->at(i, j, 0), model.temperature_k(centre, f.time_s),
                0.02 * excess_now);
  }
  // Without any excess the temperature grid is exactly ambient.
  c.devices[1].source_temperature_excess_k = 0.0;
  const ConcentrationSeries cold = dispersion_series(DispersionModel(c), {3.0}, {});
  for (float v : cold.frames[0].temperature_k->values) ASSERT_EQ(v, 290.0f);
}

TEST(DispersionGrid, ResultIsIdenticalForAnyThreadCount) {
  DispersionConfig c = base_config();
  for (int n = 0; n < 3; ++n) c.devices.push_back(device(4.0 * n, -3.0 * n, 3.0, 200.0, 1.0));
  c.devices[2].source_temperature_excess_k = 20.0;
  const DispersionModel model(c);
  for (const std::vector<double>& times :
       {std::vector<double>{4.0}, std::vector<double>{1.0, 2.0, 4.0}}) {
    DispersionGridOptions o;
    o.voxel_size_m = 0.5;
    o.threads = 1;
    const ConcentrationSeries one = dispersion_series(model, times, o);
    // Two threads also cut a frame into twice as many z slabs (4 per thread
    // when there are fewer frames than that), so this also checks that the
    // split does not change a value.
    o.threads = 2;
    const ConcentrationSeries two = dispersion_series(model, times, o);
    for (std::size_t f = 0; f < times.size(); ++f) {
      EXPECT_EQ(one.frames[f].concentration_g_m3.values, two.frames[f].concentration_g_m3.values);
      EXPECT_EQ(one.frames[f].temperature_k->values, two.frames[f].temperature_k->values);
    }
  }
}

TEST(DispersionGrid, FrameBeforeAnyReleaseIsEmptyOnTheSharedGrid) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 0.0, 100.0, 1.0));
  c.devices[0].start_s = 5.0;
  const ConcentrationSeries s = dispersion_series(DispersionModel(c), {1.0, 6.0}, {});
  EXPECT_EQ(s.frames[0].concentration_g_m3.dims, s.frames[1].concentration_g_m3.dims);
  EXPECT_EQ(grid_mass_g(s.frames[0].concentration_g_m3), 0.0);
  EXPECT_NEAR(grid_mass_g(s.frames[1].concentration_g_m3), 100.0, 0.03);
}

std::string field_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.field() + ": " + e.detail();
  }
  return "";
}

TEST(DispersionGrid, RefusesWhatWouldNotFitInMemory) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 30.0, 100.0, 1.0));
  c.source = "scenario.json";
  const DispersionModel model(c);
  DispersionGridOptions o;
  o.voxel_size_m = 1e-3;  // ~10⁵ voxels per axis of a 100 m cloud: petabytes
  const std::string m = field_of([&] { dispersion_series(model, {30.0}, o); });
  EXPECT_EQ(m.rfind("voxel_size_m: ", 0), 0u) << m;
  EXPECT_NE(m.find("available"), std::string::npos) << m;
  o.voxel_size_m = 1e-9;  // more voxels along an axis than an int holds
  EXPECT_EQ(field_of([&] { dispersion_series(model, {30.0}, o); }).rfind("voxel_size_m: ", 0), 0u);
}

TEST(DispersionGrid, RefusesBadTimesAndOptions) {
  DispersionConfig c = base_config();
  c.devices.push_back(device(0, 0, 0.0, 100.0, 1.0));
  c.devices[0].start_s = 10.0;
  const DispersionModel model(c);
  EXPECT_EQ(field_of([&] { dispersion_series(model, {}, {}); }).rfind("times_s", 0), 0u);
  EXPECT_EQ(field_of([&] {
              dispersion_series(model, {11.0, 11.0}, {});
            }).rfind("times_s/1", 0),
            0u);
  // No smoke at any requested time: nothing to put a grid around.
  const std::string none = field_of([&] { dispersion_series(model, {1.0, 2.0}, {}); });
  EXPECT_NE(none.find("no smoke"), std::string::npos) << none;
  DispersionGridOptions o;
  o.voxel_size_m = 0.0;
  EXPECT_EQ(field_of([&] { dispersion_series(model, {11.0}, o); }).rfind("voxel_size_m", 0), 0u);
}

}  // namespace
}  // namespace obscura
