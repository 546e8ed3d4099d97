#include "obscura/report/netcdf_render_output.h"

#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <numeric>

#include "obscura/core/check.h"
#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/core/version.h"
#include "obscura/report/screening_output.h"

namespace obscura {
namespace {

using Slab = std::vector<std::size_t>;

// One image quantity of every band: (time, band_S, y_S, x_S) float.
struct ImageQuantity {
  const char* name;
  const char* units;
  const char* long_name;
  const char* standard_name;  // nullptr: CF has none
};
constexpr ImageQuantity kRadiance = {"radiance", "W m-2 sr-1", "band radiance at the sensor",
                                     nullptr};
constexpr ImageQuantity kRadianceStderr = {
    "radiance_stderr", "W m-2 sr-1", "standard error of the band radiance (Monte Carlo)", nullptr};
constexpr ImageQuantity kTransmittance = {
    "transmittance", "1", "line-of-sight transmittance of the clouds to the first surface",
    nullptr};
constexpr ImageQuantity kApparentTemperature = {"apparent_temperature", "K",
                                                "blackbody temperature with the band radiance",
                                                "brightness_temperature"};

// One screening metric (analysis/screening_metrics.h): (time, band_S).
struct Metric {
  const char* name;
  const char* units;
  const char* long_name;
  bool count;  // int (pixel counts), else double
  double (*value)(const ScreeningMetrics&);
};
const Metric kMetrics[] = {
    {"target_pixels", "1", "target pixels", true,
     [](const ScreeningMetrics& m) { return double(m.target_pixels); }},
    {"background_pixels", "1", "background pixels around the target", true,
     [](const ScreeningMetrics& m) { return double(m.background_pixels); }},
    {"transmittance_mean", "1", "mean line-of-sight transmittance over the target", false,
     [](const ScreeningMetrics& m) { return m.transmittance_mean; }},
    {"transmittance_p10", "1", "10th percentile of the target's transmittance", false,
     [](const ScreeningMetrics& m) { return m.transmittance_p10; }},
    {"transmittance_p50", "1", "median of the target's transmittance", false,
     [](const ScreeningMetrics& m) { return m.transmittance_p50; }},
    {"transmittance_p90", "1", "90th percentile of the target's transmittance", false,
     [](const ScreeningMetrics& m) { return m.transmittance_p90; }},
    {"screened_fraction", "1", "fraction of target pixels below the screening threshold", false,
     [](const ScreeningMetrics& m) { return m.screened_fraction; }},
    {"target_radiance", "W m-2 sr-1", "mean band radiance of the target", false,
     [](const ScreeningMetrics& m) { return m.target_radiance; }},
    {"background_radiance", "W m-2 sr-1", "mean band radiance of the background", false,
     [](const ScreeningMetrics& m) { return m.background_radiance; }},
    {"contrast", "1", "Weber contrast of target against background", false,
     [](const ScreeningMetrics& m) { return m.contrast; }},
    {"target_apparent_temperature", "K", "apparent temperature of the target's mean radiance",
     false, [](const ScreeningMetrics& m) { return m.target_apparent_temperature_k; }},
    {"background_apparent_temperature", "K",
     "apparent temperature of the background's mean radiance", false,
     [](const ScreeningMetrics& m) { return m.background_apparent_temperature_k; }},
    {"delta_t", "K", "apparent temperature difference, target minus background", false,
     [](const ScreeningMetrics& m) { return m.delta_t_k; }},
};

// Every name a sensor's dimensions and variables take, before the suffix.
std::vector<std::string> sensor_name_prefixes() {
  std::vector<std::string> p = {"band",           "y",          "x", "band_min_um", "band_max_um",
                                "band_centre_um", "target_mask"};
  for (const ImageQuantity* q :
       {&kRadiance, &kRadianceStderr, &kTransmittance, &kApparentTemperature})
    p.push_back(q->name);
  for (const Metric& m : kMetrics) p.push_back(m.name);
  return p;
}

std::string scene_file(const Scene& scene) {
  return scene.input_files.empty() ? std::string() : scene.input_files.front().string();
}

}  // namespace

struct NetcdfRenderOutput::SensorVariables {
  std::string name, suffix;
  int width = 0, height = 0;
  std::vector<Band> bands;
  int band_dim = -1, y_dim = -1, x_dim = -1;
  int band = -1, band_min = -1, band_max = -1, band_centre = -1, y = -1, x = -1;
  int radiance = -1, radiance_stderr = -1, transmittance = -1, apparent_temperature = -1;
  std::string coordinates;  // the auxiliary band coordinates, for "coordinates" attributes
};

std::string netcdf_sensor_suffix(const std::string& sensor_name) {
  std::string s = sensor_name;
  for (char& c : s)
    if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
      c = '_';
  return s;
}

NetcdfRenderOutput::NetcdfRenderOutput(const std::filesystem::path& path, const Scene& scene,
                                       std::vector<double> times_s, const Provenance& provenance,
                                       const std::string& title)
    : path_(path), scene_(scene), times_s_(std::move(times_s)) {
  // Checks before the file is made: no name taken by two sensors (the same
  // suffix, or e.g. sensors "a" and "min_um_a" both making band_min_um_a),
  // and memory for writing one image (HDF5 compresses a chunk, one image,
  // through two buffers of its size: the shuffled and the deflated copy).
  std::map<std::string, std::string> names;  // dimension or variable → sensor
  const std::vector<std::string> prefixes = sensor_name_prefixes();
  std::uint64_t largest_image = 0;
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) {
    const Sensor& sensor = scene.sensors[i];
    const std::string suffix = netcdf_sensor_suffix(sensor.name);
    for (const std::string& prefix : prefixes) {
      const auto [it, fresh] = names.emplace(prefix + "_" + suffix, sensor.name);
      if (!fresh)
        throw InputError(scene_file(scene), fmt::format("/sensors/{}/name", i),
                         fmt::format("sensors '{}' and '{}' would both name a variable {} in {}: "
                                     "rename one",
                                     it->second, sensor.name, it->first, kNetcdfRenderFile));
    }
    largest_image = std::max<std::uint64_t>(
        largest_image, static_cast<std::uint64_t>(sensor.camera.width()) * sensor.camera.height());
  }
  check_memory(largest_image * sizeof(float) * 2, path.string(), "",
               "compressing an image into the NetCDF file");

