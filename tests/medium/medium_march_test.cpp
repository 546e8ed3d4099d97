// Medium::march_cells (medium/medium_march.h): a grid's fast march and the
// generic one from exact segments give the medium's own coefficients at
// every cell's three points, cover the ray without gaps, and Simpson's rule
// on them gives the exact optical depth.
#include "obscura/medium/medium_march.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "medium/test_grids.h"
#include "obscura/core/mat3.h"
#include "obscura/medium/composite_medium.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"

namespace obscura {
namespace {

// Records each cell and checks its points against coefficients_at.
class Checker final : public MarchVisitor {
 public:
  Checker(const Medium& medium, const Ray& ray, int samples)
      : medium_(medium), ray_(ray), tau_(samples, 0.0) {}
  bool visit(const MarchCell& cell) override {
    EXPECT_LE(cell.t_begin, cell.t_end);
    if (cells_ > 0) {
      EXPECT_GE(cell.t_begin, last_end_ - 1e-12);
    }
    last_end_ = cell.t_end;
    longest_ = std::max(longest_, cell.t_end - cell.t_begin);
    ++cells_;
    // A sliver where boundaries meet carries no length: nothing to compare.
    if (cell.t_end - cell.t_begin < 1e-9) return true;
    const double t[3] = {cell.t_begin, 0.5 * (cell.t_begin + cell.t_end), cell.t_end};
    MediumPoint expect;
    for (int p = 0; p < 3; ++p) {
      // Inside the cell (a hair from its faces, where the grid's trilinear
      // field is continuous anyway).
      const double tp = std::clamp(t[p], cell.t_begin + 1e-9, cell.t_end - 1e-9);
      medium_.coefficients_at(ray_.at(tp), expect);
      for (int k = 0; k < cell.spectral_count; ++k) {
        double a = 0, s = 0;
        for (int c = 0; c < cell.component_count; ++c) {
          a += cell.point[p][c].sigma_a[k];
          s += cell.point[p][c].sigma_s[k];
        }
        EXPECT_NEAR(a, expect.sigma_a[k], 1e-6 * (1 + expect.sigma_a[k]));
        EXPECT_NEAR(s, expect.sigma_s[k], 1e-6 * (1 + expect.sigma_s[k]));
      }
    }
    for (int k = 0; k < cell.spectral_count; ++k)
      for (int c = 0; c < cell.component_count; ++c) {
        double sum = 0;
        for (int p = 0; p < 3; ++p)
          sum += (p == 1 ? 4.0 : 1.0) * (cell.point[p][c].sigma_a[k] + cell.point[p][c].sigma_s[k]);
        tau_[k] += (cell.t_end - cell.t_begin) / 6.0 * sum;
      }
    return true;
  }
  int cells_ = 0;
  double last_end_ = 0, longest_ = 0;

