#include "obscura/core/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "support/chi2.h"

namespace obscura {
namespace {

using testing::chi2_passes;
using testing::chi2_sphere;

constexpr double kPi = std::numbers::pi;
constexpr double kSunHalfAngle = 0.00465;  // rad

// A warp under test: forward map, its density at a local direction, its inverse.
struct Warp {
  std::string name;
  std::function<Vec3(double, double)> sample;
  std::function<double(const Vec3&)> pdf;
  std::function<SquareSample(const Vec3&)> invert;
  std::vector<double> cos_theta_edges;  // resolves the support, edges on discontinuities
};

std::vector<Warp> all_warps() {
  const double sun = std::cos(kSunHalfAngle), wide = std::cos(0.3);
  std::vector<Warp> w;
  w.push_back({"uniform sphere", sample_uniform_sphere,
               [](const Vec3&) { return uniform_sphere_pdf(); }, invert_uniform_sphere,
               testing::uniform_cos_theta_edges(20)});
  w.push_back({"cosine hemisphere", sample_cosine_hemisphere,
               [](const Vec3& d) { return cosine_hemisphere_pdf(d.z); }, invert_cosine_hemisphere,
               testing::uniform_cos_theta_edges(20)});
  for (const auto& [name, c] : {std::pair{"sun cone 0.00465 rad", sun}, {"cone 0.3 rad", wide}})
    w.push_back({name, [c](double u1, double u2) { return sample_uniform_cone(u1, u2, c); },
                 [c](const Vec3& d) { return uniform_cone_pdf(d, c); },
                 [c](const Vec3& d) { return invert_uniform_cone(d, c); },
                 testing::cone_cos_theta_edges(c, 10)});
  return w;
}

// u values for round trips: a grid avoiding the poles and the concentric map's
// centre (u = 1/2 exactly), plus values next to the square's edges.
std::vector<double> u_values() {
  std::vector<double> u;
  constexpr int kN = 64;
  for (int i = 0; i < kN; ++i) u.push_back((i + 0.5) / kN);
  for (double e : {1e-9, 1e-6, 1.0 - 1e-6, 1.0 - 1e-9}) u.push_back(e);
  return u;
}

double circular_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 1.0 - d);
}

TEST(Sampling, PdfsIntegrateToOne) {
  for (const Warp& w : all_warps()) {
    EXPECT_NEAR(testing::integrate_sphere(w.pdf, w.cos_theta_edges), 1.0, 1e-9) << w.name;
  }
}

TEST(Sampling, SamplesAreUnitVectors) {
  for (const Warp& w : all_warps())
    for (double u1 : u_values())
      for (double u2 : u_values()) {
        const Vec3 d = w.sample(u1, u2);
        ASSERT_NEAR(length(d), 1.0, 1e-14) << w.name << " u = " << u1 << ", " << u2;
        ASSERT_GT(w.pdf(d), 0.0) << w.name << " sample outside its own support";
      }
}

TEST(Sampling, InverseRoundTrip) {
  for (const Warp& w : all_warps()) {
    double worst = 0.0;
    for (double u1 : u_values())
      for (double u2 : u_values()) {
        const SquareSample back = w.invert(w.sample(u1, u2));
        const double err = std::max(std::abs(back.u1 - u1), circular_distance(back.u2, u2));
        worst = std::max(worst, err);
        ASSERT_LT(err, 1e-9) << w.name << " u = (" << u1 << ", " << u2 << ") came back as ("
                             << back.u1 << ", " << back.u2 << ")";
      }
    std::printf("[ warp     ] %-24s worst round-trip error %.3g\n", w.name.c_str(), worst);
  }
}

// The density is the inverse Jacobian of the warp: dΩ = |∂d/∂u1 × ∂d/∂u2| du1 du2
// = du1 du2 / pdf. Central differences at points away from the concentric map's
// seams (the square's diagonals and midlines).
TEST(Sampling, PdfIsInverseJacobian) {
  const std::vector<SquareSample> points{{0.3, 0.8}, {0.7, 0.15}, {0.9, 0.55}, {0.12, 0.4}};
  constexpr double kStep = 1e-5;
  for (const Warp& w : all_warps())
    for (const SquareSample& p : points) {
      const Vec3 d1 = (w.sample(p.u1 + kStep, p.u2) - w.sample(p.u1 - kStep, p.u2)) / (2 * kStep);
      const Vec3 d2 = (w.sample(p.u1, p.u2 + kStep) - w.sample(p.u1, p.u2 - kStep)) / (2 * kStep);
      const double jacobian = length(cross(d1, d2));
      const double pdf = w.pdf(w.sample(p.u1, p.u2));
      EXPECT_NEAR(jacobian * pdf, 1.0, 1e-6) << w.name << " at (" << p.u1 << ", " << p.u2 << ")";
    }
}

