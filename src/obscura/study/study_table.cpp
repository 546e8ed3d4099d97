#include "obscura/study/study_table.h"

#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "obscura/core/version.h"
#include "obscura/io/atomic_file.h"
#include "obscura/io/netcdf_output_file.h"
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

void write_study_netcdf(const std::filesystem::path& path, const StudySpec& spec,
                        const StudyResult& result, const Provenance& provenance) {
  const auto columns = study_series_columns(result);
  const std::size_t n = result.cases.size();
  NetcdfOutputFile f(path);
  const int g = NetcdfOutputFile::kGlobal;
  f.put_attribute(g, "Conventions", "CF-1.10");
  f.put_attribute(g, "title", "obscura parameter study " + spec.file.filename().string());
  f.put_attribute(g, "source", fmt::format("obscura {}", kVersion));
  f.put_attribute(g, "history", provenance.created_utc + ": " + provenance.command_line);
  f.put_attribute(g, "comment",
                  "One entry per case along dimension case; each axis of the study is a "
                  "variable of its labels; <sensor>_<band>_<figure> are the screening figures "
                  "of docs/metrics.md (NaN: never screened, or the case failed).");
  f.put_attribute(g, "provenance", provenance.to_string());
  f.put_attribute(g, "times_s", spec.times_s);
  const int dim = f.define_dimension("case", n);
  const int index = f.define_variable("case", NcType::kInt, {dim});
  f.put_attribute(index, "long_name", "case number");
  const int id = f.define_variable("id", NcType::kString, {dim});
  const int status = f.define_variable("status", NcType::kString, {dim});
  f.put_attribute(status, "long_name", "ok, or failed (error says why)");
  const int error = f.define_variable("error", NcType::kString, {dim});
  const int seconds = f.define_variable("seconds", NcType::kDouble, {dim});
  f.put_attribute(seconds, "units", "s");
  f.put_attribute(seconds, "long_name", "wall time of the case");
  // An axis whose labels are all numbers is a number variable, else text.
  std::vector<int> axis_vars;
  std::vector<bool> numeric;
  for (const StudyAxis& a : spec.axes) {
    bool all_numbers = true;
    for (const nlohmann::json& l : a.labels) all_numbers = all_numbers && l.is_number();
    numeric.push_back(all_numbers);
    const int v = f.define_variable(a.name, all_numbers ? NcType::kDouble : NcType::kString, {dim});
    f.put_attribute(v, "long_name",
                    fmt::format("study axis: {} of {}", a.path,
                                a.file == StudyAxis::File::kPrepare ? "prepare" : "scene"));
    axis_vars.push_back(v);
  }
  struct Figure {
    const char* name;
    const char* units;
    const char* long_name;
  };
  constexpr Figure figures[] = {
      {"time_to_screen_s", "s", "time from the reference time to the first screened interval"},
      {"screening_duration_s", "s", "total time screened"},
      {"min_transmittance", "1", "lowest mean transmittance over the target"},
      {"max_screened_fraction", "1", "largest fraction of target pixels screened"}};
  std::vector<int> figure_vars;
  for (const auto& [sensor, band] : columns)
    for (const Figure& fig : figures) {
      const int v = f.define_variable(
          fmt::format("{}_{}_{}", column_word(sensor), column_word(band), fig.name),
          NcType::kDouble, {dim});
      f.put_attribute(v, "units", fig.units);
      f.put_attribute(v, "long_name", fmt::format("{} ({} {})", fig.long_name, sensor, band));
      f.put_attribute(v, "_FillValue", std::vector<double>{std::nan("")});
      figure_vars.push_back(v);
    }
  f.end_definitions();
  if (n > 0) {
    const std::vector<std::size_t> start{0}, count{n};
    std::vector<int> indices;
    std::vector<std::string> ids, statuses, errors;
    std::vector<double> secs;
    for (const CaseResult& c : result.cases) {
      indices.push_back(static_cast<int>(c.index));
      ids.push_back(c.id);
      statuses.push_back(c.ok ? "ok" : "failed");
      errors.push_back(c.ok ? "" : c.error);
      secs.push_back(c.seconds);
    }
    f.put(index, start, count, indices.data());
    f.put(id, start, count, ids);
    f.put(status, start, count, statuses);
    f.put(error, start, count, errors);
    f.put(seconds, start, count, secs.data());
    for (std::size_t a = 0; a < spec.axes.size(); ++a) {
      std::vector<double> numbers;
      std::vector<std::string> texts;
      for (const CaseResult& c : result.cases) {
        const nlohmann::json& l = spec.axes[a].labels[study_case(spec, c.index).value[a]];
        if (numeric[a])
          numbers.push_back(l.get<double>());
        else
          texts.push_back(l.is_string() ? l.get<std::string>() : l.dump());
      }
      if (numeric[a])
        f.put(axis_vars[a], start, count, numbers.data());
      else
        f.put(axis_vars[a], start, count, texts);
    }
    std::size_t v = 0;
    const double nan = std::nan("");
    for (const auto& [sensor, band] : columns) {
      std::vector<std::vector<double>> values(4);
      for (const CaseResult& c : result.cases) {
        const CaseSeries* s = find_series(c, sensor, band);
        values[0].push_back(s && s->time_to_screen_s ? *s->time_to_screen_s : nan);
        values[1].push_back(s && s->screening_duration_s ? *s->screening_duration_s : nan);
        values[2].push_back(s ? s->min_transmittance : nan);
        values[3].push_back(s ? s->max_screened_fraction : nan);
      }
      for (const std::vector<double>& column : values)
        f.put(figure_vars[v++], start, count, column.data());
    }
  }
  f.commit();
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
  const auto nc_path = out_dir / "results.nc";
  write_study_netcdf(nc_path, spec, result, provenance);
  written.push_back(nc_path);

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
