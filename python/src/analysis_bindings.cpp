// The analysis layer in Python: screening metrics (docs/metrics.md) of
// images given as arrays, through the library's screening_metrics and
// summarize_screening, as metrics.json's "frames" and "series" (the figures
// of metrics.csv and summary.json). python/obscura/__init__.py turns a
// render or render_sequence result into these arrays; _scene_screening gives
// what a scene decides (target masks, bands, metrics settings).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bindings.h"
#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/report/screening_output.h"
#include "scene_handle.h"

namespace obscura::python {
namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// One frame of one sensor: its images as (band, y, x) arrays and its target.
struct FrameInput {
  double time_s = 0;
  std::string sensor;
  std::vector<Band> bands;
  FloatArray transmittance;
  std::optional<FloatArray> radiance;
  py::array target;  // (y, x): nonzero where the target is (1 in a scene's mask)
};

// A (band, y, x) array of `n` bands, named `field` in errors.
void check_cube(const FloatArray& a, std::size_t n, const std::string& field) {
  if (a.ndim() != 3 || static_cast<std::size_t>(a.shape(0)) != n)
    throw InputError("", field,
                     "expected an array of shape (band, y, x) with " + std::to_string(n) +
                         " bands, got " + std::to_string(a.ndim()) + " dimensions");
}

SensorImage sensor_image(const FrameInput& in) {
  const std::size_t n = in.bands.size();
  check_cube(in.transmittance, n, "transmittance");
  SensorImage image;
  image.sensor = in.sensor;
  image.height = static_cast<int>(in.transmittance.shape(1));
  image.width = static_cast<int>(in.transmittance.shape(2));
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  if (in.radiance) {
    check_cube(*in.radiance, n, "radiance");
    if (in.radiance->shape(1) != image.height || in.radiance->shape(2) != image.width)
      throw InputError("", "radiance", "must have the shape of transmittance");
  }
  for (std::size_t b = 0; b < n; ++b) {
    BandImage band;
    band.band = in.bands[b];
    const float* t = in.transmittance.data() + b * pixels;
    band.transmittance.assign(t, t + pixels);
    if (in.radiance) {
      const float* l = in.radiance->data() + b * pixels;
      band.radiance.assign(l, l + pixels);
    } else {
      band.radiance.assign(pixels, 0.0f);  // the radiance figures are NaN below
    }
    image.bands.push_back(std::move(band));
  }
  return image;
}

TargetMask target_mask(const FrameInput& in, const SensorImage& image, int margin) {
  const auto target = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(
      in.target.attr("astype")("bool"));
  if (!target || target.ndim() != 2 || target.shape(0) != image.height ||
      target.shape(1) != image.width)
    throw InputError("", "target",
                     "expected a (y, x) array of the images' size " + std::to_string(image.height) +
                         "x" + std::to_string(image.width) + ", nonzero or True on the target");
  TargetMask mask;
  mask.sensor = in.sensor;
  mask.width = image.width;
  mask.height = image.height;
  const std::uint8_t* p = target.data();
  for (py::ssize_t i = 0; i < target.size(); ++i)
    mask.labels.push_back(p[i] ? MaskLabel::kTarget : MaskLabel::kOther);
  finish_target_mask(mask, margin);
  return mask;
}

// Without radiances only the transmittance figures are defined.
void drop_radiance_figures(std::vector<ScreeningMetrics>& rows) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (ScreeningMetrics& m : rows)
    m.target_radiance = m.background_radiance = m.contrast = m.target_apparent_temperature_k =
        m.background_apparent_temperature_k = m.delta_t_k = kNaN;
}

// spectral_nodes_per_band as Python gives it: a count for every band, or
// {band: count, "*": count for the others} (the scene file's forms), range-
// checked by the library's one check of the render settings.
RenderSettings spectral_nodes_from(const py::object& value) {
  RenderSettings render;
  if (py::isinstance<py::dict>(value)) {
    for (const auto& [key, n] : value.cast<py::dict>()) {
      const std::string band = key.cast<std::string>();
      if (band == "*")
        render.spectral_nodes_per_band = n.cast<int>();
      else
        render.spectral_nodes_by_band[band] = n.cast<int>();
    }
  } else {
    render.spectral_nodes_per_band = value.cast<int>();
  }
  check_render_settings(render, [](std::string_view key, std::string_view what) {
    return InputError("", std::string(key), std::string(what));
  });
  return render;
}

