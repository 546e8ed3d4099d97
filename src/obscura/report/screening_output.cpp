#include "obscura/report/screening_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <optional>

#include "obscura/io/png_file.h"
#include "obscura/report/line_plot.h"

namespace obscura {
namespace {

// The numeric columns of a frame row, shared by the CSV (csv name, with units)
// and the JSON (json name; units in the document's "units").
struct Column {
  const char* csv;
  const char* json;
  std::function<double(const ScreeningMetrics&)> get;
};

const std::vector<Column>& numeric_columns() {
  static const std::vector<Column> columns = {
      {"band_min_um", "band_min_um", [](const auto& m) { return m.band.lo_um(); }},
      {"band_max_um", "band_max_um", [](const auto& m) { return m.band.hi_um(); }},
      {"target_pixels", "target_pixels", [](const auto& m) { return double(m.target_pixels); }},
      {"background_pixels", "background_pixels",
       [](const auto& m) { return double(m.background_pixels); }},
      {"transmittance_mean", "transmittance_mean",
       [](const auto& m) { return m.transmittance_mean; }},
      {"transmittance_p10", "transmittance_p10", [](const auto& m) { return m.transmittance_p10; }},
      {"transmittance_p50", "transmittance_p50", [](const auto& m) { return m.transmittance_p50; }},
      {"transmittance_p90", "transmittance_p90", [](const auto& m) { return m.transmittance_p90; }},
      {"screened_fraction", "screened_fraction", [](const auto& m) { return m.screened_fraction; }},
      {"target_radiance_W_m-2_sr-1", "target_radiance",
       [](const auto& m) { return m.target_radiance; }},
      {"background_radiance_W_m-2_sr-1", "background_radiance",
       [](const auto& m) { return m.background_radiance; }},
      {"contrast", "contrast", [](const auto& m) { return m.contrast; }},
      {"target_apparent_temperature_K", "target_apparent_temperature_k",
       [](const auto& m) { return m.target_apparent_temperature_k; }},
      {"background_apparent_temperature_K", "background_apparent_temperature_k",
       [](const auto& m) { return m.background_apparent_temperature_k; }},
      {"delta_t_K", "delta_t_k", [](const auto& m) { return m.delta_t_k; }},
  };
  return columns;
}

nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
}
nlohmann::json number_or_null(const std::optional<double>& v) {
  return v ? number_or_null(*v) : nlohmann::json();
}

std::string series_label(const ScreeningMetrics& m) { return m.sensor + " / " + m.band.name(); }

PlotSeries make_series(std::string label, const std::vector<const ScreeningMetrics*>& frames,
                       double ScreeningMetrics::*field, PlotSeries::Style style) {
  PlotSeries s;
  s.label = std::move(label);
  s.style = style;
  for (const ScreeningMetrics* m : frames) {
    s.x.push_back(m->time_s);
    s.y.push_back(m->*field);
  }
  return s;
}

bool has_finite_point(const LinePlot& plot) {
  for (const PlotSeries& s : plot.series)
    for (std::size_t i = 0; i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) return true;
  return false;
}

}  // namespace

std::string screening_metrics_csv(const std::vector<ScreeningMetrics>& rows) {
  std::string csv = "time_s,sensor,band";
  for (const Column& c : numeric_columns()) csv += fmt::format(",{}", c.csv);
  csv += "\n";
  for (const ScreeningMetrics& m : rows) {
    csv += fmt::format("{:.9g},{},{}", m.time_s, m.sensor, m.band.name());
    for (const Column& c : numeric_columns()) {
      const double v = c.get(m);
      csv += std::isfinite(v) ? fmt::format(",{:.9g}", v) : ",";
    }
    csv += "\n";
  }
  return csv;
}

nlohmann::json screening_settings_json(const MetricsSettings& settings, double reference_time_s) {
  return {
      {"transmittance_threshold", settings.transmittance_threshold},
      {"screened_fraction", settings.screened_fraction},
      {"background_margin_px", settings.background_margin_px},
      {"reference_time_s", reference_time_s},
      {"percentile_method", "linear interpolation between order statistics (Hyndman & Fan type 7)"},
      {"thermal_boundary_um", kThermalBoundaryUm}};
}

