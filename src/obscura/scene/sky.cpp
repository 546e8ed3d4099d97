#include "obscura/scene/sky.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "obscura/core/band.h"
#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "obscura/core/sampling.h"

namespace obscura {
namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr int kNormalZ = 129;  // n_z samples of the reflected-radiance table

// Index i of the interval [v[i], v[i+1]] holding x (clamped to the ends).
std::size_t interval_of(const std::vector<double>& v, double x) {
  const auto it = std::upper_bound(v.begin(), v.end(), x);
  const std::size_t i = it == v.begin() ? 0 : static_cast<std::size_t>(it - v.begin()) - 1;
  return std::min(i, v.size() - 2);
}

// ∫_0^{2π} max(0, a + b cos ψ) dψ for b >= 0: the azimuthal integral of the
// cosine factor n·ω when ω has zenith cosine μ and n has zenith cosine n_z
// (a = n_z μ, b = sin θ_n sin θ).
double clamped_cosine_azimuth_integral(double a, double b) {
  if (a >= b) return 2.0 * std::numbers::pi * a;
  if (a <= -b) return 0.0;
  const double psi0 = std::acos(std::clamp(-a / b, -1.0, 1.0));
  return 2.0 * (a * psi0 + b * std::sin(psi0));
}

void check_increasing(const std::vector<double>& v, const std::string& source,
                      const std::string& field) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i]))
      throw InputError(source, fmt::format("{}/{}", field, i), "must be a finite number");
    if (i > 0 && !(v[i] > v[i - 1]))
      throw InputError(source, fmt::format("{}/{}", field, i), "must be strictly increasing");
  }
}

}  // namespace

Sky Sky::blackbody(double temperature_k, bool below_horizon) {
  Sky s;
  if (temperature_k > 0.0) s.kind_ = Kind::kBlackbody;
  s.temperature_k_ = temperature_k;
  s.below_horizon_ = below_horizon;
  return s;
}

Sky Sky::zenith_table(std::vector<double> zenith_deg, std::vector<double> wavelengths_um,
                      std::vector<std::vector<double>> radiance, const std::string& source) {
  if (zenith_deg.size() < 2)
    throw InputError(source, "zenith_deg", "needs at least two zenith angles (0 and 90 or 180)");
  check_increasing(zenith_deg, source, "zenith_deg");
  if (zenith_deg.front() != 0.0)
    throw InputError(source, "zenith_deg/0", "must be 0 (the table starts at the zenith)");
  if (zenith_deg.back() != 90.0 && zenith_deg.back() != 180.0)
    throw InputError(source, fmt::format("zenith_deg/{}", zenith_deg.size() - 1),
                     "must be 90 (black below the horizon) or 180 (the whole sphere)");
  if (wavelengths_um.empty())
    throw InputError(source, "wavelengths_um", "needs at least one wavelength");
  check_increasing(wavelengths_um, source, "wavelengths_um");
  if (!(wavelengths_um.front() > 0.0))
    throw InputError(source, "wavelengths_um/0", "must be > 0 µm");
  if (radiance.size() != zenith_deg.size())
    throw InputError(source, "radiance",
                     fmt::format("needs one row per zenith angle ({} rows, got {})",
                                 zenith_deg.size(), radiance.size()));
  Sky s;
  s.kind_ = Kind::kTable;
  const std::size_t nw = wavelengths_um.size();
  for (std::size_t i = 0; i < radiance.size(); ++i) {
    if (radiance[i].size() != nw)
      throw InputError(
          source, fmt::format("radiance/{}", i),
          fmt::format("needs one value per wavelength ({}, got {})", nw, radiance[i].size()));
    for (std::size_t j = 0; j < nw; ++j)
      if (!(std::isfinite(radiance[i][j]) && radiance[i][j] >= 0.0))
        throw InputError(source, fmt::format("radiance/{}/{}", i, j),
                         "must be a finite radiance >= 0 W m-2 sr-1 um-1");
    // Held at the end wavelengths: a table sky has radiance at every wavelength.
    s.radiance_.emplace_back(wavelengths_um, std::move(radiance[i]));
  }
  s.zenith_deg_ = std::move(zenith_deg);

  // Sampling weights per zenith interval: trapezoid of each column's radiance
  // (normalised by the column's largest value) times the interval's solid
  // angle per 2π, averaged over the columns.
  const std::size_t nz = s.zenith_deg_.size();
  std::vector<double> column_max(nw, 0.0);
  for (std::size_t i = 0; i < nz; ++i)
    for (std::size_t j = 0; j < nw; ++j)
      column_max[j] = std::max(column_max[j], s.radiance_[i].values()[j]);
  s.interval_cdf_.assign(nz, 0.0);
  for (std::size_t i = 0; i + 1 < nz; ++i) {
    double w = 0.0;
    for (std::size_t j = 0; j < nw; ++j)
      if (column_max[j] > 0.0)
        w += 0.5 * (s.radiance_[i].values()[j] + s.radiance_[i + 1].values()[j]) / column_max[j];
    const double solid =
        std::cos(s.zenith_deg_[i] * kDegToRad) - std::cos(s.zenith_deg_[i + 1] * kDegToRad);
    s.interval_cdf_[i + 1] = s.interval_cdf_[i] + w * solid;
  }
  if (!(s.interval_cdf_.back() > 0.0)) return Sky();  // all zero: a black sky
  for (double& c : s.interval_cdf_) c /= s.interval_cdf_.back();

  s.reflected_ = s.reflected_table(wavelengths_um);
  return s;
}

