#include "obscura/medium/grid_medium.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "medium/test_grids.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

Ray random_ray_through(const BBox3& box, Rng& rng) {
  const Vec3 c = box.center(), e = box.extent();
  const Vec3 target(c.x + e.x * (rng.uniform() - 0.5), c.y + e.y * (rng.uniform() - 0.5),
                    c.z + e.z * (rng.uniform() - 0.5));
  const double z = 2 * rng.uniform() - 1, phi = 2 * M_PI * rng.uniform();
  const Vec3 dir(std::sqrt(1 - z * z) * std::cos(phi), std::sqrt(1 - z * z) * std::sin(phi), z);
  return Ray{target - dir * (2.0 * length(e)), dir};
}

// The segment cubics must be the exact restriction of the trilinear field to
// the ray: at any s inside a segment they equal coefficients_at(ray.at(t)).
TEST(GridMedium, SegmentCubicsEqualPointEvaluation) {
  for (const Mat3& rot : {Mat3::identity(), rotation_from_euler_deg({20, -35, 70})}) {
    const auto grid = testing::random_grid({7, 5, 9}, 2, 21, rot);
    const GridMedium medium(grid, 3);
    Rng rng(7, 0);
    MediumPoint point;
    int checked = 0;
    for (int r = 0; r < 200; ++r) {
      const Ray ray = random_ray_through(medium.bounds(), rng);
      medium.trace_segments(ray, 0, 1e9, [&](const MediumSegment& seg) {
        EXPECT_LE(seg.t_begin, seg.t_end);
        const double s = (seg.t_end - seg.t_begin) * rng.uniform();
        medium.coefficients_at(ray.at(seg.t_begin + s), point);
        EXPECT_EQ(seg.component_count, 1);
        const MediumComponent& c = seg.components[0];
        for (int k = 0; k < 2; ++k) {
          EXPECT_NEAR(c.sigma_a[k](s), point.sigma_a[k], 1e-9);
          EXPECT_NEAR(c.sigma_s[k](s), point.sigma_s[k], 1e-9);
        }
        EXPECT_NEAR(c.temperature(s), point.temperature_k, 1e-8);
        ++checked;
        return true;
      });
    }
    EXPECT_GT(checked, 1000);
  }
}

// Two samples alone (what tracking at one wavelength reads) are the same
// bits as coefficients_at gives them, with the temperature, and so is σt at
// a wavelength between them (a tentative collision's), at points inside the
// grid, in its outer half voxels and outside it.
TEST(GridMedium, TwoSamplesEqualTheWholePointsBits) {
  const auto grid = testing::random_grid({7, 5, 9}, 4, 21, rotation_from_euler_deg({20, -35, 70}));
  const GridMedium medium(grid, 3);
  const BBox3 box = medium.bounds();
  Rng rng(11, 0);
  MediumPoint all, two, scratch;
  int inside = 0;
  for (int i = 0; i < 2000; ++i) {
    // Over a box 20 % larger than the bounds: some points are outside.
    const Vec3 e = box.extent() * 1.2;
    const Vec3 p = box.center() + Vec3(e.x * (rng.uniform() - 0.5), e.y * (rng.uniform() - 0.5),
                                       e.z * (rng.uniform() - 0.5));
    const int first = static_cast<int>(rng.uniform() * 4), second = std::min(3, first + 1);
    medium.coefficients_at(p, all);
    medium.coefficients_of_samples(p, first, second, two);
    const SpectralLerp lambda{first, second, rng.uniform()};
    EXPECT_EQ(medium.extinction_at(p, lambda, scratch),
              lambda(all.sigma_a.data()) + lambda(all.sigma_s.data()))
        << i;
    for (const int s : {first, second}) {
      EXPECT_EQ(all.sigma_a[s], two.sigma_a[s]) << i;
      EXPECT_EQ(all.sigma_s[s], two.sigma_s[s]) << i;
      EXPECT_EQ(all.g[s], two.g[s]) << i;
    }
    EXPECT_EQ(all.temperature_k, two.temperature_k) << i;
    inside += all.temperature_k > 0.0;
  }
  EXPECT_GT(inside, 200);  // 290: the bounds hold the rotated grid
  EXPECT_LT(inside, 1900);
}

