// fast_exp (core/fast_exp.h) against the C library's exp: a few ulp over the
// whole range where e^x is a normal double, and its edges.
#include "obscura/core/fast_exp.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "obscura/core/rng.h"

namespace obscura {
namespace {

TEST(FastExp, WithinFourUlpOfLibmOverTheNormalRange) {
  Rng rng(7, 0);
  double worst = 0.0;
  for (int i = 0; i < 2000000; ++i) {
    // Dense near 0, where the cell quadrature calls it, and over the whole range.
    const double x = i % 2 ? -0.5 * rng.uniform() : -708.3 + 1418.0 * rng.uniform();
    const double exact = std::exp(x);
    worst = std::max(worst, std::abs(fast_exp(x) - exact) / exact);
  }
  EXPECT_LT(worst, 4.0 * std::numeric_limits<double>::epsilon()) << worst;
}

TEST(FastExp, EdgesOfTheRange) {
  EXPECT_EQ(fast_exp(0.0), 1.0);
  EXPECT_EQ(fast_exp(-0.0), 1.0);
  EXPECT_EQ(fast_exp(-800.0), 0.0);
  EXPECT_EQ(fast_exp(-std::numeric_limits<double>::infinity()), 0.0);
  EXPECT_EQ(fast_exp(710.0), std::numeric_limits<double>::infinity());
  EXPECT_TRUE(std::isnan(fast_exp(std::numeric_limits<double>::quiet_NaN())));
  // Just above the cut the result is still a normal number close to libm's.
  EXPECT_NEAR(fast_exp(-708.0) / std::exp(-708.0), 1.0, 1e-14);
  EXPECT_NEAR(fast_exp(709.0) / std::exp(709.0), 1.0, 1e-14);
}

}  // namespace
}  // namespace obscura
