#pragma once
// Sensor spectral bands: a wavelength interval with a tabulated relative
// response R(λ) (piecewise linear, 0 outside the table), and the quadrature that
// integrates spectral quantities over it. Band radiance L = ∫ R(λ) L_λ dλ in
// W m⁻² sr⁻¹ (docs/domain.md §5.3: in-band radiance, not band-mean spectral radiance).
#include <string>
#include <vector>

#include "obscura/core/tabulated_spectrum.h"

namespace obscura {

struct ResponsePoint {
  double wavelength_um;
  double response;  // dimensionless, >= 0
};

class Band {
 public:
  // A flat response of 1 between lo and hi (µm).
  static Band flat(std::string name, double lo_um, double hi_um);
  // A tabulated response, wavelengths strictly increasing; throws on bad tables.
  static Band tabulated(std::string name, std::vector<ResponsePoint> table);
  // Presets: visible 0.4–0.7, laser1064 1.059–1.069, mwir 3–5, lwir 8–12 (µm).
  static Band preset(const std::string& name);
  static std::vector<std::string> preset_names();
  // "LO:HI" in µm, or a preset name. Throws InputError naming `field` otherwise.
  static Band parse(const std::string& text, const std::string& field = "--band");

  const std::string& name() const { return name_; }
  double lo_um() const { return response_.front_um(); }
  double hi_um() const { return response_.back_um(); }
  // R(λ) as a table (zero outside it).
  const TabulatedSpectrum& response_table() const { return response_; }
  double response(double wavelength_um) const { return response_(wavelength_um); }

 private:
  std::string name_;
  TabulatedSpectrum response_;
};

// Composite Gauss–Legendre quadrature over a band: panels between the response
// table's breakpoints (so the integrand is smooth inside each), optionally split
// further in geometric progression. Weights include R(λ), so
// ∫ R(λ) f(λ) dλ ≈ Σ w_i f(λ_i).
class BandQuadrature {
 public:
  // `max_panel_ratio`: split a table interval until hi/lo of each panel is at
  // most this ratio (use a large value for one panel per interval).
  BandQuadrature(const Band& band, int nodes_per_panel, double max_panel_ratio);

  // High-accuracy quadrature (relative error < 1e-9 for Planck spectra above 150 K).
  static BandQuadrature accurate(const Band& band);

  const std::vector<double>& wavelengths_um() const { return nodes_um_; }
  const std::vector<double>& weights() const { return weights_um_; }
  std::size_t size() const { return nodes_um_.size(); }
  // ∫ R dλ, µm.
  double response_integral() const { return response_integral_; }

  // ∫ R B_λ(T) dλ, W m⁻² sr⁻¹.
  double blackbody_radiance(double temperature_k) const;
  double blackbody_radiance_dT(double temperature_k) const;
  // Both at once (one exponential per node): returns ∫ R B dλ, writes
  // ∫ R dB/dT dλ (W m⁻² sr⁻¹ K⁻¹) to `d_dt`.
  double blackbody_radiance_and_dT(double temperature_k, double& d_dt) const;
  // Inverse of blackbody_radiance: the temperature (K) whose blackbody band
  // radiance equals `band_radiance`. Newton on log L with a bisection guard;
  // converged to 1e-9 K relative. Returns 0 for band_radiance <= 0.
  double apparent_temperature(double band_radiance) const;
  // Σ w_i values[i] for spectral values at the nodes.
  double integrate(const double* values) const;

 private:
  std::vector<double> nodes_um_;
  std::vector<double> weights_um_;
  double response_integral_ = 0;
  // What apparent_temperature needs at every call: the response-weighted mean
  // wavelength (µm) and the radiance at its bracket's ends, 1 K and 10⁶ K.
  double centroid_um_ = 0;
  double radiance_at_1k_ = 0, radiance_at_1e6k_ = 0;
};

// Gauss–Legendre nodes and weights on [-1, 1] (Newton on P_n, Golub–Welsch accuracy).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights);

}  // namespace obscura
