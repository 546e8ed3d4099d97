#pragma once
// A quantity tabulated against wavelength: rows (λ_i µm, strictly increasing;
// v_i), linear between rows, v(λ) = v_i + f (v_{i+1} − v_i) with
// f = (λ − λ_i)/(λ_{i+1} − λ_i) (a constant table stays exactly constant).
// Outside the table the value is held at the end rows or is zero, as the
// quantity requires: a surface's emissivity and a refractive index are held,
// a sensor's response and a sun's irradiance table are zero beyond their
// ends. One type for every such table (sun, surface emissivity, band
// response, sky radiance per zenith row, refractive indices), and one
// bracketing rule shared with the media's spectral samples (SpectralLerp).
#include <cstddef>
#include <vector>

namespace obscura {

// Where λ falls among strictly increasing wavelengths: rows `lower` and
// `upper` and the weight `frac` of the upper one; clamped to the ends
// (lower = upper, frac = 0 there). One wavelength: always row 0.
struct WavelengthBracket {
  std::size_t lower = 0, upper = 0;
  double frac = 0.0;
};
WavelengthBracket bracket_wavelength(const std::vector<double>& wavelengths_um,
                                     double wavelength_um);

class TabulatedSpectrum {
 public:
  enum class Outside { kHold, kZero };

  TabulatedSpectrum() = default;  // empty: no rows
  // Throws Error unless there is at least one row, one value per wavelength,
  // wavelengths finite, > 0 and strictly increasing, values finite.
  TabulatedSpectrum(std::vector<double> wavelengths_um, std::vector<double> values,
                    Outside outside = Outside::kHold);

  bool empty() const { return wavelengths_um_.empty(); }
  std::size_t size() const { return wavelengths_um_.size(); }
  const std::vector<double>& wavelengths_um() const { return wavelengths_um_; }
  const std::vector<double>& values() const { return values_; }
  double front_um() const { return wavelengths_um_.front(); }
  double back_um() const { return wavelengths_um_.back(); }
  Outside outside() const { return outside_; }
  bool covers(double wavelength_um) const {
    return !empty() && wavelength_um >= front_um() && wavelength_um <= back_um();
  }

  // The value at λ (µm); 0 for an empty table.
  double operator()(double wavelength_um) const;

 private:
  std::vector<double> wavelengths_um_, values_;
  Outside outside_ = Outside::kHold;
};

}  // namespace obscura