  const Medium& medium_;
  const Ray& ray_;
  std::vector<double> tau_;
};

std::vector<Ray> rays_through(const Medium& medium, int count) {
  Rng rng(5, 1);
  const BBox3 b = medium.bounds();
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i) {
    const Vec3 e = b.hi - b.lo;
    const Vec3 target = b.lo + Vec3(e.x * rng.uniform(), e.y * rng.uniform(), e.z * rng.uniform());
    const double z = 2 * rng.uniform() - 1, phi = 6.283185307179586 * rng.uniform();
    const double r = std::sqrt(1 - z * z);
    const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    rays.push_back(Ray{target - d * 20.0, d});
  }
  return rays;
}

void expect_exact_depth(const Medium& medium, const MarchOptions& options) {
  const int samples = static_cast<int>(medium.wavelengths_um().size());
  for (const Ray& ray : rays_through(medium, 40)) {
    Checker checker(medium, ray, samples);
    medium.march_cells(ray, 0.0, 40.0, options, checker);
    std::vector<double> exact(samples, 0.0);
    medium.add_optical_depth(ray, 0.0, 40.0, exact.data());
    for (int k = 0; k < samples; ++k) EXPECT_NEAR(checker.tau_[k], exact[k], 1e-6 * (1 + exact[k]));
  }
}

TEST(MediumMarch, GridCellsCarryTheGridsCoefficientsAndExactDepth) {
  const GridMedium grid(
      testing::random_grid({9, 7, 6}, 2, 11, rotation_from_euler_deg({10, 25, -40})));
  expect_exact_depth(grid, {});
}

TEST(MediumMarch, CellsCutToTheLongestLengthStayExact) {
  const GridMedium grid(testing::random_grid({6, 6, 6}, 1, 12));
  MarchOptions options;
  options.max_cell_m = 0.1;  // under a third of the voxel
  int cells = 0;
  for (const Ray& ray : rays_through(grid, 10)) {
    Checker checker(grid, ray, 1);
    grid.march_cells(ray, 0.0, 40.0, options, checker);
    cells += checker.cells_;
    EXPECT_LE(checker.longest_, 0.1 + 1e-12);
  }
  EXPECT_GT(cells, 30);
  expect_exact_depth(grid, options);
}

// Cells cut into pieces meet exactly: each piece's entry is the last one's
// exit as the same double, marked continuous, with the same values, so a
// marcher reuses what it computed there (emission_marcher.h) and finds a
// lookup it kept by its distance (the radiance cache's march). An exit
// computed as q h + h against the next entry (q + 1) h missed by an ulp.
// Only a real gap (a grid's empty blocks, skipped) may break the chain.
class Seams final : public MarchVisitor {
 public:
  bool visit(const MarchCell& cell) override {
    if (cells_ > 0 && cell.t_begin <= last_end_ + 1e-9) {
      ++seams_;
      EXPECT_TRUE(cell.continuous_with_previous) << "cell " << cells_;
      EXPECT_EQ(cell.t_begin, last_end_) << "cell " << cells_;
      for (int k = 0; k < cell.spectral_count; ++k) {
        EXPECT_EQ(cell.point[0][0].sigma_a[k], last_exit_[2 * k]);
        EXPECT_EQ(cell.point[0][0].sigma_s[k], last_exit_[2 * k + 1]);
      }
    }
    last_end_ = cell.t_end;
    last_exit_.clear();
    for (int k = 0; k < cell.spectral_count; ++k) {
      last_exit_.push_back(cell.point[2][0].sigma_a[k]);
      last_exit_.push_back(cell.point[2][0].sigma_s[k]);
    }
    ++cells_;
    return true;
  }
  int cells_ = 0, seams_ = 0;

 private:
  double last_end_ = 0;
  std::vector<double> last_exit_;
};

TEST(MediumMarch, CutPiecesMeetExactly) {
  const HomogeneousMedium box(BBox3({-1, -1, -1}, {1, 1, 1}), std::vector<double>{3.0, 4.0},
                              std::vector<double>{0.3, 0.4}, std::vector<double>{0.2, 0.1},
                              std::vector<double>{0.5, 0.5}, 300.0);
  const GridMedium grid(testing::random_grid({6, 6, 6}, 1, 12));
  MarchOptions options;
  options.max_cell_m = 0.013;  // pieces of awkward lengths
  for (const Medium* medium :
       {static_cast<const Medium*>(&box), static_cast<const Medium*>(&grid)}) {
    int seams = 0;
    for (const Ray& ray : rays_through(*medium, 20)) {
      Seams check;
      medium->march_cells(ray, 0.0, 40.0, options, check);
      seams += check.seams_;
    }
    EXPECT_GT(seams, 1000);
  }
}

TEST(MediumMarch, GenericMarchOfOverlappingCloudsIsExact) {
  auto a = std::make_shared<GridMedium>(testing::random_grid({5, 6, 7}, 2, 3));
  auto b = std::make_shared<HomogeneousMedium>(
      BBox3({-1, 0, 2}, {0.5, 2, 3.5}), std::vector<double>{3.0, 4.0},
      std::vector<double>{0.3, 0.4}, std::vector<double>{0.2, 0.1}, std::vector<double>{0.5, 0.5},
      300.0);
  const CompositeMedium both({a, b});
  expect_exact_depth(both, {});
}

TEST(MediumMarch, AMarchCanBeStopped) {
  const GridMedium grid(testing::random_grid({8, 8, 8}, 1, 4));
  struct StopAtOnce final : MarchVisitor {
    int seen = 0;
    bool visit(const MarchCell&) override {
      ++seen;
      return false;
    }
  } stop;
  for (const Ray& ray : rays_through(grid, 5)) grid.march_cells(ray, 0.0, 40.0, {}, stop);
  EXPECT_LE(stop.seen, 5);
}

}  // namespace
}  // namespace obscura
