#include "obscura/prep/dispersion/stability.h"

#include <gtest/gtest.h>

#include <cmath>

namespace obscura {
namespace {

constexpr StabilityClass kClasses[6] = {StabilityClass::kA, StabilityClass::kB, StabilityClass::kC,
                                        StabilityClass::kD, StabilityClass::kE, StabilityClass::kF};

// docs/domain.md §3.4, "Instantaneous puff σ" (Slade 1968 / CCPS 1999), transcribed
// here independently of the implementation: σy = σx = a x^b, σz = c x^d.
struct PuffRow {
  double a, b, c, d;
};
constexpr PuffRow kPuffTable[6] = {{0.18, 0.92, 0.60, 0.75}, {0.14, 0.92, 0.53, 0.73},
                                   {0.10, 0.92, 0.34, 0.71}, {0.06, 0.92, 0.15, 0.70},
                                   {0.04, 0.92, 0.10, 0.65}, {0.02, 0.89, 0.05, 0.61}};

// docs/domain.md §3.4, "Briggs (1973) open-country (rural) plume σ", as functions.
double briggs_y(int row, double x) {
  const double c[6] = {0.22, 0.16, 0.11, 0.08, 0.06, 0.04};
  return c[row] * x * std::pow(1 + 0.0001 * x, -0.5);
}
double briggs_z(int row, double x) {
  switch (row) {
    case 0:
      return 0.20 * x;
    case 1:
      return 0.12 * x;
    case 2:
      return 0.08 * x * std::pow(1 + 0.0002 * x, -0.5);
    case 3:
      return 0.06 * x * std::pow(1 + 0.0015 * x, -0.5);
    case 4:
      return 0.03 * x / (1 + 0.0003 * x);
    default:
      return 0.016 * x / (1 + 0.0003 * x);
  }
}

TEST(Stability, PuffSigmasMatchTheSladeCcpsTableForEveryClass) {
  for (int r = 0; r < 6; ++r)
    for (double x : {10.0, 50.0, 100.0, 500.0, 2000.0}) {
      const DispersionSigmas s = dispersion_sigmas(SigmaSet::kCcpsPuff, kClasses[r], x);
      const PuffRow& t = kPuffTable[r];
      EXPECT_NEAR(s.y_m, t.a * std::pow(x, t.b), 1e-12 * s.y_m) << "class " << r << " x " << x;
      EXPECT_NEAR(s.z_m, t.c * std::pow(x, t.d), 1e-12 * s.z_m) << "class " << r << " x " << x;
      EXPECT_EQ(s.x_m, s.y_m);
    }
}

TEST(Stability, BriggsSigmasMatchTheOpenCountryTableForEveryClass) {
  for (int r = 0; r < 6; ++r)
    for (double x : {10.0, 100.0, 1000.0, 10000.0}) {
      const DispersionSigmas s = dispersion_sigmas(SigmaSet::kBriggsOpenCountry, kClasses[r], x);
      EXPECT_NEAR(s.y_m, briggs_y(r, x), 1e-12 * s.y_m) << "class " << r << " x " << x;
      EXPECT_NEAR(s.z_m, briggs_z(r, x), 1e-12 * s.z_m) << "class " << r << " x " << x;
      EXPECT_EQ(s.x_m, s.y_m);
    }
}

TEST(Stability, RoundedFiguresOfDomainTableAgree) {
  // docs/domain.md §3.4 "Numbers": σy/σz in metres at 50 / 100 / 500 m.
  struct Case {
    SigmaSet set;
    StabilityClass cls;
    double x, sy, sz, tol;
  };
  const Case cases[] = {
      {SigmaSet::kCcpsPuff, StabilityClass::kD, 50, 2.2, 2.3, 0.05},
      {SigmaSet::kCcpsPuff, StabilityClass::kD, 100, 4.2, 3.8, 0.05},
      {SigmaSet::kCcpsPuff, StabilityClass::kD, 500, 18, 12, 0.5},
      {SigmaSet::kCcpsPuff, StabilityClass::kF, 50, 0.7, 0.5, 0.05},
      {SigmaSet::kCcpsPuff, StabilityClass::kF, 100, 1.2, 0.8, 0.05},
      {SigmaSet::kCcpsPuff, StabilityClass::kF, 500, 5, 2.2, 0.1},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kD, 50, 4.0, 2.9, 0.05},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kD, 100, 8.0, 5.6, 0.05},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kD, 500, 39, 23, 0.5},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kF, 50, 2.0, 0.8, 0.05},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kF, 100, 4.0, 1.6, 0.05},
      {SigmaSet::kBriggsOpenCountry, StabilityClass::kF, 500, 19.5, 7.0, 0.1},
  };
  for (const Case& c : cases) {
    const DispersionSigmas s = dispersion_sigmas(c.set, c.cls, c.x);
    EXPECT_NEAR(s.y_m, c.sy, c.tol) << to_string(c.set) << " " << to_string(c.cls) << " " << c.x;
    EXPECT_NEAR(s.z_m, c.sz, c.tol) << to_string(c.set) << " " << to_string(c.cls) << " " << c.x;
  }
}

