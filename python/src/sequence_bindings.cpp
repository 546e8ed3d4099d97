// The sequence layer in Python: obscura._render_sequence renders a scene over
// a list of times through the library's render_sequence (the call behind
// `obscura render --time`) and returns, per sensor, (time, band, y, x) arrays
// of every image quantity, the target mask and the screening metrics over
// time, with provenance. python/obscura/_dataset.py turns that into an
// xarray.Dataset per sensor (or leaves the dict when xarray is missing).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "long_call.h"
#include "numpy_view.h"
#include "obscura/core/version.h"
#include "obscura/io/provenance.h"
#include "obscura/sequence/sequence_runner.h"
#include "scene_handle.h"
#include "settings_override.h"

namespace obscura::python {
namespace {

// One sensor's images over the frames, frame-major then band: a (time, band,
// y, x) array per quantity, filled as frames complete (without the GIL).
struct SensorSeries {
  int width = 0, height = 0;
  std::vector<Band> bands;
  std::vector<float> radiance, radiance_stderr, transmittance, apparent_temperature;
  void append(const SensorImage& image) {
    for (const BandImage& b : image.bands) {
      radiance.insert(radiance.end(), b.radiance.begin(), b.radiance.end());
      radiance_stderr.insert(radiance_stderr.end(), b.radiance_stderr.begin(),
                             b.radiance_stderr.end());
      transmittance.insert(transmittance.end(), b.transmittance.begin(), b.transmittance.end());
      apparent_temperature.insert(apparent_temperature.end(), b.apparent_temperature.begin(),
                                  b.apparent_temperature.end());
    }
  }
};

struct SequenceRun {
  std::vector<SensorSeries> sensors;
  SequenceResult result;
  std::string method;
  std::uint64_t seed = 0;
  std::vector<std::string> warnings;  // given as Python RuntimeWarnings, GIL held
};

void check_times(const std::vector<double>& times) {
  if (times.empty()) throw InputError("", "times", "must hold at least one time (s)");
  for (std::size_t i = 0; i < times.size(); ++i) {
    check_time(times[i], "times");
    // Screening times interpolate between frames in time order.
    if (i > 0 && !(times[i] > times[i - 1]))
      throw InputError("", "times", "must be strictly increasing (s)");
  }
}

SequenceRun run_sequence(SceneHandle& h, const std::vector<double>& times,
                         const SettingsOverride& o, LongCall& call) {
  std::lock_guard<std::mutex> lock(h.mutex);
  Scene& scene = h.scene;
  ScopedSettings settings(scene, o);
  SequenceRun run;
  run.method = std::string(render_method_name(scene.settings.method));
  run.seed = scene.settings.seed;
  for (const Sensor& s : scene.sensors)
    run.sensors.push_back({s.camera.width(), s.camera.height(), s.bands, {}, {}, {}, {}});
  SequenceOptions options;
  options.progress = [&](const RenderProgress& p) { call.report(p); };
  options.on_frame = [&](const RenderedFrame& frame) {
    for (std::size_t s = 0; s < frame.images.size(); ++s) run.sensors[s].append(frame.images[s]);
  };
  options.on_warning = [&](const std::string& w) { run.warnings.push_back(w); };
  run.result = render_sequence(scene, times, options);
  return run;
}

// A (time, band, y, x) array over `v`, owned by `owner`; None when empty.
py::object cube(const std::vector<float>& v, const SensorSeries& s, std::size_t frames,
                const std::shared_ptr<const SequenceRun>& owner) {
  if (v.empty()) return py::none();
  return read_only_view<float, SequenceRun>(
      v.data(),
      {static_cast<py::ssize_t>(frames), static_cast<py::ssize_t>(s.bands.size()), s.height,
       s.width},
      owner);
}

// The screening metrics of sensor `name` as (time, band) arrays, by field.
py::dict metrics_of(const SequenceResult& r, const std::string& name, std::size_t frames,
                    std::size_t bands) {
  using Field = double (*)(const ScreeningMetrics&);
  const std::vector<std::pair<const char*, Field>> fields = {
      {"target_pixels", [](const ScreeningMetrics& m) { return double(m.target_pixels); }},
      {"background_pixels", [](const ScreeningMetrics& m) { return double(m.background_pixels); }},
      {"transmittance_mean", [](const ScreeningMetrics& m) { return m.transmittance_mean; }},
      {"transmittance_p10", [](const ScreeningMetrics& m) { return m.transmittance_p10; }},
      {"transmittance_p50", [](const ScreeningMetrics& m) { return m.transmittance_p50; }},
      {"transmittance_p90", [](const ScreeningMetrics& m) { return m.transmittance_p90; }},
      {"screened_fraction", [](const ScreeningMetrics& m) { return m.screened_fraction; }},
      {"target_radiance", [](const ScreeningMetrics& m) { return m.target_radiance; }},
      {"background_radiance", [](const ScreeningMetrics& m) { return m.background_radiance; }},
      {"contrast", [](const ScreeningMetrics& m) { return m.contrast; }},
      {"target_apparent_temperature",
       [](const ScreeningMetrics& m) { return m.target_apparent_temperature_k; }},
      {"background_apparent_temperature",
       [](const ScreeningMetrics& m) { return m.background_apparent_temperature_k; }},
      {"delta_t", [](const ScreeningMetrics& m) { return m.delta_t_k; }},
  };
  std::vector<const ScreeningMetrics*> rows;
  for (const ScreeningMetrics& m : r.metrics)
    if (m.sensor == name) rows.push_back(&m);
  // render_sequence measures every band of every frame: frame-major rows.
  if (rows.size() != frames * bands)
    throw Error("internal: " + std::to_string(rows.size()) + " screening rows for sensor " + name +
                ", expected " + std::to_string(frames * bands));
  py::dict out;
  for (const auto& [key, get] : fields) {
    py::array_t<double> a({static_cast<py::ssize_t>(frames), static_cast<py::ssize_t>(bands)});
    double* p = a.mutable_data();
    for (std::size_t i = 0; i < rows.size(); ++i) p[i] = get(*rows[i]);
    out[key] = a;
  }
  return out;
}

py::object optional_value(const std::optional<double>& v) {
  return v ? py::object(py::float_(*v)) : py::object(py::none());
}

py::list screening_summary(const SequenceResult& r) {
  py::list l;
  for (const ScreeningSeries& s : r.series) {
    py::dict d;
    d["sensor"] = s.sensor;
    d["band"] = s.band.name();
    d["target_pixels"] = s.target_pixels;
    d["time_to_screen_s"] = optional_value(s.screening.time_to_screen_s);
    d["screened_from_s"] = optional_value(s.screening.screened_from_s);
    d["screened_until_s"] = optional_value(s.screening.screened_until_s);
    d["screening_duration_s"] = optional_value(s.screening.screening_duration_s);
    d["max_screened_fraction"] = s.max_screened_fraction;
    d["min_transmittance_mean"] = s.min_transmittance_mean;
    d["min_transmittance_mean_time_s"] = s.min_transmittance_mean_time_s;
    l.append(d);
  }
  return l;
}

py::dict sensor_entry(const std::shared_ptr<const SequenceRun>& run, std::size_t s,
                      const std::string& name) {
  const SensorSeries& series = run->sensors[s];
  const std::size_t frames = run->result.times_s.size();
  py::dict d;
  d["width"] = series.width;
  d["height"] = series.height;
  py::list names, lo, hi;
  for (const Band& b : series.bands) {
    names.append(b.name());
    lo.append(b.lo_um());
    hi.append(b.hi_um());
  }
  d["bands"] = names;
  d["band_min_um"] = lo;
  d["band_max_um"] = hi;
  d["radiance"] = cube(series.radiance, series, frames, run);
  d["radiance_stderr"] = cube(series.radiance_stderr, series, frames, run);
  d["transmittance"] = cube(series.transmittance, series, frames, run);
  d["apparent_temperature"] = cube(series.apparent_temperature, series, frames, run);
  d["target_mask"] = py::none();
  d["metrics"] = py::none();
  if (run->result.with_metrics) {
    const TargetMask& mask = run->result.masks[s];
    py::array_t<std::uint8_t> labels({mask.height, mask.width});
    std::uint8_t* p = labels.mutable_data();
    for (std::size_t i = 0; i < mask.labels.size(); ++i)
      p[i] = static_cast<std::uint8_t>(mask.labels[i]);
    d["target_mask"] = labels;
    d["metrics"] = metrics_of(run->result, name, frames, series.bands.size());
  }
  return d;
}

}  // namespace

void bind_sequence(py::module_& m) {
  m.def(
      "_render_sequence",
      [](const std::shared_ptr<SceneHandle>& h, const std::vector<double>& times,
         const std::optional<std::string>& method, std::optional<int> threads,
         std::optional<std::uint64_t> seed, const py::object& progress,
         const std::string& command_line) {
        check_times(times);
        LongCall call(progress, h->scene);
        auto run = std::make_shared<const SequenceRun>(call.run([&] {
          return run_sequence(*h, times, SettingsOverride{method, threads, seed}, call);
        }));
        // What the CLI prints as "obscura: warning: …" (scene/spectral_coverage.h).
        const py::object warn = py::module_::import("warnings").attr("warn");
        for (const std::string& w : run->warnings)
          warn(w, py::reinterpret_borrow<py::object>(PyExc_RuntimeWarning), 2);
        py::dict out;
        out["times_s"] = py::array_t<double>(static_cast<py::ssize_t>(times.size()), times.data());
        out["method"] = run->method;
        out["seed"] = run->seed;
        out["scene"] = json_to_python(h->scene.source);
        out["provenance"] = json_to_python(
            make_provenance(command_line, run->seed, h->scene.input_files).to_json());
        py::dict sensors;
        for (std::size_t s = 0; s < h->scene.sensors.size(); ++s) {
          const std::string& name = h->scene.sensors[s].name;
          sensors[py::str(name)] = sensor_entry(run, s, name);
        }
        out["sensors"] = sensors;
        out["screening"] = screening_summary(run->result);
        out["units"] =
            py::dict(py::arg("radiance") = "W m-2 sr-1", py::arg("radiance_stderr") = "W m-2 sr-1",
                     py::arg("transmittance") = "1", py::arg("apparent_temperature") = "K",
                     py::arg("time") = "s");
        return out;
      },
      py::arg("scene"), py::arg("times"), py::arg("method"), py::arg("threads"), py::arg("seed"),
      py::arg("progress"), py::arg("command_line"));
}

}  // namespace obscura::python
