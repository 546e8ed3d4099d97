#include "obscura/core/tabulated_spectrum.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "obscura/core/error.h"

namespace obscura {

WavelengthBracket bracket_wavelength(const std::vector<double>& w, double wavelength_um) {
  WavelengthBracket b;
  if (w.size() <= 1 || wavelength_um <= w.front()) return b;
  if (wavelength_um >= w.back()) {
    b.lower = b.upper = w.size() - 1;
    return b;
  }
  b.upper =
      static_cast<std::size_t>(std::upper_bound(w.begin(), w.end(), wavelength_um) - w.begin());
  b.lower = b.upper - 1;
  b.frac = (wavelength_um - w[b.lower]) / (w[b.upper] - w[b.lower]);
  return b;
}

TabulatedSpectrum::TabulatedSpectrum(std::vector<double> wavelengths_um, std::vector<double> values,
                                     Outside outside)
    : wavelengths_um_(std::move(wavelengths_um)), values_(std::move(values)), outside_(outside) {
  if (wavelengths_um_.empty()) throw Error("tabulated spectrum: no rows");
  if (values_.size() != wavelengths_um_.size())
    throw Error("tabulated spectrum: " + std::to_string(wavelengths_um_.size()) +
                " wavelengths but " + std::to_string(values_.size()) + " values");
  for (std::size_t i = 0; i < wavelengths_um_.size(); ++i) {
    const double w = wavelengths_um_[i];
    if (!(std::isfinite(w) && w > 0.0) || (i > 0 && !(w > wavelengths_um_[i - 1])))
      throw Error("tabulated spectrum: wavelength " + std::to_string(i) +
                  " must be finite, > 0 µm and above the one before");
    if (!std::isfinite(values_[i]))
      throw Error("tabulated spectrum: value " + std::to_string(i) + " must be finite");
  }
}

double TabulatedSpectrum::operator()(double wavelength_um) const {
  if (empty()) return 0.0;
  if (outside_ == Outside::kZero && !covers(wavelength_um)) return 0.0;
  const WavelengthBracket b = bracket_wavelength(wavelengths_um_, wavelength_um);
  const double lo = values_[b.lower];
  return b.frac == 0.0 ? lo : lo + b.frac * (values_[b.upper] - lo);
}

}  // namespace obscura
