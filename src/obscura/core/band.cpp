#include "obscura/core/band.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <numbers>

#include "obscura/core/error.h"
#include "obscura/core/planck.h"

namespace obscura {
namespace {

// The bracket apparent_temperature searches, K.
constexpr double kApparentTemperatureLowK = 1.0, kApparentTemperatureHighK = 1.0e6;

}  // namespace

Band Band::flat(std::string name, double lo_um, double hi_um) {
  return tabulated(std::move(name), {{lo_um, 1.0}, {hi_um, 1.0}});
}

Band Band::tabulated(std::string name, std::vector<ResponsePoint> table) {
  const std::string field = "band '" + name + "'";
  if (table.size() < 2) throw InputError("", field, "a response table needs at least 2 points");
  for (std::size_t i = 0; i < table.size(); ++i) {
    const auto& p = table[i];
    if (!(std::isfinite(p.wavelength_um) && p.wavelength_um > 0.0))
      throw InputError("", field,
                       fmt::format("wavelength {} µm must be finite and > 0", p.wavelength_um));
    if (!(std::isfinite(p.response) && p.response >= 0.0))
      throw InputError("", field, fmt::format("response {} must be finite and >= 0", p.response));
    if (i > 0 && !(p.wavelength_um > table[i - 1].wavelength_um))
      throw InputError("", field, "wavelengths must be strictly increasing");
  }
  if (std::all_of(table.begin(), table.end(), [](auto& p) { return p.response == 0.0; }))
    throw InputError("", field, "response is zero everywhere");
  Band b;
  b.name_ = std::move(name);
  std::vector<double> wavelengths, responses;
  for (const ResponsePoint& p : table) {
    wavelengths.push_back(p.wavelength_um);
    responses.push_back(p.response);
  }
  b.response_ = TabulatedSpectrum(std::move(wavelengths), std::move(responses),
                                  TabulatedSpectrum::Outside::kZero);
  return b;
}

Band Band::preset(const std::string& name) {
  if (name == "visible") return flat(name, 0.4, 0.7);
  // A 10 nm band-pass filter centred on the Nd:YAG line at 1.064 µm.
  if (name == "laser1064") return flat(name, 1.059, 1.069);
  if (name == "mwir") return flat(name, 3.0, 5.0);
  if (name == "lwir") return flat(name, 8.0, 12.0);
  std::string known;
  for (auto& n : preset_names()) known += (known.empty() ? "" : ", ") + n;
  throw InputError("", "band", fmt::format("unknown band preset '{}' (known: {})", name, known));
}

std::vector<std::string> Band::preset_names() { return {"visible", "laser1064", "mwir", "lwir"}; }

Band Band::parse(const std::string& text, const std::string& field) {
  const auto colon = text.find(':');
  if (colon == std::string::npos) {
    const auto names = preset_names();
    if (std::find(names.begin(), names.end(), text) != names.end()) return preset(text);
    throw InputError(
        "", field,
        fmt::format("'{}' is neither LO:HI in µm nor a preset ({})", text, fmt::join(names, ", ")));
  }
  auto to_double = [&](std::string_view s) {
    double v = 0;
    auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v))
      throw InputError("", field, fmt::format("'{}' is not LO:HI with numbers in µm", text));
    return v;
  };
  const std::string_view sv(text);
  const double lo = to_double(sv.substr(0, colon));
  const double hi = to_double(sv.substr(colon + 1));
  if (!(lo > 0.0 && hi > lo))
    throw InputError("", field, fmt::format("band {} needs 0 < LO < HI (µm)", text));
  return flat(text, lo, hi);
}

void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(n, 0.0);
  weights.assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Initial guess (Tricomi), then Newton on P_n(x) using the three-term recurrence.
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double dp = 0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) {
        p1 = x;
        p0 = 1.0;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) break;
    }
    nodes[i] = -x;
    nodes[n - 1 - i] = x;
    const double w = 2.0 / ((1.0 - x * x) * dp * dp);
    weights[i] = weights[n - 1 - i] = w;
  }
  if (n % 2 == 1) nodes[n / 2] = 0.0;
}

