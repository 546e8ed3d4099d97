#pragma once
// The sun: a uniformly bright disc seen in a direction given by azimuth and
// elevation, with spectral irradiance E_λ at the scene (W m⁻² µm⁻¹, on a
// surface facing the sun). By default a 5778 K blackbody scaled so that the
// total irradiance is 1361 W m⁻² (the total solar irradiance), or a user table
// of spectral irradiance, linear between its wavelengths and zero outside them.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "obscura/core/planck.h"
#include "obscura/core/tabulated_spectrum.h"
#include "obscura/core/vec3.h"

namespace obscura {

struct Sun {
  bool enabled = false;
  double azimuth_deg = 180.0;   // clockwise from +y (north) towards +x (east)
  double elevation_deg = 45.0;  // above the horizon (the z = 0 plane)
  double angular_diameter_deg = 0.533;
  double temperature_k = 5778.0;          // blackbody shape of the spectrum
  double total_irradiance_w_m2 = 1361.0;  // ∫ E_λ dλ
  // User spectrum, W m⁻² µm⁻¹, zero outside its wavelengths (empty: the
  // blackbody above).
  TabulatedSpectrum irradiance_table;

  // Unit vector pointing from the scene towards the sun.
  Vec3 direction() const {
    const double k = std::numbers::pi / 180.0;
    const double el = elevation_deg * k, az = azimuth_deg * k;
    return {std::cos(el) * std::sin(az), std::cos(el) * std::cos(az), std::sin(el)};
  }
  // cos of the disc's angular radius.
  double cos_half_angle() const {
    return std::cos(0.5 * angular_diameter_deg * std::numbers::pi / 180.0);
  }
  // Solid angle of the disc, sr: 2π(1 − cos α).
  double solid_angle_sr() const {
    const double a = 0.5 * angular_diameter_deg * std::numbers::pi / 180.0;
    return 4.0 * std::numbers::pi * std::sin(0.5 * a) * std::sin(0.5 * a);
  }
  // Spectral irradiance, W m⁻² µm⁻¹: π B_λ(T) scaled to the total irradiance
  // (σ T⁴ is the blackbody's total exitance, π ∫ B_λ dλ).
  double irradiance(double wavelength_um) const {
    if (!irradiance_table.empty()) return irradiance_table(wavelength_um);
    const double exitance = kStefanBoltzmann * std::pow(temperature_k, 4);
    return std::numbers::pi * planck_radiance(wavelength_um, temperature_k) *
           (total_irradiance_w_m2 / exitance);
  }
  // Radiance of the disc, W m⁻² sr⁻¹ µm⁻¹.
  double radiance(double wavelength_um) const {
    return irradiance(wavelength_um) / solid_angle_sr();
  }
};

}  // namespace obscura
