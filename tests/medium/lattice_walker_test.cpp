#include "obscura/medium/lattice_walker.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/rng.h"

namespace obscura {
namespace {

// Every cell the walker reports must contain the midpoint of its interval, the
// intervals must tile [t_begin, t_end] without gaps, and a dense sampling of the
// ray must find no cell the walker skipped.
TEST(LatticeWalker, VisitsExactlyTheCellsTheRayCrosses) {
  Rng rng(11, 0);
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3 o(10 * rng.uniform(), 10 * rng.uniform(), 10 * rng.uniform());
    Vec3 d(rng.uniform() - 0.5, rng.uniform() - 0.5, rng.uniform() - 0.5);
    if (trial % 10 == 0) d = Vec3(rng.uniform() - 0.5, 0.0, 0.0);  // axis-parallel rays
    d = normalize(d);
    const double cell = trial % 2 ? 1.0 : 2.5;
    const double t_end = 8.0 * rng.uniform();
    LatticeWalker w(o, d, 0.0, t_end, cell, {-100, -100, -100}, {100, 100, 100});
    std::array<int, 3> c;
    double t0, t1, expected_t0 = 0.0;
    std::vector<std::pair<std::array<int, 3>, std::pair<double, double>>> visited;
    while (w.next(c, t0, t1)) {
      EXPECT_NEAR(t0, expected_t0, 1e-12);
      EXPECT_GE(t1, t0);
      expected_t0 = t1;
      if (t1 - t0 > 1e-9) {
        const Vec3 mid = o + d * (0.5 * (t0 + t1));
        for (int a = 0; a < 3; ++a) EXPECT_EQ(static_cast<int>(std::floor(mid[a] / cell)), c[a]);
      }
      visited.push_back({c, {t0, t1}});
    }
    EXPECT_NEAR(expected_t0, t_end, 1e-12);
    for (int i = 0; i < 2000; ++i) {
      const double t = t_end * (i + 0.5) / 2000;
      const Vec3 p = o + d * t;
      std::array<int, 3> cp;
      for (int a = 0; a < 3; ++a) cp[a] = static_cast<int>(std::floor(p[a] / cell));
      bool found = false;
      for (auto& [vc, range] : visited)
        if (vc == cp && t >= range.first - 1e-9 && t <= range.second + 1e-9) found = true;
      EXPECT_TRUE(found) << "t=" << t;
    }
  }
}

}  // namespace
}  // namespace obscura