BandQuadrature::BandQuadrature(const Band& band, int nodes_per_panel, double max_panel_ratio) {
  if (nodes_per_panel < 1) throw Error("BandQuadrature: nodes_per_panel must be >= 1");
  std::vector<double> gx, gw;
  gauss_legendre(nodes_per_panel, gx, gw);
  const std::vector<double>& breaks = band.response_table().wavelengths_um();
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    int panels = 1;
    if (max_panel_ratio > 1.0 && b / a > max_panel_ratio)
      panels = static_cast<int>(std::ceil(std::log(b / a) / std::log(max_panel_ratio)));
    const double r = std::pow(b / a, 1.0 / panels);
    double lo = a;
    for (int p = 0; p < panels; ++p) {
      const double hi = (p + 1 == panels) ? b : lo * r;
      const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
      for (int k = 0; k < nodes_per_panel; ++k) {
        const double lam = mid + half * gx[k];
        const double w = half * gw[k] * band.response(lam);
        if (w == 0.0) continue;
        nodes_um_.push_back(lam);
        weights_um_.push_back(w);
        response_integral_ += w;
      }
      lo = hi;
    }
  }
  for (std::size_t i = 0; i < nodes_um_.size(); ++i) centroid_um_ += weights_um_[i] * nodes_um_[i];
  if (response_integral_ > 0) centroid_um_ /= response_integral_;
  radiance_at_1k_ = blackbody_radiance(kApparentTemperatureLowK);
  radiance_at_1e6k_ = blackbody_radiance(kApparentTemperatureHighK);
}

BandQuadrature BandQuadrature::accurate(const Band& band) { return BandQuadrature(band, 12, 1.05); }

double BandQuadrature::blackbody_radiance(double temperature_k) const {
  double sum = 0;
  for (std::size_t i = 0; i < nodes_um_.size(); ++i)
    sum += weights_um_[i] * planck_radiance(nodes_um_[i], temperature_k);
  return sum;
}

double BandQuadrature::blackbody_radiance_dT(double temperature_k) const {
  double sum = 0;
  for (std::size_t i = 0; i < nodes_um_.size(); ++i)
    sum += weights_um_[i] * planck_radiance_dT(nodes_um_[i], temperature_k);
  return sum;
}

double BandQuadrature::blackbody_radiance_and_dT(double temperature_k, double& d_dt) const {
  double sum = 0, sum_dt = 0;
  d_dt = 0;
  if (temperature_k <= 0.0) return 0.0;
  for (std::size_t i = 0; i < nodes_um_.size(); ++i) {
    // B = c1L / (λ⁵ (eˣ − 1)), dB/dT = B (x / T) (1 + 1 / (eˣ − 1)),
    // x = c2 / (λ T): finite (zero) where eˣ overflows.
    const double lambda = nodes_um_[i];
    const double x = kC2_umK / (lambda * temperature_k);
    const double l5 = lambda * lambda * lambda * lambda * lambda;
    const double em1 = std::expm1(x);
    const double b = kC1L_um / (l5 * em1);
    sum += weights_um_[i] * b;
    sum_dt += weights_um_[i] * (b * x / temperature_k * (1.0 + 1.0 / em1));
  }
  d_dt = sum_dt;
  return sum;
}

double BandQuadrature::integrate(const double* values) const {
  double sum = 0;
  for (std::size_t i = 0; i < nodes_um_.size(); ++i) sum += weights_um_[i] * values[i];
  return sum;
}

double BandQuadrature::apparent_temperature(double band_radiance) const {
  if (!(band_radiance > 0.0)) return 0.0;
  if (!std::isfinite(band_radiance)) return band_radiance;
  // Bracket in [lo, hi]; L(T) is strictly increasing. Newton on f(T) = ln L(T) − ln L*,
  // which is close to linear in 1/T (Wien), with bisection whenever a step leaves the bracket.
  double lo = kApparentTemperatureLowK, hi = kApparentTemperatureHighK;
  const double target = std::log(band_radiance);
  if (std::log(radiance_at_1e6k_) < target) return std::numeric_limits<double>::infinity();
  if (radiance_at_1k_ > 0 && std::log(radiance_at_1k_) > target) return lo;
  // Start from the monochromatic brightness temperature at the band centroid.
  const double centroid = centroid_um_;
  const double mean_spectral = band_radiance / response_integral_;
  double t = kC2_umK / (centroid * std::log1p(kC1L_um / (std::pow(centroid, 5) * mean_spectral)));
  if (!(t > lo && t < hi)) t = std::sqrt(lo * hi);
  for (int iter = 0; iter < 200; ++iter) {
    double dl_dt;
    const double l = blackbody_radiance_and_dT(t, dl_dt);
    const double f = (l > 0 ? std::log(l) : -1e300) - target;
    if (f > 0)
      hi = t;
    else
      lo = t;
    const double df = dl_dt / l;
    double next = t - f / df;
    if (!(next > lo && next < hi) || !std::isfinite(next)) next = 0.5 * (lo + hi);
    if (std::abs(next - t) <= 1e-12 * t) return next;
    t = next;
  }
  return t;
}

}  // namespace obscura