nlohmann::json screening_series_json(const std::vector<ScreeningSeries>& series) {
  nlohmann::json out = nlohmann::json::array();
  for (const ScreeningSeries& s : series) {
    nlohmann::json intervals = nlohmann::json::array();
    for (const auto& iv : s.screening.intervals) intervals.push_back({iv.from_s, iv.until_s});
    out.push_back(
        {{"sensor", s.sensor},
         {"band", s.band.name()},
         {"target_pixels", s.target_pixels},
         {"frames", s.times_s.size()},
         {"time_to_screen_s", number_or_null(s.screening.time_to_screen_s)},
         {"screened_from_s", number_or_null(s.screening.screened_from_s)},
         {"screened_until_s", number_or_null(s.screening.screened_until_s)},
         {"screening_duration_s", number_or_null(s.screening.screening_duration_s)},
         {"screened_intervals_s", intervals},
         {"max_screened_fraction", number_or_null(s.max_screened_fraction)},
         {"min_transmittance_mean", number_or_null(s.min_transmittance_mean)},
         {"min_transmittance_mean_time_s", number_or_null(s.min_transmittance_mean_time_s)}});
  }
  return out;
}

nlohmann::json target_masks_json(const std::vector<TargetMask>& masks) {
  nlohmann::json out = nlohmann::json::array();
  for (const TargetMask& m : masks) {
    out.push_back({{"sensor", m.sensor},
                   {"width", m.width},
                   {"height", m.height},
                   {"target_pixels", m.target_pixels},
                   {"background_pixels", m.background_pixels},
                   {"target_bbox_px",
                    m.empty() ? nlohmann::json() : nlohmann::json{m.x0, m.y0, m.x1, m.y1}}});
  }
  return out;
}

nlohmann::json screening_metrics_json(const nlohmann::json& provenance,
                                      const MetricsSettings& settings, double reference_time_s,
                                      const std::vector<TargetMask>& masks,
                                      const std::vector<ScreeningMetrics>& rows,
                                      const std::vector<ScreeningSeries>& series) {
  nlohmann::json frames = nlohmann::json::array();
  for (const ScreeningMetrics& m : rows) {
    nlohmann::json f = {{"time_s", m.time_s}, {"sensor", m.sensor}, {"band", m.band.name()}};
    for (const Column& c : numeric_columns()) f[c.json] = number_or_null(c.get(m));
    frames.push_back(std::move(f));
  }
  return {{"provenance", provenance},
          {"settings", screening_settings_json(settings, reference_time_s)},
          {"units",
           {{"time", "s"},
            {"radiance", "W m-2 sr-1"},
            {"apparent_temperature", "K"},
            {"delta_t", "K"},
            {"transmittance", "1"},
            {"screened_fraction", "1"},
            {"contrast", "1"},
            {"wavelength", "um"}}},
          {"targets", target_masks_json(masks)},
          {"frames", frames},
          {"series", screening_series_json(series)}};
}