// A point's coefficients are the trilinear formula written out (std::floor,
// each corner's weight the product of its axes' factors, the corners summed
// in order, g weighted by scattering), bit for bit: at random points, at
// voxel centres (integer index coordinates, where the cell changes), in the
// outer half voxels (index coordinates in [−½, 0), whose truncation rounds
// the other way) and on the grid's faces.
TEST(GridMedium, APointIsTheTrilinearFormulaToTheBit) {
  const GridDims dims{7, 5, 9};
  const auto grid = testing::random_grid(dims, 2, 23);
  GridPlacement unit;  // index coordinates exact in world metres
  grid->set_placement(unit);
  const GridMedium medium(grid, 3);
  auto expected = [&](const Vec3& u, int s, double& sa, double& ss, double& g, double& t) {
    const double c[3] = {std::floor(u.x), std::floor(u.y), std::floor(u.z)};
    const double f[3] = {u.x - c[0], u.y - c[1], u.z - c[2]};
    const int n[3] = {dims.nx, dims.ny, dims.nz};
    sa = ss = g = t = 0.0;
    double gs = 0.0;
    for (int corner = 0; corner < 8; ++corner) {
      int i[3];
      double w = 1.0;
      for (int a = 0; a < 3; ++a) {
        const bool far = corner >> a & 1;
        i[a] = std::clamp(static_cast<int>(c[a]) + (far ? 1 : 0), 0, n[a] - 1);
        w = a == 0 ? (far ? f[a] : 1 - f[a]) : w * (far ? f[a] : 1 - f[a]);
      }
      const std::size_t v = grid->index(i[0], i[1], i[2]);
      sa += w * grid->sigma_a(s)[v];
      const double ssc = w * grid->sigma_s(s)[v];
      ss += ssc;
      gs += ssc * grid->g(s)[v];
      t += w * grid->temperature()[v];
    }
    g = ss > 0 ? gs / ss : 0.0;
  };
  Rng rng(5, 0);
  std::vector<Vec3> points;
  for (int i = 0; i < 500; ++i)  // anywhere in the box, outer half voxels included
    points.emplace_back((dims.nx) * rng.uniform() - 0.5, (dims.ny) * rng.uniform() - 0.5,
                        (dims.nz) * rng.uniform() - 0.5);
  for (int i = 0; i < 200; ++i)  // voxel centres and the outer half voxels' negative side
    points.emplace_back(std::floor(dims.nx * rng.uniform()), -0.5 * rng.uniform(),
                        i % 2 ? std::floor(dims.nz * rng.uniform()) : -0.25);
  points.emplace_back(-0.5, -0.5, -0.5);
  points.emplace_back(dims.nx - 0.5, dims.ny - 0.5, dims.nz - 0.5);
  points.emplace_back(-0.0, 0.0, dims.nz - 1.0);
  MediumPoint point;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& u = points[i];
    const Vec3 world = unit.index_to_world(u);
    ASSERT_EQ(unit.world_to_index(world).x, u.x);  // the unit placement is exact
    medium.coefficients_at(world, point);
    for (int s = 0; s < 2; ++s) {
      double sa, ss, g, t;
      expected(unit.world_to_index(world), s, sa, ss, g, t);
      EXPECT_EQ(point.sigma_a[s], sa) << i;
      EXPECT_EQ(point.sigma_s[s], ss) << i;
      EXPECT_EQ(point.g[s], g) << i;
      EXPECT_EQ(point.temperature_k, t) << i;
    }
  }
}