// Reflected radiance (1/π)∫ L(μ) K(μ; n_z) dμ at kNormalZ normals, with K the
// clamped-cosine azimuthal integral: Gauss–Legendre on pieces split at the
// table's zenith angles and at the kernel's kinks μ = ±sin θ_n, so every
// piece is smooth.
std::vector<TabulatedSpectrum> Sky::reflected_table(
    const std::vector<double>& wavelengths_um) const {
  const std::size_t nw = wavelengths_um.size();
  std::vector<double> gl_x, gl_w;
  gauss_legendre(16, gl_x, gl_w);
  std::vector<TabulatedSpectrum> rows;
  for (int k = 0; k < kNormalZ; ++k) {
    std::vector<double> reflected(nw, 0.0);
    const double n_z = -1.0 + 2.0 * k / (kNormalZ - 1);
    const double sin_n = std::sqrt(std::max(0.0, 1.0 - n_z * n_z));
    std::vector<double> breaks{-1.0, 1.0, sin_n, -sin_n};
    for (double z : zenith_deg_) breaks.push_back(std::cos(z * kDegToRad));
    std::sort(breaks.begin(), breaks.end());
    for (std::size_t b = 0; b + 1 < breaks.size(); ++b) {
      const double lo = breaks[b], hi = breaks[b + 1];
      if (!(hi > lo)) continue;
      for (std::size_t q = 0; q < gl_x.size(); ++q) {
        const double mu = 0.5 * (lo + hi) + 0.5 * (hi - lo) * gl_x[q];
        const double kernel = clamped_cosine_azimuth_integral(
            n_z * mu, sin_n * std::sqrt(std::max(0.0, 1.0 - mu * mu)));
        const double weight = 0.5 * (hi - lo) * gl_w[q] * kernel / std::numbers::pi;
        if (weight == 0.0) continue;
        for (std::size_t j = 0; j < nw; ++j)
          reflected[j] += weight * table_radiance(mu, wavelengths_um[j]);
      }
    }
    rows.emplace_back(wavelengths_um, std::move(reflected));
  }
  return rows;
}

