#pragma once
// Planck's law for blackbody spectral radiance, with the exact 2019 SI constants
// (docs/domain.md §5.2): B_λ(T) = c1L / (λ⁵ (exp(c2 / (λ T)) − 1)).
// Wavelengths are in micrometres; spectral radiance in W m⁻² sr⁻¹ µm⁻¹.
#include <cmath>

#include "obscura/core/host_device.h"

namespace obscura {

inline constexpr double kPlanckH = 6.62607015e-34;    // J s
inline constexpr double kSpeedOfLight = 299792458.0;  // m/s
inline constexpr double kBoltzmannK = 1.380649e-23;   // J/K
// c1L = 2 h c² expressed for λ in µm and radiance per µm: W µm⁴ m⁻² sr⁻¹.
inline constexpr double kC1L_um = 2.0 * kPlanckH * kSpeedOfLight * kSpeedOfLight * 1e24;
// c2 = h c / k in µm K.
inline constexpr double kC2_umK = kPlanckH * kSpeedOfLight / kBoltzmannK * 1e6;
// Stefan–Boltzmann constant σ = 2 π⁵ k⁴ / (15 h³ c²), W m⁻² K⁻⁴.
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

// Spectral radiance of a blackbody, W m⁻² sr⁻¹ µm⁻¹. Zero for T <= 0.
inline double planck_radiance(double wavelength_um, double temperature_k) {
  if (temperature_k <= 0.0) return 0.0;
  const double x = kC2_umK / (wavelength_um * temperature_k);
  const double l5 = wavelength_um * wavelength_um * wavelength_um * wavelength_um * wavelength_um;
  return kC1L_um / (l5 * std::expm1(x));
}

// dB_λ/dT, W m⁻² sr⁻¹ µm⁻¹ K⁻¹.
inline double planck_radiance_dT(double wavelength_um, double temperature_k) {
  if (temperature_k <= 0.0) return 0.0;
  const double x = kC2_umK / (wavelength_um * temperature_k);
  const double l5 = wavelength_um * wavelength_um * wavelength_um * wavelength_um * wavelength_um;
  const double em1 = std::expm1(x);
  // d/dT [1/(e^x − 1)] = e^x x / (T (e^x − 1)²)
  return kC1L_um / l5 * (em1 + 1.0) * x / (temperature_k * em1 * em1);
}

// Precomputed form for one fixed wavelength, used in inner loops:
// B(T) = a / expm1(b / T).
struct PlanckAtWavelength {
  double a = 0, b = 0;
  explicit PlanckAtWavelength(double wavelength_um)
      : a(kC1L_um / std::pow(wavelength_um, 5)), b(kC2_umK / wavelength_um) {}
  PlanckAtWavelength() = default;
  double operator()(double temperature_k) const {
    return temperature_k > 0.0 ? a / std::expm1(b / temperature_k) : 0.0;
  }
  // The same with exp where exp(x) − 1 loses nothing (x = c2/(λT) > 0.1, i.e.
  // λT < 1.4e5 µm K: every obscurant band and temperature); exp is cheaper
  // than expm1. Relative difference from operator() below 2e-15. Also on a
  // CUDA device (core/host_device.h), with CUDA's exp.
  OBSCURA_HOST_DEVICE double fast(double temperature_k) const {
    if (!(temperature_k > 0.0)) return 0.0;
    const double x = b / temperature_k;
    return a / (x > 0.1 ? std::exp(x) - 1.0 : std::expm1(x));
  }
};

}  // namespace obscura