  file_ = std::make_unique<NetcdfOutputFile>(path);
  NetcdfOutputFile& f = *file_;
  time_dim_ = f.define_dimension("time", NetcdfOutputFile::kUnlimited);
  time_var_ = f.define_variable("time", NcType::kDouble, {time_dim_});
  f.put_attribute(time_var_, "standard_name", "time");
  f.put_attribute(time_var_, "long_name", "scene time");
  f.put_attribute(time_var_, "units", "s");
  f.put_attribute(time_var_, "axis", "T");

  const int g = NetcdfOutputFile::kGlobal;
  f.put_attribute(g, "Conventions", "CF-1.10");
  f.put_attribute(g, "title", "obscura render of " + title);
  f.put_attribute(g, "source", fmt::format("obscura {}", kVersion));
  f.put_attribute(g, "history", provenance.created_utc + ": " + provenance.command_line);
  f.put_attribute(g, "comment",
                  "Each sensor S has its own dimensions band_S, y_S, x_S and variables "
                  "<quantity>_S; S is the sensor's name with characters other than letters, "
                  "digits and '_' replaced by '_' (global attribute sensors). Pixel (x, y) is "
                  "column x from the left, row y from the top.");
  f.put_attribute(g, "method", render_method_name(scene.settings.method));
  f.put_attribute(g, "seed", static_cast<std::uint64_t>(scene.settings.seed));
  f.put_attribute(g, "frames_planned", std::vector<int>{static_cast<int>(times_s_.size())});
  f.put_attribute(g, "provenance", provenance.to_string());
  f.put_attribute(g, "scene", scene.source.dump());
  nlohmann::json sensors = nlohmann::json::array();
  for (const Sensor& s : scene.sensors)
    sensors.push_back({{"name", s.name}, {"suffix", netcdf_sensor_suffix(s.name)}});
  f.put_attribute(g, "sensors", sensors.dump());

