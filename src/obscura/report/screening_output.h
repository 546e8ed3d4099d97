#pragma once
// Writes screening metrics (analysis/screening_metrics.h, docs/metrics.md):
// metrics.csv (one row per frame, sensor and band), metrics.json (settings,
// frames, per sensor/band summary), one PNG plot per metric against time, the
// target masks as PNGs, and the text summary the CLI prints. Every file goes
// through an AtomicFile (temporary name, then rename).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/scene/metrics_settings.h"

namespace obscura {

// The header and one line per row; undefined values (NaN) are empty cells.
std::string screening_metrics_csv(const std::vector<ScreeningMetrics>& rows);

// {"transmittance_threshold", "screened_fraction", "background_margin_px",
//  "reference_time_s", "percentile_method", "thermal_boundary_um"}.
nlohmann::json screening_settings_json(const MetricsSettings& settings, double reference_time_s);
// One object per series: sensor, band, target pixels, time_to_screen_s,
// screened_from_s, screened_until_s, screening_duration_s (null where not
// reached or undefined), intervals, max screened fraction, min mean transmittance.
nlohmann::json screening_series_json(const std::vector<ScreeningSeries>& series);
// One object per mask: sensor, size, target and background pixels, bounding box.
nlohmann::json target_masks_json(const std::vector<TargetMask>& masks);
// The whole metrics.json document: provenance, settings, units, masks, frames, series.
nlohmann::json screening_metrics_json(const nlohmann::json& provenance,
                                      const MetricsSettings& settings, double reference_time_s,
                                      const std::vector<TargetMask>& masks,
                                      const std::vector<ScreeningMetrics>& rows,
                                      const std::vector<ScreeningSeries>& series);

// File names of the plots, in the order written.
inline constexpr const char* kTransmittancePlot = "metrics_transmittance.png";
inline constexpr const char* kScreenedFractionPlot = "metrics_screened_fraction.png";
inline constexpr const char* kContrastPlot = "metrics_contrast.png";
inline constexpr const char* kDeltaTPlot = "metrics_delta_t.png";

struct ScreeningPlotFiles {
  std::vector<std::filesystem::path> written;
  // "<file>: <why>" for each plot not written (no eligible band, or no
  // finite value to draw).
  std::vector<std::string> skipped;
};

// The four plots against time (s), one series per sensor/band: mean
// transmittance with its 10th and 90th percentiles; screened fraction with
// the criterion as a horizontal line; contrast for visible/NIR bands only
// (is_reflective_band); ΔT for thermal bands only (is_thermal_band).
ScreeningPlotFiles write_screening_plots(const std::filesystem::path& dir,
                                         const std::vector<ScreeningMetrics>& rows,
                                         const MetricsSettings& settings,
                                         const std::string& provenance_json);

// The mask as an 8-bit RGB PNG, one PNG pixel per sensor pixel: target white,
// background grey (128), other pixels black.
void write_target_mask_png(const std::filesystem::path& path, const TargetMask& mask,
                           const std::string& provenance_json);

// The text summary: the criterion, then per series the time to screen, the
// screening duration and first interval, and the lowest mean transmittance.
std::string screening_summary_text(const std::vector<ScreeningSeries>& series,
                                   const MetricsSettings& settings, double reference_time_s);

}  // namespace obscura