// Optical depth from the cubics against brute-force integration of the point
// evaluation (composite two-point Gauss–Legendre, 20 000 panels).
// The optical depth is Simpson's rule on march_cells' three points per cell
// (σa + σs of each sample), bit for bit, for every sample: along whole rays
// and over parts of them, through a rotated grid with empty voxels (whose
// cells both skip, so a cell's entry is not always the last one's exit).
TEST(GridMedium, OpticalDepthIsSimpsonOnTheMarchsPointsToTheBit) {
  const auto grid = testing::random_grid({9, 7, 11}, 3, 29, rotation_from_euler_deg({15, 40, -25}));
  for (std::size_t v = 0; v < grid->dims().count(); v += 3)
    for (int s = 0; s < 3; ++s) grid->sigma_a(s)[v] = grid->sigma_s(s)[v] = 0.0f;
  for (std::size_t v = 40; v < 160; ++v)  // a run of empty cells
    for (int s = 0; s < 3; ++s) grid->sigma_a(s)[v] = grid->sigma_s(s)[v] = 0.0f;
  const GridMedium medium(grid, 3);
  struct Simpson final : MarchVisitor {
    double* tau;
    explicit Simpson(double* t) : tau(t) {}
    bool visit(const MarchCell& cell) override {
      const double h = cell.t_end - cell.t_begin;
      for (int k = 0; k < cell.spectral_count; ++k) {
        const MarchPoint* p[3] = {&cell.point[0][0], &cell.point[1][0], &cell.point[2][0]};
        tau[k] +=
            h / 6.0 *
            ((p[0]->sigma_a[k] + p[0]->sigma_s[k]) + 4.0 * (p[1]->sigma_a[k] + p[1]->sigma_s[k]) +
             (p[2]->sigma_a[k] + p[2]->sigma_s[k]));
      }
      return true;
    }
  };
  Rng rng(13, 0);
  int nonzero = 0;
  for (int r = 0; r < 400; ++r) {
    const Ray ray = random_ray_through(medium.bounds(), rng);
    double t0 = 0.0, t1 = 1e9;
    if (r % 2 == 1) {  // from and to points inside the box
      double a = 0.0, b = 1e9;
      ASSERT_TRUE(medium.bounds().intersect(ray, a, b));
      t0 = a + (b - a) * 0.3 * rng.uniform();
      t1 = b - (b - a) * 0.3 * rng.uniform();
    }
    std::array<double, 3> got{0.1, 0.2, 0.3}, want = got;  // it adds to what is there
    medium.add_optical_depth(ray, t0, t1, got.data());
    Simpson simpson(want.data());
    medium.march_cells(ray, t0, t1, {}, simpson);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(got[k], want[k]) << r << " " << k;
    nonzero += got[0] > 0.1;
  }
  EXPECT_GT(nonzero, 150);  // 223: a third of the voxels are empty
}

TEST(GridMedium, OpticalDepthMatchesBruteForceIntegration) {
  const auto grid = testing::random_grid({6, 6, 6}, 1, 5, rotation_from_euler_deg({10, 0, 30}));
  const GridMedium medium(grid);
  Rng rng(9, 0);
  MediumPoint p;
  for (int r = 0; r < 20; ++r) {
    const Ray ray = random_ray_through(medium.bounds(), rng);
    // Integrate between the grid's true faces, where the field jumps from zero:
    // the ray clipped to [−½, n−½]³ in index space (t is unchanged by the map).
    const GridPlacement& pl = grid->placement();
    const Ray index_ray{pl.world_to_index(ray.origin), pl.world_to_index_direction(ray.direction)};
    double t0 = 0, t1 = 1e9;
    if (!BBox3({-0.5, -0.5, -0.5}, {5.5, 5.5, 5.5}).intersect(index_ray, t0, t1)) continue;
    const double tau = medium.optical_depth(ray, 0, 1e9)[0];
    const int n = 20000;
    const double h = (t1 - t0) / n;
    double brute = 0;
    const double gx[2] = {-1 / std::sqrt(3.0), 1 / std::sqrt(3.0)};
    for (int i = 0; i < n; ++i)
      for (double x : gx) {
        medium.coefficients_at(ray.at(t0 + h * (i + 0.5 + 0.5 * x)), p);
        brute += 0.5 * h * (p.sigma_a[0] + p.sigma_s[0]);
      }
    // Kinks of the field at cell faces limit the brute force to ~h²: 1e-6 relative is ample.
    EXPECT_NEAR(tau, brute, 1e-6 * brute + 1e-12) << r;
  }
}

TEST(GridMedium, MajorantAndMinorantBoundExtinctionEverywhere) {
  const auto grid = testing::random_grid({13, 9, 11}, 2, 3);
  const GridMedium medium(grid, 4);
  const MajorantGrid& maj = medium.majorants();
  Rng rng(2, 0);
  MediumPoint p;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 u(-0.5 + 13 * rng.uniform(), -0.5 + 9 * rng.uniform(), -0.5 + 11 * rng.uniform());
    medium.coefficients_at(grid->placement().index_to_world(u), p);
    const int bx = static_cast<int>(std::floor(u.x + 1)) / 4,
              by = static_cast<int>(std::floor(u.y + 1)) / 4,
              bz = static_cast<int>(std::floor(u.z + 1)) / 4;
    for (int s = 0; s < 2; ++s) {
      EXPECT_LE(p.sigma_a[s] + p.sigma_s[s], maj.majorant(bx, by, bz, s) * (1.0 + 1e-12));
      EXPECT_GE(p.sigma_a[s] + p.sigma_s[s], maj.minorant(bx, by, bz, s) * (1.0 - 1e-12));
      EXPECT_LE(maj.majorant(bx, by, bz, s), maj.max_majorant(bx, by, bz));
    }
  }
}

