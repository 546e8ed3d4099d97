#pragma once
// How well a smoke screen hides a target, per frame, sensor and band, and over
// a frame sequence (docs/metrics.md has every formula).
//
// Per frame, over the target pixels T and background pixels B of a
// TargetMask (N_T, N_B pixels; t_i line-of-sight transmittance, L_i band
// radiance of pixel i):
//   transmittance mean  t̄ = Σ_T t_i / N_T, and its 10th, 50th, 90th percentiles;
//   screened fraction   s = #{i ∈ T : t_i < transmittance_threshold} / N_T;
//   mean radiances      L_T = Σ_T L_i / N_T,  L_B = Σ_B L_i / N_B   (W m⁻² sr⁻¹);
//   contrast            C = (L_T − L_B) / L_B   (Weber contrast of the mean
//                       radiances: the visible/NIR metric, reported for every band);
//   apparent temperatures T_T, T_B of L_T and L_B (K: the blackbody temperatures
//                       with those band radiances) and ΔT = T_T − T_B (K: the
//                       infrared metric, reported for every band).
// Undefined values are NaN: everything with no target pixel, the background
// values with no background pixel, C when L_B <= 0, an apparent temperature
// (and so ΔT) of a mean radiance <= 0.
//
// Over a sequence, the screened fraction is taken as linear between frames;
// the target counts as screened while s >= screened_fraction (the criterion).
#include <optional>
#include <string>
#include <vector>

#include "obscura/analysis/target_mask.h"
#include "obscura/core/band.h"
#include "obscura/film/sensor_image.h"
#include "obscura/scene/metrics_settings.h"
#include "obscura/scene/scene.h"

namespace obscura {

// Bands ending at or below this wavelength see reflected light (visible/NIR:
// contrast is their metric); bands starting at or above it see emission
// (thermal infrared: ΔT is their metric). Bands straddling it are neither.
inline constexpr double kThermalBoundaryUm = 2.5;
inline bool is_reflective_band(const Band& b) { return b.hi_um() <= kThermalBoundaryUm; }
inline bool is_thermal_band(const Band& b) { return b.lo_um() >= kThermalBoundaryUm; }

// The p-quantile (p in [0, 1]) of `sorted` (increasing) by linear interpolation
// between order statistics (Hyndman & Fan 1996, definition 7; numpy's
// default): with n values x₀ ≤ … ≤ x_{n−1}, h = (n − 1) p and k = ⌊h⌋,
// Q(p) = x_k + (h − k)(x_{k+1} − x_k). Q(0) is the minimum, Q(1) the maximum,
// one value is its own every percentile. NaN for no values.
double percentile_of_sorted(const std::vector<double>& sorted, double p);
// The same of unsorted values (sorts a copy).
double percentile(std::vector<double> values, double p);

// The metrics of one frame, sensor and band. Radiances W m⁻² sr⁻¹,
// temperatures K, times s, transmittances and fractions 1.
struct ScreeningMetrics {
  double time_s = 0;
  std::string sensor;
  Band band;
  int target_pixels = 0;
  int background_pixels = 0;
  double transmittance_mean = 0;
  double transmittance_p10 = 0, transmittance_p50 = 0, transmittance_p90 = 0;
  double screened_fraction = 0;
  double target_radiance = 0;
  double background_radiance = 0;
  double contrast = 0;
  double target_apparent_temperature_k = 0;
  double background_apparent_temperature_k = 0;
  double delta_t_k = 0;
};

// One row per band of `image`, whose sensor `mask` must describe (same size;
// Error otherwise). Apparent temperatures use the renderer's quadrature
// (RenderSettings::spectral_nodes of `render`), so a uniform blackbody region
// gives its temperature.
std::vector<ScreeningMetrics> screening_metrics(const SensorImage& image, const TargetMask& mask,
                                                const MetricsSettings& settings,
                                                const RenderSettings& render, double time_s);

// The time screening is measured from: the earliest activation time of the
// scene's animated clouds, or 0 s when it has none (static clouds are present
// at all times).
double screening_reference_time_s(const Scene& scene);

struct ScreenedInterval {
  double from_s = 0, until_s = 0;  // scene times, s; from_s <= until_s
};

// When a screened-fraction series meets the criterion.
struct ScreeningTimes {
  // Maximal intervals over which the criterion holds, in time order. Between
  // frames the fraction is linear, so an interval starts or ends where the
  // line crosses the criterion; a frame meeting it at either end of the
  // sequence makes the interval start at the first / end at the last frame.
  // A fraction touching the criterion at a single frame gives an interval of
  // length 0.
  std::vector<ScreenedInterval> intervals;
  // Start of the first interval minus the reference time, s (negative when
  // the criterion already holds before the reference time). Empty: never
  // screened.
  std::optional<double> time_to_screen_s;
  // The first interval (empty: never screened).
  std::optional<double> screened_from_s, screened_until_s;
  // Total length of the intervals, s (0 when never screened; empty when the
  // fractions are undefined).
  std::optional<double> screening_duration_s;
};

// `times_s` strictly increasing (Error otherwise), one fraction per time.
// Any NaN fraction (no target pixel) leaves every result empty.
ScreeningTimes screening_times(const std::vector<double>& times_s,
                               const std::vector<double>& screened_fractions, double criterion,
                               double reference_time_s);

// The summary of one (sensor, band) over a sequence of frames.
struct ScreeningSeries {
  std::string sensor;
  Band band;
  int target_pixels = 0;
  std::vector<double> times_s;  // the frames', increasing
  ScreeningTimes screening;
  double max_screened_fraction = 0;          // NaN with no target pixel
  double min_transmittance_mean = 0;         // lowest frame mean; NaN with no target pixel
  double min_transmittance_mean_time_s = 0;  // when it occurred (the first such frame)
};

// `rows` (any order) grouped by sensor and band, groups in order of first
// appearance, each group's rows in time order (pointers into `rows`).
std::vector<std::vector<const ScreeningMetrics*>> group_screening_series(
    const std::vector<ScreeningMetrics>& rows);

// Groups `rows` (several frames of each sensor and band) as
// group_screening_series and summarises each group.
std::vector<ScreeningSeries> summarize_screening(const std::vector<ScreeningMetrics>& rows,
                                                 const MetricsSettings& settings,
                                                 double reference_time_s);

}  // namespace obscura
