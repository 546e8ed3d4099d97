// The tabulated Planck function (core/planck_table.h) against the formula.
#include "obscura/core/planck_table.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "obscura/core/planck.h"

namespace obscura {
namespace {

TEST(PlanckTable, WithinThreeTenthsOfAMillionthEverywhere) {
  for (const double wavelength : {0.4, 0.55, 1.06, 3.8, 4.6, 8.0, 10.6, 14.0}) {
    const PlanckTable table(wavelength);
    double worst = 0.0;
    // Between the kelvins (where the Hermite error peaks) and across the
    // table's edges.
    for (double t = 1.0; t < 4400.0; t += 0.37) {
      const double exact = planck_radiance(wavelength, t);
      if (exact < 1e-300) continue;
      worst = std::max(worst, std::abs(table(t) / exact - 1.0));
    }
    EXPECT_LT(worst, 3e-7) << wavelength << " µm";
  }
}

TEST(PlanckTable, ZeroAtAndBelowZeroKelvin) {
  const PlanckTable table(10.0);
  EXPECT_EQ(table(0.0), 0.0);
  EXPECT_EQ(table(-5.0), 0.0);
}

}  // namespace
}  // namespace obscura