TEST(GridMedium, SkipsEmptyBlocksAndKeepsIsolatedVoxels) {
  // A 40³ grid that is empty but for one voxel: the walk must visit only the
  // cells around it and still integrate it exactly.
  GridPlacement placement;
  placement.voxel_size_m = 1.0;
  auto grid =
      std::make_shared<VoxelGrid>(GridDims{40, 40, 40}, placement, std::vector<double>{10.0});
  grid->sigma_a(0)[grid->index(20, 20, 20)] = 2.0f;
  const GridMedium medium(grid);
  // Along x through the voxel centre: a tent of height 2 and half-width 1 m, τ = 2.
  const Ray ray{{-5, 20.5, 20.5}, {1, 0, 0}};
  int segments = 0;
  medium.trace_segments(ray, 0, 1e9, [&](const MediumSegment&) { return ++segments, true; });
  EXPECT_LE(segments, 2 * GridMedium::kDefaultBlockSize + 2);
  EXPECT_NEAR(medium.optical_depth(ray, 0, 1e9)[0], 2.0, 1e-12);
}

TEST(GridMedium, ConstantGridEqualsHomogeneousMedium) {
  GridPlacement placement;
  placement.origin_m = {0, 0, 0};
  placement.voxel_size_m = 0.5;
  auto grid = std::make_shared<VoxelGrid>(GridDims{4, 4, 4}, placement, std::vector<double>{10.0});
  for (std::size_t v = 0; v < 64; ++v) {
    grid->sigma_a(0)[v] = 0.7f;
    grid->sigma_s(0)[v] = 0.3f;
    grid->temperature()[v] = 300.0f;
  }
  const GridMedium gm(grid);
  const HomogeneousMedium hm(BBox3({0, 0, 0}, {2, 2, 2}), {10.0}, {0.7}, {0.3}, {0.0}, 300.0);
  Rng rng(4, 0);
  for (int r = 0; r < 100; ++r) {
    const Ray ray = random_ray_through(gm.bounds(), rng);
    EXPECT_NEAR(gm.optical_depth(ray, 0, 1e9)[0], hm.optical_depth(ray, 0, 1e9)[0], 1e-6);
  }
}

// Beer–Lambert through a voxelised Gaussian puff against the closed-form line
// integral (erf). Trilinear reconstruction is second-order accurate, so the
// error must fall roughly fourfold per doubling and be below 1e-3 at 128³ for
// rays passing within one radius of the centre (where the optical depth is).
TEST(GridMedium, GaussianPuffOpticalDepthConvergesToClosedForm) {
  GaussianPuffSpec spec;
  spec.center_m = {1.0, -2.0, 5.0};
  spec.radius_m = 2.0;
  spec.extent_radii = 4.0;
  spec.peak_sigma_a = {0.8};
  spec.peak_sigma_s = {0.4};
  spec.g = {0.0};
  const Ray rays[] = {
      {{-20, -2.0, 5.0}, {1, 0, 0}},                          // through the centre
      {{-20, -1.3, 5.9}, normalize(Vec3(1, 0.05, -0.02))},    // off-centre, oblique
      {{1.0, -2.0, -20.0}, normalize(Vec3(0.5, 0.5, 25.0))},  // nearly vertical
  };
  double previous_error = 1.0;
  for (int res : {32, 64, 128}) {
    spec.resolution = res;
    const GridMedium medium(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
    double worst = 0;
    for (const Ray& ray : rays) {
      double t0 = 0, t1 = 1e9;
      ASSERT_TRUE(medium.bounds().intersect(ray, t0, t1));
      const double exact = 1.2 * gaussian_puff_line_integral(spec, ray, t0, t1);
      const double tau = medium.optical_depth(ray, 0, 1e9)[0];
      worst = std::max(worst, std::abs(tau - exact) / exact);
      // Transmittance e^{−τ} inherits the same relative accuracy in τ.
    }
    RecordProperty("relative_error_" + std::to_string(res), std::to_string(worst));
    if (res == 128) {
      EXPECT_LE(worst, 1e-3);
    }
    EXPECT_LT(worst, 0.5 * previous_error) << "no convergence at " << res;
    previous_error = worst;
  }
}

}  // namespace
}  // namespace obscura