  sensors_.resize(scene.sensors.size());
  for (std::size_t i = 0; i < scene.sensors.size(); ++i) define_sensor(i, scene.sensors[i]);
  f.end_definitions();

  // The coordinates that do not change: bands and pixel indices.
  for (const SensorVariables& s : sensors_) {
    std::vector<std::string> band_names;
    std::vector<double> lo, hi, centre;
    for (const Band& b : s.bands) {
      band_names.push_back(b.name());
      lo.push_back(b.lo_um());
      hi.push_back(b.hi_um());
      centre.push_back(0.5 * (b.lo_um() + b.hi_um()));
    }
    const Slab start{0}, count{s.bands.size()};
    f.put(s.band, start, count, band_names);
    f.put(s.band_min, start, count, lo.data());
    f.put(s.band_max, start, count, hi.data());
    f.put(s.band_centre, start, count, centre.data());
    std::vector<int> rows(static_cast<std::size_t>(s.height));
    std::vector<int> columns(static_cast<std::size_t>(s.width));
    std::iota(rows.begin(), rows.end(), 0);
    std::iota(columns.begin(), columns.end(), 0);
    f.put(s.y, start, {rows.size()}, rows.data());
    f.put(s.x, start, {columns.size()}, columns.data());
  }
}

NetcdfRenderOutput::~NetcdfRenderOutput() = default;

void NetcdfRenderOutput::define_sensor(std::size_t index, const Sensor& sensor) {
  NetcdfOutputFile& f = *file_;
  SensorVariables& s = sensors_[index];
  s.name = sensor.name;
  s.suffix = netcdf_sensor_suffix(sensor.name);
  s.width = sensor.camera.width();
  s.height = sensor.camera.height();
  s.bands = sensor.bands;
  const std::string u = "_" + s.suffix;
  s.band_dim = f.define_dimension("band" + u, s.bands.size());
  s.y_dim = f.define_dimension("y" + u, static_cast<std::size_t>(s.height));
  s.x_dim = f.define_dimension("x" + u, static_cast<std::size_t>(s.width));

  // The band coordinate holds the band names (string labels, as in
  // obscura.render_sequence's Datasets), so that a band is picked by name.
  s.band = f.define_variable("band" + u, NcType::kString, {s.band_dim});
  f.put_attribute(s.band, "long_name", "sensor band of " + sensor.name);
  const auto limit = [&](const std::string& name, const char* long_name,
                         const char* standard_name) {
    const int id = f.define_variable(name + u, NcType::kDouble, {s.band_dim});
    f.put_attribute(id, "units", "um");
    f.put_attribute(id, "long_name", long_name);
    if (standard_name != nullptr) f.put_attribute(id, "standard_name", standard_name);
    return id;
  };
  s.band_min = limit("band_min_um", "band lower limit", nullptr);
  s.band_max = limit("band_max_um", "band upper limit", nullptr);
  s.band_centre = limit("band_centre_um", "band centre (midpoint of the limits)",
                        "sensor_band_central_radiation_wavelength");
  s.coordinates = fmt::format("band_min_um{0} band_max_um{0} band_centre_um{0}", u);
  s.y = f.define_variable("y" + u, NcType::kInt, {s.y_dim});
  f.put_attribute(s.y, "long_name", "image row, top first");
  s.x = f.define_variable("x" + u, NcType::kInt, {s.x_dim});
  f.put_attribute(s.x, "long_name", "image column, left first");

  // One chunk per frame, band and image: what a frame writes at once and
  // what a reader of one image reads.
  const std::vector<std::size_t> chunk{1, 1, static_cast<std::size_t>(s.height),
                                       static_cast<std::size_t>(s.width)};
  const auto image = [&](const ImageQuantity& q) {
    const int id = f.define_variable(q.name + u, NcType::kFloat,
                                     {time_dim_, s.band_dim, s.y_dim, s.x_dim}, chunk, true);
    f.put_attribute(id, "units", q.units);
    f.put_attribute(id, "long_name", q.long_name);
    if (q.standard_name != nullptr) f.put_attribute(id, "standard_name", q.standard_name);
    f.put_attribute(id, "coordinates", s.coordinates);
    f.put_attribute(id, "sensor", sensor.name);
    return id;
  };
  s.radiance = image(kRadiance);
  if (method_is_monte_carlo(scene_.settings.method)) s.radiance_stderr = image(kRadianceStderr);
  s.transmittance = image(kTransmittance);
  s.apparent_temperature = image(kApparentTemperature);
  if (s.radiance_stderr >= 0)
    f.put_attribute(s.radiance, "ancillary_variables", "radiance_stderr" + u);
}

