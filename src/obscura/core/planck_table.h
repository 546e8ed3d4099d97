#pragma once
// Planck's law at one wavelength tabulated in temperature, for inner loops:
// cubic Hermite interpolation of B_λ(T) and dB_λ/dT at every kelvin, used
// from T_min = √(c2/(0.1 λ)) to kMaxTableTemperatureK and the formula
// outside. Over a 1 K step the Hermite error is about (d ln B/dT)⁴/384 with
// d ln B/dT ≤ c2/(λT²) ≤ 0.1 above T_min: relative error below 3e-7
// everywhere (tests/core/planck_test.cpp measures it). T_min is 160 K at
// 10 µm and 510 K at 0.55 µm, where the visible emission is nothing anyway.
#include <cstddef>
#include <vector>

#include "obscura/core/host_device.h"
#include "obscura/core/planck.h"

namespace obscura {

inline constexpr int kMaxTableTemperatureK = 4000;

// A table's lookup as plain data, for code that runs on the CPU and on a CUDA
// device alike (docs/gpu.md): the table's coefficients where they lie (host
// or device memory), T_min and the formula. PlanckTable looks up through it,
// so both sides do the same arithmetic.
struct PlanckTableView {
  const double* cubic = nullptr;  // 4 coefficients per interval [i, i + 1] K
  double t_min_k = 0;
  PlanckAtWavelength formula;

  // B_λ(T), W m⁻² sr⁻¹ µm⁻¹; 0 for T <= 0.
  OBSCURA_HOST_DEVICE double operator()(double temperature_k) const {
    if (!(temperature_k >= t_min_k && temperature_k < kMaxTableTemperatureK))
      return formula.fast(temperature_k);
    const int i = static_cast<int>(temperature_k);
    const double u = temperature_k - i;
    // The Hermite cubic on [i, i + 1] in powers of u.
    const double* c = cubic + 4 * static_cast<std::size_t>(i);
    return (c[0] + u * c[1]) + (u * u) * (c[2] + u * c[3]);  // Estrin: two levels, not three
  }
};

class PlanckTable {
 public:
  explicit PlanckTable(double wavelength_um);

  // B_λ(T), W m⁻² sr⁻¹ µm⁻¹; 0 for T <= 0.
  double operator()(double temperature_k) const { return view()(temperature_k); }
  // The lookup over this table's coefficients (valid while the table lives).
  PlanckTableView view() const { return {cubic_.data(), t_min_k_, formula_}; }
  // The coefficients, 4 per kelvin from 0 to kMaxTableTemperatureK (what a
  // device copy of the table holds).
  const std::vector<double>& coefficients() const { return cubic_; }

 private:
  PlanckAtWavelength formula_;
  double t_min_k_;
  // Per interval [i, i + 1] K: the cubic through B and dB/dT at both ends
  // (cubic Hermite), as the coefficients of 1, u, u², u³.
  std::vector<double> cubic_;
};

}  // namespace obscura
