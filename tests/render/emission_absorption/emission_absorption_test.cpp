#include "obscura/render/emission_absorption/emission_absorption.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>

#include "obscura/core/planck.h"
#include "obscura/core/sampling.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/medium/keyframe_interpolation.h"

namespace obscura {
namespace {

// One node at 10 µm with unit weight: the integrator's spectral radiance there.
SpectralNodes single_node(double wavelength_um, const std::vector<double>& medium_wl) {
  return SpectralNodes(
      BandQuadrature(Band::flat("mono", wavelength_um - 1e-6, wavelength_um + 1e-6), 1, 0.0),
      medium_wl);
}

// A laterally large slab of voxels, thickness `nz` voxels of 0.25 m along z.
std::shared_ptr<VoxelGrid> slab_grid(int nz, double sigma_a, double sigma_s,
                                     const std::function<double(int)>& temperature_of_layer) {
  GridPlacement p;
  p.origin_m = {-50, -50, 0};
  p.voxel_size_m = 0.25;
  auto g = std::make_shared<VoxelGrid>(GridDims{400, 400, nz}, p, std::vector<double>{10.0});
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < 400; ++j)
      for (int i = 0; i < 400; ++i) {
        const std::size_t v = g->index(i, j, k);
        g->sigma_a(0)[v] = static_cast<float>(sigma_a);
        g->sigma_s(0)[v] = static_cast<float>(sigma_s);
        g->temperature()[v] = static_cast<float>(temperature_of_layer(k));
      }
  return g;
}

// Isothermal absorbing–emitting slab: L = B(T)(1 − e^{−τ}) + L_bg e^{−τ} (a validation
// case, docs/validation.md).
TEST(EmissionAbsorption, IsothermalSlabMatchesClosedForm) {
  const double t_slab = 320.0, t_bg = 280.0, lam = 10.0;
  for (double sigma_a : {0.01, 0.4, 3.0, 40.0}) {
    for (double cos_theta : {1.0, 0.6, 0.25}) {
      const auto grid = slab_grid(8, sigma_a, 0.0, [&](int) { return t_slab; });
      const GridMedium medium(grid);
      const double sin_theta = std::sqrt(1 - cos_theta * cos_theta);
      const Ray ray{{0, 0, 10}, {sin_theta, 0, -cos_theta}};
      const SpectralNodes nodes = single_node(lam, medium.wavelengths_um());
      double l = 0, tr = 1;
      // Stop at the ground plane z = −1 m below the slab.
      integrate_emission_absorption(&medium, ray, 11.0 / cos_theta, nodes, 1e-6, &l, &tr);
      // The grid stores floats: the exact answer is for the stored coefficient.
      const double tau = static_cast<double>(static_cast<float>(sigma_a)) * 2.0 / cos_theta;
      const double expected_l = planck_radiance(lam, t_slab) * -std::expm1(-tau) +
                                planck_radiance(lam, t_bg) * std::exp(-tau);
      l += tr * planck_radiance(lam, t_bg);
      EXPECT_NEAR(tr, std::exp(-tau), 1e-12 + 1e-9 * std::exp(-tau));
      EXPECT_NEAR(l / expected_l, 1.0, 1e-4) << "σa=" << sigma_a << " cosθ=" << cos_theta;
    }
  }
}

// With scattering present, the emission–absorption integral is
// ∫ e^{−σt s} σa B ds = (σa/σt) B (1 − e^{−τ}); this takes the adaptive path.
TEST(EmissionAbsorption, ScatteringSlabUsesExtinctionForAttenuation) {
  const auto grid = slab_grid(4, 0.5, 1.5, [](int) { return 300.0; });
  const GridMedium medium(grid);
  const Ray ray{{0, 0, 5}, {0, 0, -1}};
  const SpectralNodes nodes = single_node(10.0, medium.wavelengths_um());
  double l = 0, tr = 1;
  integrate_emission_absorption(&medium, ray, 100.0, nodes, 1e-8, &l, &tr);
  const double tau = 2.0 * 1.0;
  EXPECT_NEAR(tr, std::exp(-tau), 1e-12);
  EXPECT_NEAR(l / (0.25 * planck_radiance(10.0, 300.0) * -std::expm1(-tau)), 1.0, 1e-7);
}

// A slab whose temperature rises linearly with depth (trilinear reconstruction
// makes T(z) piecewise linear): compare against brute-force integration of the
// RTE with 200 000 midpoint steps.
TEST(EmissionAbsorption, NonIsothermalSlabMatchesBruteForce) {
  const int nz = 10;
  const auto grid = slab_grid(nz, 0.8, 0.0, [](int k) { return 250.0 + 40.0 * k; });
  const GridMedium medium(grid);
  const Ray ray{{0.1, 0.2, 3.0}, normalize(Vec3(0.3, 0.1, -1.0))};
  const SpectralNodes nodes = single_node(4.0, medium.wavelengths_um());
  double l = 0, tr = 1;
  integrate_emission_absorption(&medium, ray, 100.0, nodes, 1e-8, &l, &tr);
  MediumPoint p;
  const int n = 200000;
  double t0 = 0, t1 = 100.0;
  ASSERT_TRUE(medium.bounds().intersect(ray, t0, t1));
  const double h = (t1 - t0) / n;
  double brute = 0, tau = 0;
  for (int i = 0; i < n; ++i) {
    medium.coefficients_at(ray.at(t0 + (i + 0.5) * h), p);
    const double dtau = p.sigma_a[0] * h;
    // Exact for a constant step: e^{−τ}(1 − e^{−Δτ}) B.
    brute += std::exp(-tau) * -std::expm1(-dtau) * planck_radiance(4.0, p.temperature_k);
    tau += dtau;
  }
  EXPECT_NEAR(l / brute, 1.0, 1e-6);
  EXPECT_NEAR(tr, std::exp(-tau), 1e-6);
}

TEST(EmissionAbsorption, NoMediumLeavesRadianceUntouched) {
  const SpectralNodes nodes = single_node(10.0, {10.0});
  double l = 1.5, tr = 0.5;
  integrate_emission_absorption(nullptr, Ray{{0, 0, 0}, {1, 0, 0}}, 10, nodes, 1e-6, &l, &tr);
  EXPECT_EQ(l, 1.5);
  EXPECT_EQ(tr, 0.5);
}

// The adaptive quadrature's cost per cell stays bounded on the animated
// example's cloud between two keyframes (the frame at 4 s took 11 times as
// long as the others: a relative test on each piece alone chased pieces of
// negligible emission to the deepest bisection, 77 integrand evaluations per
// cell here), and its answer stays within the tolerance of a much tighter one.
TEST(EmissionAbsorption, AdaptiveCostPerCellIsBoundedBetweenKeyframes) {
  GaussianPuffSpec a;
  a.center_m = {0, -12, 3};
  a.radius_m = 2.0;
  a.extent_radii = 3;
  a.resolution = 48;
  a.wavelengths_um = {4, 10};
  a.peak_sigma_a = {0.35, 0.45};
  a.peak_sigma_s = {0.1, 0.03};
  a.g = {0.6, 0.4};
  a.ambient_temperature_k = 288;
  a.temperature_excess_k = 25;
  GaussianPuffSpec b = a;
  b.radius_m = 2.8;
  b.peak_sigma_a = {0.25, 0.3};
  b.temperature_excess_k = 15;
  const GridMedium medium(std::make_shared<VoxelGrid>(
      interpolate_keyframes(make_gaussian_puff(a), make_gaussian_puff(b), 0.5)));
  const SpectralNodes nodes(BandQuadrature(Band::preset("lwir"), 8, 0.0), {4.0, 10.0});
  Rng rng(1, 0);
  EmissionAbsorptionStats stats;
  for (int i = 0; i < 100; ++i) {
    const Vec3 d = sample_uniform_sphere(rng.uniform(), rng.uniform());
    const Vec3 offset(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
    const Ray ray{Vec3(0, -12, 3) - d * 20.0 + offset * 4.0, d};
    std::array<double, kMaxSpectralNodes> l{}, t, l_tight{}, t_tight;
    t.fill(1.0);
    t_tight.fill(1.0);
    integrate_emission_absorption(&medium, ray, 1e30, nodes, 1e-6, l.data(), t.data(), &stats);
    integrate_emission_absorption(&medium, ray, 1e30, nodes, 1e-10, l_tight.data(), t_tight.data());
    for (std::size_t j = 0; j < nodes.size(); ++j)
      EXPECT_NEAR(l[j], l_tight[j], 2e-6 * l_tight[j] + 1e-300) << "ray " << i << " node " << j;
  }
  ASSERT_GT(stats.segments, 5000u);
  EXPECT_LT(static_cast<double>(stats.integrand_evals) / stats.segments, 10.0);
}

TEST(SpectralNodes, InterpolatesMediumSamplesLinearlyAndClamps) {
  const SpectralNodes nodes(BandQuadrature(Band::flat("b", 3.0, 5.0), 4, 0.0), {3.5, 4.5});
  for (const auto& n : nodes.nodes()) {
    if (n.wavelength_um <= 3.5) {
      EXPECT_EQ(n.sample0, 0);
      EXPECT_EQ(n.sample1, 0);
    } else if (n.wavelength_um >= 4.5) {
      EXPECT_EQ(n.sample0, 1);
      EXPECT_EQ(n.sample1, 1);
    } else {
      EXPECT_EQ(n.sample0, 0);
      EXPECT_EQ(n.sample1, 1);
      EXPECT_NEAR(n.frac, n.wavelength_um - 3.5, 1e-12);
    }
  }
}

}  // namespace
}  // namespace obscura