void NetcdfRenderOutput::write_frame(const RenderedFrame& frame) {
  OBSCURA_CHECK(frame.index < times_s_.size());
  OBSCURA_CHECK(frame.images.size() == sensors_.size());
  NetcdfOutputFile& f = *file_;
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const SensorVariables& s = sensors_[i];
    const SensorImage& image = frame.images[i];
    OBSCURA_CHECK(image.sensor == s.name && image.width == s.width && image.height == s.height &&
                  image.bands.size() == s.bands.size());
    const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
    for (std::size_t b = 0; b < s.bands.size(); ++b) {
      const BandImage& band = image.bands[b];
      const Slab start{frame.index, b, 0, 0};
      const Slab count{1, 1, static_cast<std::size_t>(s.height), static_cast<std::size_t>(s.width)};
      OBSCURA_CHECK(band.radiance.size() == pixels && band.transmittance.size() == pixels &&
                    band.apparent_temperature.size() == pixels);
      f.put(s.radiance, start, count, band.radiance.data());
      f.put(s.transmittance, start, count, band.transmittance.data());
      f.put(s.apparent_temperature, start, count, band.apparent_temperature.data());
      if (s.radiance_stderr >= 0) {
        OBSCURA_CHECK(band.radiance_stderr.size() == pixels);
        f.put(s.radiance_stderr, start, count, band.radiance_stderr.data());
      }
    }
  }
  // The frame's time last: a record with its time is a complete frame.
  f.put(time_var_, {frame.index}, {1}, &times_s_[frame.index]);
  OBSCURA_CHECK(frame.time_s == times_s_[frame.index]);
  frames_written_.push_back(frame.index);
}

