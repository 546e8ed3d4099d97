// The cell quadrature (render/emission_absorption/cell_quadrature.h) against
// closed forms and a converged reference: ∫₀ʰ e^{−τ(s)} ε(s) ds.
#include "obscura/render/emission_absorption/cell_quadrature.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace obscura {
namespace {

// ∫₀ʰ e^{−∫₀ˢσt} ε ds by composite Simpson on 20000 intervals (σt, ε smooth).
double reference(double h, const std::function<double(double)>& sigma_t,
                 const std::function<double(double)>& emissivity) {
  constexpr int n = 20000;
  const double ds = h / n;
  double tau = 0.0, sum = 0.0, previous = sigma_t(0.0);
  for (int i = 0; i <= n; ++i) {
    const double s = i * ds;
    if (i > 0) {
      const double mid = sigma_t(s - 0.5 * ds), now = sigma_t(s);
      tau += ds / 6.0 * (previous + 4.0 * mid + now);
      previous = now;
    }
    const double w = (i == 0 || i == n) ? 1.0 : (i % 2 ? 4.0 : 2.0);
    sum += w * std::exp(-tau) * emissivity(s);
  }
  return sum * ds / 3.0;
}

CellEmission at_three_points(double h, const std::function<double(double)>& sigma_t,
                             const std::function<double(double)>& emissivity) {
  const double st[3] = {sigma_t(0.0), sigma_t(0.5 * h), sigma_t(h)};
  const double em[3] = {emissivity(0.0), emissivity(0.5 * h), emissivity(h)};
  return integrate_cell(h, st, em);
}

TEST(CellQuadrature, ConstantSourceIsExactForAnyDepth) {
  // σt and S = ε/σt constant: ∫ = S (1 − e^{−σt h}); exact in optical depth,
  // and within Simpson's bound D⁵ S/2880 in optically thin cells.
  for (const double d : {1e-4, 0.05, 0.3, 1.0, 4.0, 30.0, 700.0}) {
    const double h = 0.7, st = d / h, source = 2.5;
    const double sigma_t[3] = {st, st, st}, em[3] = {st * source, st * source, st * source};
    const CellEmission c = integrate_cell(h, sigma_t, em);
    const double bound =
        (d < kThinCell ? std::pow(d, 5) / 2880.0 * 1.01 : 0.0) * source + 1e-12 * source;
    EXPECT_NEAR(c.emitted, source * -std::expm1(-d), bound) << "D = " << d;
    EXPECT_NEAR(c.transmittance, std::exp(-d), 1e-15) << "D = " << d;
  }
}

TEST(CellQuadrature, CubicExtinctionGivesTheExactDepth) {
  // Trilinear σt along a line is a cubic: Simpson's three points are exact.
  const double h = 0.4;
  auto sigma_t = [](double s) { return 2.0 + 3.0 * s - 4.0 * s * s + 5.0 * s * s * s; };
  const double exact = 2.0 * h + 1.5 * h * h - 4.0 / 3.0 * h * h * h + 1.25 * h * h * h * h;
  const CellEmission c = at_three_points(h, sigma_t, [](double) { return 0.0; });
  EXPECT_NEAR(c.transmittance, std::exp(-exact), 1e-15);
}

TEST(CellQuadrature, LinearSourceInOpticalDepthIsExact) {
  // σt constant and S linear in s (so in t): the line or parabola is exact.
  for (const double d : {0.2, 1.0, 5.0, 50.0}) {
    const double h = 1.3, st = d / h;
    auto sigma_t = [&](double) { return st; };
    auto emissivity = [&](double s) { return st * (1.0 + 0.8 * s); };
    const CellEmission c = at_three_points(h, sigma_t, emissivity);
    const double ref = reference(h, sigma_t, emissivity);
    EXPECT_NEAR(c.emitted, ref, 1e-9 * ref) << "D = " << d;
  }
}

TEST(CellQuadrature, SmoothCellsConvergeAtThirdOrderOrBetter) {
  // Non-constant σt and a curved source: halving the cell must cut the error
  // by at least 2³ (third order in D, docs/physics.md) once converging.
  auto sigma_t = [](double s) { return 1.5 + std::sin(3.0 * s); };
  auto emissivity = [&](double s) { return sigma_t(s) * (2.0 + std::cos(5.0 * s)); };
  double previous_error = 0.0;
  for (const double h : {0.8, 0.4, 0.2, 0.1}) {
    // The same interval [0, 0.8] in cells of h.
    double radiance = 0.0, transmittance = 1.0;
    for (double s0 = 0.0; s0 < 0.8 - 1e-12; s0 += h) {
      const CellEmission c = at_three_points(
          h, [&](double s) { return sigma_t(s0 + s); },
          [&](double s) { return emissivity(s0 + s); });
      radiance += transmittance * c.emitted;
      transmittance *= c.transmittance;
    }
    const double error = std::abs(radiance - reference(0.8, sigma_t, emissivity));
    if (previous_error > 0.0) {
      EXPECT_LT(error, previous_error / 7.0) << "h = " << h;
    }
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-5);
}

TEST(CellQuadrature, ThickCellTendsToItsEntrySource) {
  const double h = 1.0, sigma_t[3] = {1e4, 1e4, 1e4}, em[3] = {3e4, 5e4, 9e4};
  const CellEmission c = integrate_cell(h, sigma_t, em);
  EXPECT_NEAR(c.emitted, 3.0, 1e-3);
  EXPECT_EQ(c.transmittance, 0.0);
}

TEST(CellQuadrature, EmptyCellEmitsNothingAndTransmitsAll) {
  const double zero[3] = {0.0, 0.0, 0.0};
  const CellEmission c = integrate_cell(2.0, zero, zero);
  EXPECT_EQ(c.emitted, 0.0);
  EXPECT_EQ(c.transmittance, 1.0);
}

TEST(CellQuadrature, CellThatStartsEmptyStaysBounded) {
  // A cloud's edge: σt and ε zero at the entry; S is a weighted mean of the
  // sources, so the result stays between 0 and max S (1 − e^{−D}).
  const double sigma_t[3] = {0.0, 3.0, 6.0}, em[3] = {0.0, 6.0, 12.0};  // S = 2
  const CellEmission c = integrate_cell(1.0, sigma_t, em);
  const double d = 1.0 / 6.0 * (0.0 + 12.0 + 6.0);
  EXPECT_GT(c.emitted, 0.0);
  EXPECT_LE(c.emitted, 2.0 * -std::expm1(-d) * (1 + 1e-12));
}

// Delta-M's cell (add_cell_forward): the radiance integrated with σt − φ and
// seen through the attenuation e^{−∫(σt − φ)}, the transmittance the exact
// e^{−∫σt}; with φ = 0 the same bits as add_cell.
TEST(CellQuadrature, AForwardPartLightensTheRadiancesExtinctionAlone) {
  const double h = 0.8;
  const double st0[2] = {1.5, 0.2}, st1[2] = {2.5, 0.3}, st2[2] = {2.0, 0.1};
  const double em0[2] = {3.0, 0.5}, em1[2] = {4.0, 0.7}, em2[2] = {3.5, 0.2};
  const double fw0[2] = {0.6, 0.0}, fw1[2] = {0.9, 0.0}, fw2[2] = {0.7, 0.0};
  const double* st[3] = {st0, st1, st2};
  const double* em[3] = {em0, em1, em2};
  const double* fw[3] = {fw0, fw1, fw2};
  double radiance[2] = {0.25, 0.5}, transmittance[2] = {0.8, 0.6}, attenuation[2] = {0.9, 0.6};
  add_cell_forward(h, 2, st, fw, em, radiance, transmittance, attenuation);

  // Node 0 keeps φ: its emission and attenuation are the cell's with σt − φ.
  const double scaled[3] = {1.5 - 0.6, 2.5 - 0.9, 2.0 - 0.7}, em_0[3] = {3.0, 4.0, 3.5};
  const CellEmission c = integrate_cell(h, scaled, em_0);
  EXPECT_DOUBLE_EQ(radiance[0], 0.25 + 0.9 * c.emitted);
  EXPECT_DOUBLE_EQ(attenuation[0], 0.9 * std::exp(-h / 6.0 * (0.9 + 4.0 * 1.6 + 1.3)));
  EXPECT_DOUBLE_EQ(transmittance[0], 0.8 * std::exp(-h / 6.0 * (1.5 + 4.0 * 2.5 + 2.0)));

  // Node 1 keeps none: add_cell's bits, and its attenuation is its transmittance's factor.
  double radiance_1 = 0.5, transmittance_1 = 0.6;
  const double* st_1[3] = {st0 + 1, st1 + 1, st2 + 1};
  const double* em_1[3] = {em0 + 1, em1 + 1, em2 + 1};
  add_cell(h, 1, st_1, em_1, &radiance_1, &transmittance_1);
  EXPECT_EQ(radiance[1], radiance_1);
  EXPECT_EQ(transmittance[1], transmittance_1);
  EXPECT_EQ(attenuation[1], transmittance_1);
}

}  // namespace
}  // namespace obscura
