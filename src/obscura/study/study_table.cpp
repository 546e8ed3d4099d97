#include "obscura/study/study_table.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "obscura/io/atomic_file.h"
#include "obscura/report/line_plot.h"

namespace obscura {
namespace {

// A column name made of letters, digits and '_' (band names like "8:12").
std::string column_word(const std::string& text) {
  std::string w;
  for (char c : text) w += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
  return w;
}

std::string csv_cell(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string q = "\"";
  for (char c : text) {
    q += c;
    if (c == '"') q += '"';
  }
  q += '"';
  return q;
}

// Ten significant digits: the metrics come from interpolation between frames,
// and 10.799999999999999 says no more than 10.8.
std::string number_cell(double v) { return std::isfinite(v) ? fmt::format("{:.10g}", v) : ""; }
std::string number_cell(const std::optional<double>& v) { return v ? number_cell(*v) : ""; }

std::string label_cell(const nlohmann::json& label) {
  return csv_cell(label.is_string() ? label.get<std::string>() : label.dump());
}

const CaseSeries* find_series(const CaseResult& c, const std::string& sensor,
                              const std::string& band) {
  for (const CaseSeries& s : c.series)
    if (s.sensor == sensor && s.band == band) return &s;
  return nullptr;
}

constexpr const char* kSeriesFigures[] = {"time_to_screen_s", "screening_duration_s",
                                          "min_transmittance", "max_screened_fraction"};

}  // namespace

std::vector<std::pair<std::string, std::string>> study_series_columns(const StudyResult& result) {
  std::vector<std::pair<std::string, std::string>> columns;
  for (const CaseResult& c : result.cases)
    for (const CaseSeries& s : c.series) {
      const std::pair<std::string, std::string> key{s.sensor, s.band};
      if (std::find(columns.begin(), columns.end(), key) == columns.end()) columns.push_back(key);
    }
  return columns;
}

std::string study_results_csv(const StudySpec& spec, const StudyResult& result) {
  const auto columns = study_series_columns(result);
  std::string csv = "case,id,status";
  for (const StudyAxis& a : spec.axes) csv += fmt::format(",{}", a.name);
  csv += ",seconds";
  for (const auto& [sensor, band] : columns)
    for (const char* figure : kSeriesFigures)
      csv += fmt::format(",{}_{}_{}", column_word(sensor), column_word(band), figure);
  csv += ",error\n";
  // Appends one cell (appending piecewise also keeps GCC 12's -Wrestrict quiet).
  auto cell = [&csv](const std::string& text) {
    csv += ',';
    csv += text;
  };
  for (const CaseResult& c : result.cases) {
    const StudyCase sc = study_case(spec, c.index);
    csv += fmt::format("{},{},{}", c.index, c.id, c.ok ? "ok" : "failed");
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
      cell(label_cell(spec.axes[a].labels[sc.value[a]]));
    cell(number_cell(c.seconds));
    for (const auto& [sensor, band] : columns) {
      const CaseSeries* s = find_series(c, sensor, band);
      cell(s ? number_cell(s->time_to_screen_s) : "");
      cell(s ? number_cell(s->screening_duration_s) : "");
      cell(s ? number_cell(s->min_transmittance) : "");
      cell(s ? number_cell(s->max_screened_fraction) : "");
    }
    cell(csv_cell(c.ok ? "" : c.error));
    csv += '\n';
  }
  return csv;
}

std::vector<std::filesystem::path> write_study_results(const StudySpec& spec,
                                                       const StudyResult& result,
                                                       const std::filesystem::path& out_dir,
                                                       const Provenance& provenance) {
  std::vector<std::filesystem::path> written;
  const auto csv_path = out_dir / "results.csv";
  write_text_file_atomic(csv_path, study_results_csv(spec, result));
  written.push_back(csv_path);

  nlohmann::json axes = nlohmann::json::array();
  for (const StudyAxis& a : spec.axes)
    axes.push_back({{"name", a.name},
                    {"file", a.file == StudyAxis::File::kPrepare ? "prepare" : "scene"},
                    {"path", a.path},
                    {"values", a.values},
                    {"labels", a.labels}});
  nlohmann::json cases = nlohmann::json::array();
  for (const CaseResult& c : result.cases) {
    nlohmann::json j = case_result_json(c);
    const StudyCase sc = study_case(spec, c.index);
    nlohmann::json parameters = nlohmann::json::object();
    for (std::size_t a = 0; a < spec.axes.size(); ++a)
      parameters[spec.axes[a].name] = spec.axes[a].labels[sc.value[a]];
    j["parameters"] = parameters;
    j["resumed"] = c.resumed;
    cases.push_back(std::move(j));
  }
  const nlohmann::json doc = {{"provenance", provenance.to_json()},
                              {"study", spec.file.string()},
                              {"combine", spec.zip ? "zip" : "grid"},
                              {"times_s", spec.times_s},
                              {"axes", axes},
                              {"cases", cases},
                              {"failed", result.failed},
                              {"resumed", result.resumed},
                              {"seconds", result.seconds},
                              {"units",
                               {{"time_to_screen_s", "s"},
                                {"screening_duration_s", "s"},
                                {"min_transmittance", "1"},
                                {"max_screened_fraction", "1"},
                                {"seconds", "s"}}}};
  const auto json_path = out_dir / "results.json";
  write_text_file_atomic(json_path, doc.dump(2) + "\n");
  written.push_back(json_path);

  // The screening duration per case, one series per sensor and band.
  LinePlot plot;
  plot.title = "Screening duration per case";
  plot.x.label = "case";
  plot.y.label = "screening duration (s)";
  plot.y.min = 0.0;
  bool any = false;
  for (const auto& [sensor, band] : study_series_columns(result)) {
    PlotSeries series;
    series.label = sensor + " " + band;
    series.style = PlotSeries::Style::kMarkers;
    for (const CaseResult& c : result.cases) {
      const CaseSeries* s = find_series(c, sensor, band);
      series.x.push_back(static_cast<double>(c.index));
      series.y.push_back(s && s->screening_duration_s ? *s->screening_duration_s
                                                      : std::numeric_limits<double>::quiet_NaN());
      any = any || std::isfinite(series.y.back());
    }
    plot.series.push_back(std::move(series));
  }
  if (any && result.cases.size() > 1) {
    const auto png = out_dir / "screening.png";
    write_line_plot_png(png, plot, provenance.to_string());
    written.push_back(png);
  }
  return written;
}

}  // namespace obscura
