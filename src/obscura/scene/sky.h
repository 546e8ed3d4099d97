#pragma once
// The radiance arriving from directions that hit neither surface nor cloud.
// Three forms (docs/formats.md, "sky"):
//  * black (no sky radiance: cold space), the default;
//  * a uniform blackbody of a given brightness temperature, over the whole
//    sphere (an enclosure, as in the furnace test) or only above the horizon;
//  * a user table of spectral radiance by zenith angle and wavelength,
//    bilinear in zenith angle (degrees) and wavelength (µm), clamped at the
//    table's first and last wavelengths. A table ending at 90° leaves the sky
//    below the horizon black; one ending at 180° covers the whole sphere.
// The sky is the same in every azimuth. Directions point from the scene
// towards the sky (+z is the zenith).
//
// Next-event estimation samples sky directions with sample(): uniform over the
// lit part of the sphere for the blackbody, and for a table piecewise uniform
// in cos θ with the probability of each zenith interval proportional to the
// table's radiance there (averaged over wavelength, each column normalised), so
// the density is shaped like the sky whatever the wavelength.
#include <string>
#include <vector>

#include "obscura/core/tabulated_spectrum.h"
#include "obscura/core/vec3.h"

namespace obscura {

class Sky {
 public:
  Sky() = default;  // black
  static Sky blackbody(double temperature_k, bool below_horizon);
  // radiance_w_m2_sr_um[i][j]: spectral radiance at zenith_deg[i] and
  // wavelengths_um[j]. Zenith angles strictly increasing from 0 to 90 or 180;
  // wavelengths strictly increasing; radiances finite and >= 0. Throws
  // InputError naming `source` and the offending field otherwise.
  static Sky zenith_table(std::vector<double> zenith_deg, std::vector<double> wavelengths_um,
                          std::vector<std::vector<double>> radiance_w_m2_sr_um,
                          const std::string& source = "sky");

  bool is_black() const { return kind_ == Kind::kBlack; }
  bool is_table() const { return kind_ == Kind::kTable; }
  double temperature_k() const { return temperature_k_; }

  // Spectral radiance seen in direction `toward_sky` (unit), W m⁻² sr⁻¹ µm⁻¹.
  double radiance(const Vec3& toward_sky, double wavelength_um) const;
  // (1/π) ∫ L(ω) (n·ω) dω over the hemisphere about `normal`: the radiance a
  // white Lambertian surface facing `normal` reflects. Closed form for the
  // blackbody sky ((1 + n_z)/2 of B above the horizon only: the sky view factor
  // of a tilted plane); for a table, a precomputed table over n_z.
  double cosine_weighted_mean(const Vec3& normal, double wavelength_um) const;

  // A direction from the sampling density (see above) and its pdf per sr.
  Vec3 sample(double u1, double u2, double* pdf) const;
  double pdf(const Vec3& toward_sky) const;

 private:
  enum class Kind { kBlack, kBlackbody, kTable };
  double table_radiance(double cos_zenith, double wavelength_um) const;
  std::vector<TabulatedSpectrum> reflected_table(const std::vector<double>& wavelengths_um) const;
  // Cosine of the largest zenith angle with sky radiance (−1 or 0).
  double lowest_cos_zenith() const;

  Kind kind_ = Kind::kBlack;
  double temperature_k_ = 0.0;
  bool below_horizon_ = true;
  // Table form.
  std::vector<double> zenith_deg_;
  std::vector<TabulatedSpectrum> radiance_;  // the spectrum at each zenith angle
  // Sampling: zenith intervals [zenith_i, zenith_i+1] chosen with cdf_.
  std::vector<double> interval_cdf_;
  // Reflected radiance: the spectrum at kNormalZ values of n_z from −1 to 1.
  std::vector<TabulatedSpectrum> reflected_;
};

}  // namespace obscura
