#pragma once
// Planck's law at one wavelength tabulated in temperature, for inner loops:
// cubic Hermite interpolation of B_λ(T) and dB_λ/dT at every kelvin, used
// from T_min = √(c2/(0.1 λ)) to kMaxTableTemperatureK and the formula
// outside. Over a 1 K step the Hermite error is about (d ln B/dT)⁴/384 with
// d ln B/dT ≤ c2/(λT²) ≤ 0.1 above T_min: relative error below 3e-7
// everywhere (tests/core/planck_test.cpp measures it). T_min is 160 K at
// 10 µm and 510 K at 0.55 µm, where the visible emission is nothing anyway.
#include <vector>

#include "obscura/core/planck.h"

namespace obscura {

inline constexpr int kMaxTableTemperatureK = 4000;

class PlanckTable {
 public:
  explicit PlanckTable(double wavelength_um);

  // B_λ(T), W m⁻² sr⁻¹ µm⁻¹; 0 for T <= 0.
  double operator()(double temperature_k) const {
    if (!(temperature_k >= t_min_k_ && temperature_k < kMaxTableTemperatureK))
      return exact(temperature_k);
    const int i = static_cast<int>(temperature_k);
    const double u = temperature_k - i;
    const double b0 = value_[i], b1 = value_[i + 1], d0 = slope_[i], d1 = slope_[i + 1];
    // Hermite basis on [i, i + 1] (unit spacing).
    const double u2 = u * u, u3 = u2 * u;
    return (2 * u3 - 3 * u2 + 1) * b0 + (u3 - 2 * u2 + u) * d0 + (-2 * u3 + 3 * u2) * b1 +
           (u3 - u2) * d1;
  }

 private:
  double exact(double temperature_k) const { return formula_.fast(temperature_k); }
  PlanckAtWavelength formula_;
  double t_min_k_;
  std::vector<double> value_, slope_;  // B and dB/dT at 0, 1, …, kMaxTableTemperatureK K
};

}  // namespace obscura
