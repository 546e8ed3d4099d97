// The sky: radiance by zenith angle (blackbody or table), the radiance a
// Lambertian surface reflects from it (against closed forms and an independent
// quadrature), and the sampling density used for next-event estimation
// (chi-square, normalisation).
#include "obscura/scene/sky.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "support/chi2.h"

namespace obscura {
namespace {

constexpr double kPi = std::numbers::pi;

// A sky brighter towards the horizon, black below it, at two wavelengths.
Sky horizon_brightening_sky() {
  return Sky::zenith_table({0, 20, 45, 70, 90}, {8.0, 12.0},
                           {{1.0, 2.0}, {1.2, 2.1}, {1.8, 2.6}, {3.0, 3.5}, {5.0, 4.0}});
}

// A whole-sphere table with a dark band around the horizon and a bright nadir.
Sky whole_sphere_sky() {
  return Sky::zenith_table({0, 60, 90, 120, 180}, {10.0}, {{2.0}, {1.0}, {0.0}, {0.0}, {4.0}});
}

// cos θ edges: the table's zenith angles (the pdf's discontinuities) with
// `per_interval` equal cos θ bins between consecutive ones, plus the rest of
// the sphere as one bin when the table stops at the horizon.
std::vector<double> edges_on_table(std::vector<double> zenith_deg, int per_interval) {
  std::vector<double> e;
  if (zenith_deg.back() < 180.0) e.push_back(-1.0);
  for (std::size_t i = zenith_deg.size() - 1; i > 0; --i) {
    const double c0 = std::cos(zenith_deg[i] * kPi / 180),
                 c1 = std::cos(zenith_deg[i - 1] * kPi / 180);
    for (int k = 0; k < per_interval; ++k) e.push_back(c0 + (c1 - c0) * k / per_interval);
  }
  e.push_back(1.0);
  e.front() = -1.0;
  return e;
}

// (1/π) ∫ L(ω) max(0, n·ω) dω by a brute 2-D midpoint rule in (cos θ, φ):
// independent of the sky's own kernel quadrature.
double brute_reflected(const Sky& sky, const Vec3& n, double wavelength_um) {
  const int nu = 2000, nphi = 400;
  double sum = 0.0;
  for (int i = 0; i < nu; ++i) {
    const double mu = -1.0 + (i + 0.5) * 2.0 / nu, r = std::sqrt(1 - mu * mu);
    for (int j = 0; j < nphi; ++j) {
      const double phi = (j + 0.5) * 2 * kPi / nphi;
      const Vec3 w(r * std::cos(phi), r * std::sin(phi), mu);
      sum += sky.radiance(w, wavelength_um) * std::max(0.0, dot(n, w));
    }
  }
  return sum * (2.0 / nu) * (2 * kPi / nphi) / kPi;
}

TEST(Sky, BlackSkyIsZeroEverywhere) {
  const Sky sky;
  EXPECT_TRUE(sky.is_black());
  EXPECT_EQ(sky.radiance({0, 0, 1}, 10.0), 0.0);
  EXPECT_EQ(sky.cosine_weighted_mean({0, 0, 1}, 10.0), 0.0);
  EXPECT_TRUE(Sky::blackbody(0.0, true).is_black());
}

TEST(Sky, BlackbodyAboveTheHorizonOnly) {
  const Sky full = Sky::blackbody(280.0, true), upper = Sky::blackbody(280.0, false);
  const double b = planck_radiance(10.0, 280.0);
  EXPECT_DOUBLE_EQ(full.radiance({0, 0, -1}, 10.0), b);
  EXPECT_DOUBLE_EQ(upper.radiance({0, 0, 1}, 10.0), b);
  EXPECT_EQ(upper.radiance({0, 0.6, -0.8}, 10.0), 0.0);
  // Sky view factor of a tilted plane, (1 + cos β)/2 (checked by brute force).
  for (const Vec3 n :
       {Vec3(0, 0, 1), Vec3(1, 0, 0), normalize(Vec3(0.3, 0.2, -0.7)), Vec3(0, 0, -1)}) {
    EXPECT_NEAR(upper.cosine_weighted_mean(n, 10.0), b * 0.5 * (1 + n.z), 1e-12 * b);
    EXPECT_NEAR(upper.cosine_weighted_mean(n, 10.0), brute_reflected(upper, n, 10.0), 2e-3 * b);
    EXPECT_DOUBLE_EQ(full.cosine_weighted_mean(n, 10.0), b);
  }
}

TEST(Sky, TableIsBilinearInZenithAngleAndWavelength) {
  const Sky sky = horizon_brightening_sky();
  auto dir = [](double zenith_deg) {
    const double t = zenith_deg * kPi / 180;
    return Vec3(std::sin(t), 0, std::cos(t));
  };
  EXPECT_NEAR(sky.radiance(dir(0), 8.0), 1.0, 1e-12);
  EXPECT_NEAR(sky.radiance(dir(45), 12.0), 2.6, 1e-12);
  EXPECT_NEAR(sky.radiance(dir(10), 8.0), 1.1, 1e-12);  // halfway in zenith
  EXPECT_NEAR(sky.radiance(dir(80), 10.0), 0.5 * (0.5 * (3.0 + 3.5) + 0.5 * (5.0 + 4.0)), 1e-12);
  EXPECT_NEAR(sky.radiance(dir(0), 5.0), 1.0, 1e-12);  // clamped wavelength
  EXPECT_NEAR(sky.radiance(dir(0), 20.0), 2.0, 1e-12);
  EXPECT_EQ(sky.radiance(dir(91), 10.0), 0.0);  // black below the horizon
}

TEST(Sky, ReflectedRadianceMatchesBruteForce) {
  const Sky a = horizon_brightening_sky(), b = whole_sphere_sky();
  for (const Vec3 n : {Vec3(0, 0, 1), Vec3(0, 1, 0), normalize(Vec3(0.5, 0.1, 0.4)),
                       normalize(Vec3(-0.2, 0.3, -0.9)), Vec3(0, 0, -1)}) {
    for (double w : {8.0, 9.5, 12.0}) {
      const double ref = brute_reflected(a, n, w);
      EXPECT_NEAR(a.cosine_weighted_mean(n, w), ref, 2e-3 * std::max(ref, 1.0)) << n.z << " " << w;
    }
    const double ref = brute_reflected(b, n, 10.0);
    EXPECT_NEAR(b.cosine_weighted_mean(n, 10.0), ref, 2e-3 * std::max(ref, 1.0)) << n.z;
  }
  // A constant whole-sphere table reflects its own radiance, facing anywhere
  // (the kernel quadrature and the n_z table are good to about 1e-5).
  const Sky flat = Sky::zenith_table({0, 180}, {10.0}, {{3.0}, {3.0}});
  EXPECT_NEAR(flat.cosine_weighted_mean(normalize(Vec3(0.3, -0.4, 0.2)), 10.0), 3.0, 1e-4);
}

TEST(Sky, SamplingDensitiesPassChiSquare) {
  struct Case {
    const char* name;
    Sky sky;
    std::vector<double> edges;
  };
  const Case cases[] = {
      {"blackbody whole sphere", Sky::blackbody(300, true), testing::uniform_cos_theta_edges(20)},
      {"blackbody above the horizon", Sky::blackbody(300, false), edges_on_table({0, 90}, 10)},
      {"table to the horizon", horizon_brightening_sky(), edges_on_table({0, 20, 45, 70, 90}, 3)},
      {"table over the whole sphere", whole_sphere_sky(), edges_on_table({0, 60, 90, 120, 180}, 4)},
  };
  const double threshold = testing::sidak_threshold(4);
  std::uint64_t seed = 11;
  for (const auto& c : cases) {
    const auto r = testing::chi2_sphere(
        [&](Rng& rng) {
          double pdf = 0;
          const Vec3 d = c.sky.sample(rng.uniform(), rng.uniform(), &pdf);
          EXPECT_NEAR(pdf, c.sky.pdf(d), 1e-9 * pdf);
          return d;
        },
        [&](const Vec3& d) { return c.sky.pdf(d); }, 400000, c.edges, 16, seed++);
    EXPECT_NEAR(r.pdf_integral, 1.0, 1e-6) << c.name;
    EXPECT_TRUE(testing::chi2_passes(c.name, r, threshold));
  }
}

TEST(Sky, DensityFollowsTheTable) {
  // A table twice as bright in one interval gets twice the density there.
  const Sky sky = Sky::zenith_table({0, 45, 90}, {10.0}, {{1.0}, {1.0}, {1.0}});
  const Sky bright = Sky::zenith_table({0, 30, 60, 90}, {10.0}, {{1.0}, {1.0}, {2.0}, {2.0}});
  EXPECT_NEAR(sky.pdf({0, 0, 1}), 1.0 / (2 * kPi), 1e-12);
  const double lo = bright.pdf({0, 0, 1}), hi = bright.pdf({1, 0, 1e-3});
  EXPECT_NEAR(hi / lo, 2.0, 1e-9);
  EXPECT_EQ(bright.pdf({0, 0, -1}), 0.0);
}

TEST(Sky, BadTablesNameTheField) {
  auto field_of = [](auto&& make) {
    try {
      make();
    } catch (const InputError& e) {
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of([] { Sky::zenith_table({0, 45}, {10}, {{1}, {1}}); }), "zenith_deg/1");
  EXPECT_EQ(field_of([] { Sky::zenith_table({5, 90}, {10}, {{1}, {1}}); }), "zenith_deg/0");
  EXPECT_EQ(field_of([] {
              Sky::zenith_table({0, 60, 50, 90}, {10}, {{1}, {1}, {1}, {1}});
            }),
            "zenith_deg/2");
  EXPECT_EQ(field_of([] { Sky::zenith_table({0, 90}, {10}, {{1}}); }), "radiance");
  EXPECT_EQ(field_of([] { Sky::zenith_table({0, 90}, {10, 12}, {{1, 2}, {1}}); }), "radiance/1");
  EXPECT_EQ(field_of([] { Sky::zenith_table({0, 90}, {10}, {{1}, {-1}}); }), "radiance/1/0");
  EXPECT_EQ(field_of([] {
              Sky::zenith_table({0, 90}, {12, 10}, {{1, 1}, {1, 1}});
            }),
            "wavelengths_um/1");
}

}  // namespace
}  // namespace obscura
