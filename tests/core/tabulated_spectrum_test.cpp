#include "obscura/core/tabulated_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>

#include "obscura/core/check.h"
#include "obscura/core/error.h"

namespace obscura {
namespace {

TEST(TabulatedSpectrum, LinearBetweenRowsHeldOrZeroOutside) {
  const TabulatedSpectrum held({1.0, 2.0, 4.0}, {0.5, 1.5, 0.5});
  EXPECT_DOUBLE_EQ(held(1.0), 0.5);
  EXPECT_DOUBLE_EQ(held(1.5), 1.0);
  EXPECT_DOUBLE_EQ(held(3.0), 1.0);
  EXPECT_DOUBLE_EQ(held(4.0), 0.5);
  EXPECT_DOUBLE_EQ(held(0.1), 0.5);  // held at the first row
  EXPECT_DOUBLE_EQ(held(9.0), 0.5);  // … and the last
  const TabulatedSpectrum zero({1.0, 2.0}, {3.0, 5.0}, TabulatedSpectrum::Outside::kZero);
  EXPECT_EQ(zero(0.999), 0.0);
  EXPECT_EQ(zero(2.001), 0.0);
  EXPECT_DOUBLE_EQ(zero(1.0), 3.0);
  EXPECT_DOUBLE_EQ(zero(2.0), 5.0);
  EXPECT_TRUE(zero.covers(1.5));
  EXPECT_FALSE(zero.covers(2.5));
}

// A flat table stays exactly flat between rows (v_i + f (v_{i+1} − v_i)):
// a flat band response must integrate to its width without rounding drift.
TEST(TabulatedSpectrum, AConstantTableIsExactlyConstant) {
  const TabulatedSpectrum flat({0.4, 0.7}, {1.0, 1.0});
  for (double w = 0.4; w <= 0.7; w += 0.0137) EXPECT_EQ(flat(w), 1.0) << w;
}

TEST(TabulatedSpectrum, OneRowIsAConstantAndEmptyIsZero) {
  const TabulatedSpectrum one({10.0}, {0.7});
  EXPECT_EQ(one(1.0), 0.7);
  EXPECT_EQ(one(100.0), 0.7);
  EXPECT_EQ(TabulatedSpectrum()(1.0), 0.0);
  EXPECT_TRUE(TabulatedSpectrum().empty());
}

TEST(TabulatedSpectrum, RefusesBadTables) {
  EXPECT_THROW(TabulatedSpectrum({}, {}), Error);
  EXPECT_THROW(TabulatedSpectrum({1.0, 2.0}, {1.0}), Error);
  EXPECT_THROW(TabulatedSpectrum({2.0, 1.0}, {1.0, 1.0}), Error);
  EXPECT_THROW(TabulatedSpectrum({1.0, 1.0}, {1.0, 1.0}), Error);
  EXPECT_THROW(TabulatedSpectrum({-1.0, 1.0}, {1.0, 1.0}), Error);
  EXPECT_THROW(TabulatedSpectrum({1.0, 2.0}, {1.0, std::nan("")}), Error);
}

TEST(WavelengthBracket, ClampsAtTheEndsAndWeightsTheUpperRow) {
  const std::vector<double> w = {1.0, 2.0, 4.0};
  WavelengthBracket b = bracket_wavelength(w, 3.0);
  EXPECT_EQ(b.lower, 1u);
  EXPECT_EQ(b.upper, 2u);
  EXPECT_DOUBLE_EQ(b.frac, 0.5);
  b = bracket_wavelength(w, 0.5);
  EXPECT_EQ(b.lower, 0u);
  EXPECT_EQ(b.upper, 0u);
  EXPECT_EQ(b.frac, 0.0);
  b = bracket_wavelength(w, 7.0);
  EXPECT_EQ(b.lower, 2u);
  EXPECT_EQ(b.upper, 2u);
  b = bracket_wavelength({5.0}, 1.0);
  EXPECT_EQ(b.lower, 0u);
  EXPECT_EQ(b.upper, 0u);
}

TEST(Check, AFailedInvariantThrowsAnInternalErrorNamingTheLine) {
  EXPECT_NO_THROW(OBSCURA_CHECK(1 + 1 == 2));
  try {
    OBSCURA_CHECK_MSG(2 + 2 == 5, "arithmetic");
    FAIL() << "no exception";
  } catch (const InternalError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("internal error:"), std::string::npos) << what;
    EXPECT_NE(what.find("tabulated_spectrum_test.cpp:"), std::string::npos) << what;
    EXPECT_NE(what.find("2 + 2 == 5"), std::string::npos) << what;
    EXPECT_NE(what.find("(arithmetic)"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace obscura