void NetcdfRenderOutput::write_metrics(const SequenceResult& result) {
  NetcdfOutputFile& f = *file_;
  const std::size_t frames = frames_written_.size();
  f.put_attribute(
      NetcdfOutputFile::kGlobal, "screening",
      nlohmann::json{{"settings", screening_settings_json(scene_.metrics, result.reference_time_s)},
                     {"series", screening_series_json(result.series)}}
          .dump());
  struct Defined {
    int mask = -1;
    std::vector<int> metrics;
  };
  std::vector<Defined> defined(sensors_.size());
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const SensorVariables& s = sensors_[i];
    const std::string u = "_" + s.suffix;
    Defined& d = defined[i];
    d.mask = f.define_variable("target_mask" + u, NcType::kUByte, {s.y_dim, s.x_dim});
    f.put_attribute(d.mask, "long_name", "target mask of " + s.name);
    f.put_attribute(d.mask, "flag_values", std::vector<std::uint8_t>{0, 1, 2});
    f.put_attribute(d.mask, "flag_meanings", "other target background");
    f.put_attribute(d.mask, "sensor", s.name);
    for (const Metric& m : kMetrics) {
      const int id = f.define_variable(m.name + u, m.count ? NcType::kInt : NcType::kDouble,
                                       {time_dim_, s.band_dim});
      f.put_attribute(id, "units", m.units);
      f.put_attribute(id, "long_name", m.long_name);
      f.put_attribute(id, "coordinates", s.coordinates);
      f.put_attribute(id, "sensor", s.name);
      if (std::string_view(m.name) == "screened_fraction") {
        f.put_attribute(id, "transmittance_threshold",
                        std::vector<double>{scene_.metrics.transmittance_threshold});
        f.put_attribute(id, "screened_fraction_criterion",
                        std::vector<double>{scene_.metrics.screened_fraction});
      }
      d.metrics.push_back(id);
    }
  }
  f.end_definitions();

  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const SensorVariables& s = sensors_[i];
    const TargetMask& mask = result.masks.at(i);
    OBSCURA_CHECK(mask.sensor == s.name && mask.width == s.width && mask.height == s.height);
    const std::size_t pixels = static_cast<std::size_t>(s.width) * s.height;
    check_memory(pixels, path_.string(), "target_mask_" + s.suffix,
                 "the target mask for the NetCDF file");
    std::vector<std::uint8_t> labels(pixels);
    for (std::size_t p = 0; p < pixels; ++p) labels[p] = static_cast<std::uint8_t>(mask.labels[p]);
    f.put(defined[i].mask, {0, 0},
          {static_cast<std::size_t>(s.height), static_cast<std::size_t>(s.width)}, labels.data());

    // The sensor's rows, frame-major then band (render_sequence's order).
    std::vector<const ScreeningMetrics*> rows;
    for (const ScreeningMetrics& m : result.metrics)
      if (m.sensor == s.name) rows.push_back(&m);
    const std::size_t bands = s.bands.size();
    OBSCURA_CHECK(rows.size() == frames * bands);
    check_memory(rows.size() * sizeof(double), path_.string(), "", "screening metrics");
    for (std::size_t r = 0; r < rows.size(); ++r)
      OBSCURA_CHECK(rows[r]->time_s == times_s_[r / bands] &&
                    rows[r]->band.name() == s.bands[r % bands].name());
    for (std::size_t k = 0; k < std::size(kMetrics); ++k) {
      std::vector<double> values(rows.size());
      for (std::size_t r = 0; r < rows.size(); ++r) values[r] = kMetrics[k].value(*rows[r]);
      const Slab start{0, 0}, count{frames, bands};
      if (kMetrics[k].count) {
        std::vector<int> counts(values.begin(), values.end());
        f.put(defined[i].metrics[k], start, count, counts.data());
      } else {
        f.put(defined[i].metrics[k], start, count, values.data());
      }
    }
  }
}

void NetcdfRenderOutput::finish(const SequenceResult& result) {
  OBSCURA_CHECK(result.times_s.size() == frames_written_.size());
  file_->redefine();
  file_->put_attribute(NetcdfOutputFile::kGlobal, "run_status", "complete");
  if (result.with_metrics)
    write_metrics(result);
  else
    file_->end_definitions();
  file_->commit();
}

bool NetcdfRenderOutput::finish_failed(const std::string& error) noexcept {
  try {
    // Kept only if its records are exactly frames 0 … k−1, each written whole.
    std::vector<std::size_t> done = frames_written_;
    std::sort(done.begin(), done.end());
    bool whole = !done.empty() && file_->dimension_length(time_dim_) == done.size();
    for (std::size_t k = 0; whole && k < done.size(); ++k) whole = done[k] == k;
    if (whole) {
      file_->redefine();
      const int g = NetcdfOutputFile::kGlobal;
      file_->put_attribute(g, "run_status", "failed");
      file_->put_attribute(g, "run_error", error);
      file_->put_attribute(g, "frames_completed", std::vector<int>{static_cast<int>(done.size())});
      file_->end_definitions();
      file_->commit();
      return true;
    }
  } catch (...) {
    // Finishing failed too: the file is not kept (below).
  }
  try {
    file_.reset();  // closes and removes the temporary
  } catch (...) {
  }
  return false;
}

}  // namespace obscura
