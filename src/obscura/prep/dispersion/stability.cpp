#include "obscura/prep/dispersion/stability.h"

#include <algorithm>
#include <cmath>

namespace obscura {

namespace {

// One row of a σ table: σ = a x^b for the puff set.
struct PowerLaw {
  double a, b;
};

// Instantaneous puff σ, Slade (1968) "Meteorology and Atomic Energy" as
// tabulated in CCPS (1999) "Guidelines for Consequence Analysis of Chemical
// Releases" (docs/domain.md §3.4, "Instantaneous puff σ"); the same constants are
// in GasDispersion.jl `src/utils/equation_sets/ccps.jl`. The
// correlations were fitted to field trials far from the source; within tens
// of metres they are extrapolations, and there the device's initial cloud size
// (added in quadrature, docs/domain.md §3.1) dominates anyway.
constexpr PowerLaw kPuffHorizontal[6] = {{0.18, 0.92}, {0.14, 0.92}, {0.10, 0.92},
                                         {0.06, 0.92}, {0.04, 0.92}, {0.02, 0.89}};
constexpr PowerLaw kPuffVertical[6] = {{0.60, 0.75}, {0.53, 0.73}, {0.34, 0.71},
                                       {0.15, 0.70}, {0.10, 0.65}, {0.05, 0.61}};

// Briggs (1973) open-country (rural) plume σ (docs/domain.md §3.4, second table; as
// in CCPS 1999 and GasDispersion.jl `ccps.jl`, `CCPSRural`), for 10²–10⁴ m:
//   σy = c x (1 + 0.0001 x)^(−½)
//   σz = d x (1 + e x)^(−n)
constexpr double kBriggsY[6] = {0.22, 0.16, 0.11, 0.08, 0.06, 0.04};
struct BriggsVertical {
  double d, e, n;
};
constexpr BriggsVertical kBriggsZ[6] = {{0.20, 0.0, 0.0},    {0.12, 0.0, 0.0},
                                        {0.08, 0.0002, 0.5}, {0.06, 0.0015, 0.5},
                                        {0.03, 0.0003, 1.0}, {0.016, 0.0003, 1.0}};

int row(StabilityClass s) { return static_cast<int>(s); }

}  // namespace

std::optional<StabilityClass> parse_stability_class(const std::string& text) {
  if (text.size() != 1 || text[0] < 'A' || text[0] > 'F') return std::nullopt;
  return static_cast<StabilityClass>(text[0] - 'A');
}

std::string to_string(StabilityClass stability) {
  return std::string(1, static_cast<char>('A' + row(stability)));
}

std::optional<SigmaSet> parse_sigma_set(const std::string& text) {
  if (text == "ccps-puff") return SigmaSet::kCcpsPuff;
  if (text == "briggs-open-country") return SigmaSet::kBriggsOpenCountry;
  return std::nullopt;
}

std::string to_string(SigmaSet set) {
  return set == SigmaSet::kCcpsPuff ? "ccps-puff" : "briggs-open-country";
}

DispersionSigmas dispersion_sigmas(SigmaSet set, StabilityClass stability, double downwind_m) {
  const double x = std::max(downwind_m, 0.0);
  const int r = row(stability);
  DispersionSigmas s;
  if (set == SigmaSet::kCcpsPuff) {
    s.y_m = kPuffHorizontal[r].a * std::pow(x, kPuffHorizontal[r].b);
    s.z_m = kPuffVertical[r].a * std::pow(x, kPuffVertical[r].b);
  } else {
    s.y_m = kBriggsY[r] * x / std::sqrt(1.0 + 0.0001 * x);
    const BriggsVertical& v = kBriggsZ[r];
    s.z_m = v.d * x * std::pow(1.0 + v.e * x, -v.n);
  }
  s.x_m = s.y_m;
  return s;
}

double default_wind_profile_exponent(StabilityClass stability) {
  // CCPS (1999) rural power-law exponents (docs/domain.md §3.6).
  constexpr double kRural[6] = {0.07, 0.07, 0.10, 0.15, 0.35, 0.55};
  return kRural[row(stability)];
}

}  // namespace obscura