TEST(Stability, PuffsGrowMoreSlowlyThanAveragedPlumesAndUnstableFasterThanStable) {
  for (double x : {50.0, 200.0, 1000.0}) {
    for (StabilityClass c : kClasses)
      EXPECT_LT(dispersion_sigmas(SigmaSet::kCcpsPuff, c, x).y_m,
                dispersion_sigmas(SigmaSet::kBriggsOpenCountry, c, x).y_m);
    for (int r = 0; r + 1 < 6; ++r)
      EXPECT_GT(dispersion_sigmas(SigmaSet::kCcpsPuff, kClasses[r], x).z_m,
                dispersion_sigmas(SigmaSet::kCcpsPuff, kClasses[r + 1], x).z_m);
  }
}

TEST(Stability, ZeroDistanceGivesZeroSigma) {
  for (SigmaSet set : {SigmaSet::kCcpsPuff, SigmaSet::kBriggsOpenCountry}) {
    const DispersionSigmas s = dispersion_sigmas(set, StabilityClass::kC, 0.0);
    EXPECT_EQ(s.x_m, 0.0);
    EXPECT_EQ(s.y_m, 0.0);
    EXPECT_EQ(s.z_m, 0.0);
  }
}

TEST(Stability, ParsesClassesAndSetsAndRejectsOthers) {
  const char* names[6] = {"A", "B", "C", "D", "E", "F"};
  for (int r = 0; r < 6; ++r) {
    ASSERT_TRUE(parse_stability_class(names[r]).has_value());
    EXPECT_EQ(*parse_stability_class(names[r]), kClasses[r]);
    EXPECT_EQ(to_string(kClasses[r]), names[r]);
  }
  for (const char* bad : {"", "G", "a", "AB", "D "})
    EXPECT_FALSE(parse_stability_class(bad)) << bad;
  EXPECT_EQ(parse_sigma_set("ccps-puff"), SigmaSet::kCcpsPuff);
  EXPECT_EQ(parse_sigma_set("briggs-open-country"), SigmaSet::kBriggsOpenCountry);
  EXPECT_FALSE(parse_sigma_set("briggs"));
  EXPECT_EQ(to_string(SigmaSet::kBriggsOpenCountry), "briggs-open-country");
}

TEST(Stability, DefaultWindExponentsAreTheRuralPowerLaw) {
  // docs/domain.md §3.6: A–B 0.07, C 0.10, D 0.15, E 0.35, F 0.55.
  const double expected[6] = {0.07, 0.07, 0.10, 0.15, 0.35, 0.55};
  for (int r = 0; r < 6; ++r) EXPECT_EQ(default_wind_profile_exponent(kClasses[r]), expected[r]);
}

}  // namespace
}  // namespace obscura
