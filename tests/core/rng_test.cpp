#include "obscura/core/rng.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace obscura {
namespace {

TEST(Rng, SameSeedAndStreamRepeat) {
  Rng a(42, 7), b(42, 7);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u32(), b.next_u32());
}

TEST(Rng, StreamsDiffer) {
  Rng a(42, 7), b(42, 8);
  int same = 0;
  for (int i = 0; i < 100; ++i) same += a.next_u32() == b.next_u32();
  EXPECT_LT(same, 3);
}

TEST(Rng, UniformIsUniformByChiSquare) {
  // 20 equal bins, 100 000 draws: χ² with 19 degrees of freedom; 43.8 is the 0.1 % critical value.
  Rng rng(1, 0);
  constexpr int kBins = 20, kDraws = 100000;
  std::vector<int> counts(kBins, 0);
  for (int i = 0; i < kDraws; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    ++counts[static_cast<int>(u * kBins)];
  }
  const double expected = static_cast<double>(kDraws) / kBins;
  double chi2 = 0;
  for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chi2, 43.8);
}

}  // namespace
}  // namespace obscura