py::object screening(const std::vector<FrameInput>& frames, const MetricsSettings& settings,
                     const RenderSettings& nodes, double reference_time_s) {
  std::vector<ScreeningMetrics> rows;
  std::vector<TargetMask> masks;
  for (const FrameInput& in : frames) {
    const SensorImage image = sensor_image(in);
    TargetMask mask = target_mask(in, image, settings.background_margin_px);
    std::vector<ScreeningMetrics> r = screening_metrics(image, mask, settings, nodes, in.time_s);
    if (!in.radiance) drop_radiance_figures(r);
    rows.insert(rows.end(), r.begin(), r.end());
    bool seen = false;
    for (const TargetMask& m : masks) seen = seen || m.sensor == mask.sensor;
    if (!seen) masks.push_back(std::move(mask));
  }
  const std::vector<ScreeningSeries> series = summarize_screening(rows, settings, reference_time_s);
  nlohmann::json doc =
      screening_metrics_json(nullptr, settings, reference_time_s, masks, rows, series);
  doc.erase("provenance");
  return json_to_python(doc);
}

}  // namespace

void bind_analysis(py::module_& m) {
  m.def(
      "_screening_metrics",
      [](const py::list& inputs, double threshold, double fraction, int margin,
         const py::object& nodes, double reference_time_s) {
        MetricsSettings settings;
        settings.transmittance_threshold = threshold;
        settings.screened_fraction = fraction;
        settings.background_margin_px = margin;
        if (!(threshold >= 0 && threshold <= 1))
          throw InputError("", "transmittance_threshold", "must lie in [0, 1]");
        if (!(fraction > 0 && fraction <= 1))
          throw InputError("", "screened_fraction", "must lie in (0, 1]");
        if (margin < 0) throw InputError("", "background_margin_px", "must be >= 0");
        const RenderSettings render = spectral_nodes_from(nodes);
        std::vector<FrameInput> frames;
        for (const py::handle& h : inputs) {
          const py::dict d = py::reinterpret_borrow<py::dict>(h);
          FrameInput in;
          in.time_s = d["time_s"].cast<double>();
          in.sensor = d["sensor"].cast<std::string>();
          in.bands = d["bands"].cast<std::vector<Band>>();
          in.transmittance = FloatArray::ensure(d["transmittance"]);
          if (!in.transmittance) throw InputError("", "transmittance", "expected a float array");
          if (!d["radiance"].is_none()) {
            in.radiance = FloatArray::ensure(d["radiance"]);
            if (!*in.radiance) throw InputError("", "radiance", "expected a float array");
          }
          in.target = py::array::ensure(d["target"]);
          if (!in.target) throw InputError("", "target", "expected an array");
          frames.push_back(std::move(in));
        }
        return screening(frames, settings, render, reference_time_s);
      },
      py::arg("inputs"), py::arg("transmittance_threshold"), py::arg("screened_fraction"),
      py::arg("background_margin_px"), py::arg("spectral_nodes_per_band"),
      py::arg("reference_time_s"));

  m.def(
      "_scene_screening",
      [](const std::shared_ptr<SceneHandle>& h) {
        std::lock_guard<std::mutex> lock(h->mutex);
        const Scene& scene = h->scene;
        py::dict d;
        d["transmittance_threshold"] = scene.metrics.transmittance_threshold;
        d["screened_fraction"] = scene.metrics.screened_fraction;
        d["background_margin_px"] = scene.metrics.background_margin_px;
        d["spectral_nodes_per_band"] = spectral_nodes_object(scene.settings);
        d["reference_time_s"] = screening_reference_time_s(scene);
        py::dict targets, bands;
        for (const Sensor& s : scene.sensors) {
          TargetMask mask;
          {
            py::gil_scoped_release release;  // rays through every pixel
            mask = compute_target_mask(scene, s, scene.metrics.background_margin_px);
          }
          py::array_t<std::uint8_t> labels({mask.height, mask.width});
          for (std::size_t i = 0; i < mask.labels.size(); ++i)
            labels.mutable_data()[i] = mask.labels[i] == MaskLabel::kTarget ? 1 : 0;
          targets[py::str(s.name)] = labels;
          bands[py::str(s.name)] = py::cast(s.bands);
        }
        d["targets"] = targets;
        d["bands"] = bands;
        return d;
      },
      py::arg("scene"));
}

}  // namespace obscura::python