ScreeningPlotFiles write_screening_plots(const std::filesystem::path& dir,
                                         const std::vector<ScreeningMetrics>& rows,
                                         const MetricsSettings& settings,
                                         const std::string& provenance_json) {
  const auto groups = group_screening_series(rows);
  const PlotAxis time_axis{"time (s)", false, std::nullopt, std::nullopt};
  using Style = PlotSeries::Style;

  LinePlot transmittance{"Target line-of-sight transmittance (mean, 10th and 90th percentiles)",
                         time_axis,
                         {"transmittance", false, -0.02, 1.02},
                         {}};
  LinePlot screened{fmt::format("Screened fraction of target pixels (transmittance < {:g})",
                                settings.transmittance_threshold),
                    time_axis,
                    {"screened fraction", false, -0.02, 1.02},
                    {}};
  LinePlot contrast{"Target contrast (L_target − L_background) / L_background, visible/NIR bands",
                    time_axis,
                    {"contrast", false, std::nullopt, std::nullopt},
                    {}};
  LinePlot delta_t{"Apparent temperature difference T_target − T_background, infrared bands",
                   time_axis,
                   {"ΔT (K)", false, std::nullopt, std::nullopt},
                   {}};
  double t_lo = std::numeric_limits<double>::infinity(), t_hi = -t_lo;
  for (const auto& g : groups) {
    const std::string label = series_label(*g.front());
    const Band& band = g.front()->band;
    transmittance.series.push_back(make_series(
        label + " mean", g, &ScreeningMetrics::transmittance_mean, Style::kLineAndMarkers));
    transmittance.series.push_back(
        make_series(label + " p10", g, &ScreeningMetrics::transmittance_p10, Style::kLine));
    transmittance.series.push_back(
        make_series(label + " p90", g, &ScreeningMetrics::transmittance_p90, Style::kLine));
    screened.series.push_back(
        make_series(label, g, &ScreeningMetrics::screened_fraction, Style::kLineAndMarkers));
    if (is_reflective_band(band))
      contrast.series.push_back(
          make_series(label, g, &ScreeningMetrics::contrast, Style::kLineAndMarkers));
    if (is_thermal_band(band))
      delta_t.series.push_back(
          make_series(label, g, &ScreeningMetrics::delta_t_k, Style::kLineAndMarkers));
    t_lo = std::min(t_lo, g.front()->time_s);
    t_hi = std::max(t_hi, g.back()->time_s);
  }
  // The criterion line only beside data: alone it would make a plot of nothing.
  if (has_finite_point(screened))
    screened.series.push_back({fmt::format("criterion {:g}", settings.screened_fraction),
                               {t_lo, t_hi},
                               {settings.screened_fraction, settings.screened_fraction},
                               Style::kLine});

  ScreeningPlotFiles files;
  auto write = [&](const char* name, const LinePlot& plot, const std::string& no_series) {
    if (plot.series.empty()) {
      files.skipped.push_back(fmt::format("{}: {}", name, no_series));
      return;
    }
    if (!has_finite_point(plot)) {
      files.skipped.push_back(fmt::format("{}: no defined value to plot (no target pixel?)", name));
      return;
    }
    write_line_plot_png(dir / name, plot, provenance_json);
    files.written.push_back(dir / name);
  };
  write(kTransmittancePlot, transmittance, "no sensor band");
  write(kScreenedFractionPlot, screened, "no sensor band");
  write(kContrastPlot, contrast,
        fmt::format("no visible/NIR band (upper edge <= {:g} µm)", kThermalBoundaryUm));
  write(kDeltaTPlot, delta_t,
        fmt::format("no infrared band (lower edge >= {:g} µm)", kThermalBoundaryUm));
  return files;
}

void write_target_mask_png(const std::filesystem::path& path, const TargetMask& mask,
                           const std::string& provenance_json) {
  std::vector<std::uint8_t> rgb(mask.labels.size() * 3);
  for (std::size_t i = 0; i < mask.labels.size(); ++i) {
    const std::uint8_t v = mask.labels[i] == MaskLabel::kTarget       ? 255
                           : mask.labels[i] == MaskLabel::kBackground ? 128
                                                                      : 0;
    rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = v;
  }
  std::map<std::string, std::string> chunks;
  if (!provenance_json.empty()) chunks["obscura.provenance"] = provenance_json;
  chunks["obscura.target_mask"] = "target 255, background 128, other 0";
  write_rgb_png(path, mask.width, mask.height, rgb, chunks);
}

std::string screening_summary_text(const std::vector<ScreeningSeries>& series,
                                   const MetricsSettings& settings, double reference_time_s) {
  std::string out = fmt::format(
      "screening metrics: a target pixel is screened below transmittance {:g}, the target while "
      "at least {:g} % of its pixels are; times to screen from t = {:g} s\n",
      settings.transmittance_threshold, 100.0 * settings.screened_fraction, reference_time_s);
  std::size_t width = 0;
  for (const ScreeningSeries& s : series)
    width = std::max(width, (s.sensor + " / " + s.band.name()).size());
  for (const ScreeningSeries& s : series) {
    const std::string label = s.sensor + " / " + s.band.name();
    out += fmt::format("  {:<{}}  ", label, width);
    if (s.target_pixels == 0) {
      out += "no target pixel in view: no metrics\n";
      continue;
    }
    const ScreeningTimes& st = s.screening;
    if (st.time_to_screen_s) {
      out +=
          fmt::format("time to screen {:.4g} s, screened {:.4g} s in all (first {:.4g}–{:.4g} s)",
                      *st.time_to_screen_s, *st.screening_duration_s, *st.screened_from_s,
                      *st.screened_until_s);
    } else {
      out += fmt::format("not screened (max screened fraction {:.3g})", s.max_screened_fraction);
    }
    out += fmt::format("; min mean transmittance {:.4g} at t = {:.4g} s ({} target px)\n",
                       s.min_transmittance_mean, s.min_transmittance_mean_time_s, s.target_pixels);
  }
  return out;
}

}  // namespace obscura
