// The tabulated Planck function (core/planck_table.h) and its fallback
// formula against the formula.
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

// The formula the table falls back on outside its range
// (PlanckAtWavelength::fast, exp instead of expm1) against expm1's, over the
// temperatures and wavelengths the marches meet, to 2e-15 as documented.
TEST(PlanckTable, TheFastFormulaEqualsExpm1sToRounding) {
  for (const double wavelength : {0.4, 0.55, 1.06, 3.8, 10.6, 14.0}) {
    const PlanckAtWavelength formula(wavelength);
    double worst = 0.0;
    for (double t = 20.0; t < 6000.0; t *= 1.013) {
      const double exact = formula(t);
      if (exact < 1e-300) continue;
      worst = std::max(worst, std::abs(formula.fast(t) / exact - 1.0));
    }
    EXPECT_LT(worst, 2e-15) << wavelength << " µm";
  }
  EXPECT_EQ(PlanckAtWavelength(10.0).fast(0.0), 0.0);
}

TEST(PlanckTable, ZeroAtAndBelowZeroKelvin) {
  const PlanckTable table(10.0);
  EXPECT_EQ(table(0.0), 0.0);
  EXPECT_EQ(table(-5.0), 0.0);
}

}  // namespace
}  // namespace obscura