TEST(Sampling, SunConeKeepsItsPrecision) {
  const double cos_max = std::cos(kSunHalfAngle);
  const double h = 1.0 - cos_max;
  for (double u1 : u_values())
    for (double u2 : {0.1, 0.6}) {
      const Vec3 d = sample_uniform_cone(u1, u2, cos_max);
      // 1 − cos θ = u1 (1 − cos θmax) to full relative precision.
      EXPECT_NEAR(one_minus_cos_theta(d) / (u1 * h), 1.0, 1e-14);
      // The angle from the axis, from the chord |d − z| = 2 sin(θ/2), stays in the cone.
      const double theta = 2.0 * std::asin(0.5 * length(d - Vec3{0, 0, 1}));
      EXPECT_LE(theta, kSunHalfAngle * (1.0 + 1e-12));
      EXPECT_NEAR(theta, 2.0 * std::asin(std::sqrt(u1) * std::sin(0.5 * kSunHalfAngle)), 1e-15);
    }
}

TEST(Sampling, FrameRoundTrip) {
  const std::vector<Vec3> axes{{0, 0, 1},
                               {0, 0, -1},
                               {1, 0, 0},
                               normalize(Vec3{0.3, -0.5, 0.81}),
                               normalize(Vec3{-1e-9, 2e-9, -1})};
  const Vec3 v = normalize(Vec3{0.2, 0.7, -0.4});
  for (const Vec3& a : axes) {
    const Vec3 z = local_to_world(a, {0, 0, 1});
    EXPECT_NEAR(length(z - a), 0.0, 1e-15);
    const Vec3 back = world_to_local(a, local_to_world(a, v));
    EXPECT_NEAR(length(back - v), 0.0, 1e-15);
    EXPECT_NEAR(length(local_to_world(a, v)), 1.0, 1e-15);
  }
}

// Chi-square tests (tests/support/chi2.h): one case per test, p > 1e-3.
constexpr int kSamples = 1000000;

testing::Chi2Result chi2_for(const Warp& w, int phi_bins, std::uint64_t seed) {
  return chi2_sphere([&](Rng& rng) { return w.sample(rng.uniform(), rng.uniform()); }, w.pdf,
                     kSamples, w.cos_theta_edges, phi_bins, seed);
}

TEST(Sampling, UniformSphereChiSquare) {
  EXPECT_TRUE(chi2_passes("uniform sphere", chi2_for(all_warps()[0], 20, 1)));
}

TEST(Sampling, CosineHemisphereChiSquare) {
  EXPECT_TRUE(chi2_passes("cosine hemisphere", chi2_for(all_warps()[1], 20, 2)));
}

TEST(Sampling, SunConeChiSquare) {
  EXPECT_TRUE(chi2_passes("sun cone 0.00465 rad", chi2_for(all_warps()[2], 16, 3)));
}

TEST(Sampling, WideConeChiSquare) {
  EXPECT_TRUE(chi2_passes("cone 0.3 rad", chi2_for(all_warps()[3], 16, 4)));
}

// The sun cone about a tilted axis, through the frame helpers; binned about that axis.
TEST(Sampling, TiltedSunConeChiSquare) {
  const double cos_max = std::cos(kSunHalfAngle);
  const Vec3 axis = normalize(Vec3{0.3, -0.5, 0.81});
  const auto r = chi2_sphere(
      [&](Rng& rng) {
        return local_to_world(axis, sample_uniform_cone(rng.uniform(), rng.uniform(), cos_max));
      },
      [&](const Vec3& d) { return uniform_cone_pdf(world_to_local(axis, d), cos_max); }, kSamples,
      testing::cone_cos_theta_edges(cos_max, 10), 16, 5, axis);
  EXPECT_TRUE(chi2_passes("sun cone about a tilted axis", r));
}

}  // namespace
}  // namespace obscura