double Sky::table_radiance(double cos_zenith, double wavelength_um) const {
  const double zenith = std::acos(std::clamp(cos_zenith, -1.0, 1.0)) / kDegToRad;
  if (zenith > zenith_deg_.back()) return 0.0;
  const std::size_t i = interval_of(zenith_deg_, zenith);
  const double fz =
      std::clamp((zenith - zenith_deg_[i]) / (zenith_deg_[i + 1] - zenith_deg_[i]), 0.0, 1.0);
  return (1 - fz) * radiance_[i](wavelength_um) + fz * radiance_[i + 1](wavelength_um);
}

double Sky::radiance(const Vec3& toward_sky, double wavelength_um) const {
  switch (kind_) {
    case Kind::kBlack:
      return 0.0;
    case Kind::kBlackbody:
      return (below_horizon_ || toward_sky.z > 0.0) ? planck_radiance(wavelength_um, temperature_k_)
                                                    : 0.0;
    case Kind::kTable:
      return table_radiance(toward_sky.z, wavelength_um);
  }
  return 0.0;
}

double Sky::cosine_weighted_mean(const Vec3& normal, double wavelength_um) const {
  switch (kind_) {
    case Kind::kBlack:
      return 0.0;
    case Kind::kBlackbody: {
      const double b = planck_radiance(wavelength_um, temperature_k_);
      return below_horizon_ ? b : b * 0.5 * (1.0 + std::clamp(normal.z, -1.0, 1.0));
    }
    case Kind::kTable: {
      const double x = (std::clamp(normal.z, -1.0, 1.0) + 1.0) * 0.5 * (kNormalZ - 1);
      const int k = std::min(static_cast<int>(x), kNormalZ - 2);
      const double fk = x - k;
      return (1 - fk) * reflected_[k](wavelength_um) + fk * reflected_[k + 1](wavelength_um);
    }
  }
  return 0.0;
}

double Sky::lowest_cos_zenith() const {
  if (kind_ == Kind::kTable) return zenith_deg_.back() == 90.0 ? 0.0 : -1.0;
  return below_horizon_ ? -1.0 : 0.0;
}

Vec3 Sky::sample(double u1, double u2, double* pdf) const {
  const double phi = 2.0 * std::numbers::pi * u2;
  double mu = 0.0;
  if (kind_ == Kind::kTable) {
    const std::size_t i = interval_of(interval_cdf_, u1);
    const double width = interval_cdf_[i + 1] - interval_cdf_[i];
    const double f = width > 0.0 ? std::clamp((u1 - interval_cdf_[i]) / width, 0.0, 1.0) : 0.5;
    const double c0 = std::cos(zenith_deg_[i] * kDegToRad),
                 c1 = std::cos(zenith_deg_[i + 1] * kDegToRad);
    mu = c0 + f * (c1 - c0);
  } else {
    const double lowest = lowest_cos_zenith();
    mu = 1.0 - u1 * (1.0 - lowest);
  }
  const double r = std::sqrt(std::max(0.0, 1.0 - mu * mu));
  const Vec3 d(r * std::cos(phi), r * std::sin(phi), mu);
  if (pdf) *pdf = this->pdf(d);
  return d;
}

double Sky::pdf(const Vec3& toward_sky) const {
  switch (kind_) {
    case Kind::kBlack:
      return 0.0;
    case Kind::kBlackbody:
      if (below_horizon_) return uniform_sphere_pdf();
      return toward_sky.z > 0.0 ? 0.5 * std::numbers::inv_pi : 0.0;
    case Kind::kTable: {
      const double zenith = std::acos(std::clamp(toward_sky.z, -1.0, 1.0)) / kDegToRad;
      if (zenith > zenith_deg_.back()) return 0.0;
      const std::size_t i = interval_of(zenith_deg_, zenith);
      const double solid =
          2.0 * std::numbers::pi *
          (std::cos(zenith_deg_[i] * kDegToRad) - std::cos(zenith_deg_[i + 1] * kDegToRad));
      return (interval_cdf_[i + 1] - interval_cdf_[i]) / solid;
    }
  }
  return 0.0;
}

}  // namespace obscura
