#pragma once
// Pasquill–Gifford atmospheric stability classes and the dispersion
// coefficients σx, σy, σz (m) as functions of downwind travel distance x (m)
// that the built-in dispersion model grows its puffs with (docs/dispersion.md,
// docs/domain.md §3.4–3.7).
#include <optional>
#include <string>

namespace obscura {

// Pasquill (1961) classes: A very unstable … D neutral … F moderately stable.
enum class StabilityClass { kA, kB, kC, kD, kE, kF };

// "A".."F" (upper case only, as the tables write them); nullopt otherwise.
std::optional<StabilityClass> parse_stability_class(const std::string& text);
std::string to_string(StabilityClass stability);

// Which table of σ(x) correlations to use.
enum class SigmaSet {
  // Instantaneous puff σ (Slade 1968, as tabulated in CCPS 1999): the right
  // set for puffs, and the default (docs/domain.md §3.7).
  kCcpsPuff,
  // Briggs (1973) open-country plume σ (10-min averaged continuous plumes):
  // offered for long-averaged plume studies; it grows several times faster.
  kBriggsOpenCountry,
};

// "ccps-puff" or "briggs-open-country"; nullopt otherwise.
std::optional<SigmaSet> parse_sigma_set(const std::string& text);
std::string to_string(SigmaSet set);

struct DispersionSigmas {
  double x_m = 0;  // along the wind
  double y_m = 0;  // across the wind (horizontal)
  double z_m = 0;  // vertical
};

// σx, σy, σz at travel distance `downwind_m` (>= 0; 0 gives 0). Both sets have
// σx = σy: Slade's puff table states it; Briggs' plume table has no σx and the
// usual puff practice (CCPS 1999) takes σx = σy.
DispersionSigmas dispersion_sigmas(SigmaSet set, StabilityClass stability, double downwind_m);

// Default exponent p of the power-law wind profile u(z) = u_ref (z/z_ref)^p for
// rural terrain (CCPS 1999, docs/domain.md §3.6): A–B 0.07, C 0.10, D 0.15,
// E 0.35, F 0.55.
double default_wind_profile_exponent(StabilityClass stability);

}  // namespace obscura
