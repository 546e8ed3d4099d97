// The render layer in Python: obscura.render(scene, time=…) renders sensors
// at one time exactly as one frame of `obscura render` does (the same
// staging, integrator and per-sensor loop, so the same seed gives the same
// images bit for bit), and returns each sensor's images as numpy arrays over
// the renderer's own memory (no copy).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.h"
#include "long_call.h"
#include "numpy_view.h"
#include "obscura/gpu/frame_integrator.h"
#include "obscura/render/renderer.h"
#include "scene_handle.h"
#include "settings_override.h"

namespace obscura::python {
namespace {

// One band of a rendered sensor image, as numpy arrays of shape (height, width).
struct BandView {
  std::shared_ptr<const SensorImage> image;
  std::size_t index = 0;
  const BandImage& band() const { return image->bands[index]; }
  py::object plane(const std::vector<float>& v) const {
    if (v.empty()) return py::none();
    return read_only_view<float, SensorImage>(v.data(), {image->height, image->width}, image);
  }
};

py::dict units() {
  py::dict u;
  u["radiance"] = "W m-2 sr-1";
  u["radiance_stderr"] = "W m-2 sr-1";
  u["transmittance"] = "1";
  u["apparent_temperature"] = "K";
  return u;
}

// The indices of the sensors named (all, in scene order, for None).
std::vector<int> sensor_indices(const Scene& scene,
                                const std::optional<std::vector<std::string>>& names) {
  std::vector<int> out;
  if (!names) {
    for (std::size_t i = 0; i < scene.sensors.size(); ++i) out.push_back(static_cast<int>(i));
    return out;
  }
  std::string known;
  for (const Sensor& s : scene.sensors) known += (known.empty() ? "" : ", ") + s.name;
  for (const std::string& name : *names) {
    int found = -1;
    for (std::size_t i = 0; i < scene.sensors.size(); ++i)
      if (scene.sensors[i].name == name) found = static_cast<int>(i);
    if (found < 0)
      throw InputError("", "sensors",
                       "no sensor '" + name + "' in the scene (sensors: " + known + ")");
    out.push_back(found);
  }
  if (out.empty()) throw InputError("", "sensors", "names no sensor (sensors: " + known + ")");
  return out;
}

std::vector<std::shared_ptr<SensorImage>> render_sensors(SceneHandle& h, double time,
                                                         const std::vector<int>& sensors,
                                                         const SettingsOverride& o,
                                                         LongCall& call) {
  std::lock_guard<std::mutex> lock(h.mutex);
  Scene& scene = h.scene;
  ScopedSettings settings(scene, o);
  stage_scene(scene, time);
  // As render_frame (sequence/sequence_runner.h): one integrator prepared for
  // every sensor of the frame, then each sensor through it.
  const FrameSpectra spectra = frame_spectra(scene);
  const std::unique_ptr<Integrator> integrator =
      make_frame_integrator(scene, spectra, single_process(), [&](long long done, long long total) {
        RenderProgress p{0, 1, time, -1, 0, 0};
        p.photons_done = done;
        p.photons_total = total;
        call.report(p);
      });
  std::vector<std::shared_ptr<SensorImage>> images;
  for (int s : sensors) {
    RenderOptions options;
    options.progress = [&](int done, int total) { call.report({0, 1, time, s, done, total}); };
    images.push_back(
        std::make_shared<SensorImage>(render_sensor(scene, s, *integrator, spectra, options)));
  }
  return images;
}

}  // namespace

void bind_render(py::module_& m) {
  py::class_<BandView>(m, "BandImage",
                       "One band of a sensor image; arrays (height, width), float32, top row "
                       "first, read-only views of the rendered image.")
      .def_property_readonly("band", [](const BandView& v) { return v.band().band; })
      .def_property_readonly(
          "radiance", [](const BandView& v) { return v.plane(v.band().radiance); },
          "Band radiance, W m-2 sr-1.")
      .def_property_readonly(
          "radiance_stderr", [](const BandView& v) { return v.plane(v.band().radiance_stderr); },
          "Standard error of the radiance, W m-2 sr-1 (Monte Carlo methods; None otherwise).")
      .def_property_readonly(
          "transmittance", [](const BandView& v) { return v.plane(v.band().transmittance); },
          "Line-of-sight transmittance of the clouds up to the first surface, 1.")
      .def_property_readonly(
          "apparent_temperature",
          [](const BandView& v) { return v.plane(v.band().apparent_temperature); },
          "Blackbody temperature with the pixel's band radiance, K.")
      .def_property_readonly_static("units", [](const py::object&) { return units(); });

  py::class_<SensorImage, std::shared_ptr<SensorImage>>(m, "SensorImage",
                                                        "What a render made for one sensor.")
      .def_readonly("sensor", &SensorImage::sensor)
      .def_readonly("width", &SensorImage::width)
      .def_readonly("height", &SensorImage::height)
      .def_property_readonly(
          "bands",
          [](const std::shared_ptr<SensorImage>& image) {
            py::dict d;
            for (std::size_t i = 0; i < image->bands.size(); ++i)
              d[py::str(image->bands[i].band.name())] = BandView{image, i};
            return d;
          },
          "Band images by band name, in the sensor's order.")
      .def_property_readonly("samples_per_pixel",
                             [](const std::shared_ptr<SensorImage>& image) {
                               return read_only_view<std::uint32_t, SensorImage>(
                                   image->samples_per_pixel.data(), {image->height, image->width},
                                   image);
                             })
      .def_property_readonly("seconds", [](const SensorImage& i) { return i.stats.seconds; })
      .def_property_readonly("rays", [](const SensorImage& i) { return i.stats.rays; });

  m.def(
      "render",
      [](const std::shared_ptr<SceneHandle>& h, double time,
         const std::optional<std::vector<std::string>>& sensors,
         const std::optional<std::string>& method, std::optional<int> threads,
         std::optional<std::uint64_t> seed, const py::object& progress) {
        check_time(time, "time");
        const std::vector<int> indices = sensor_indices(h->scene, sensors);
        LongCall call(progress, h->scene);
        const auto images = call.run([&] {
          return render_sensors(*h, time, indices, SettingsOverride{method, threads, seed}, call);
        });
        py::dict out;
        for (const auto& image : images) out[py::str(image->sensor)] = image;
        return out;
      },
      py::arg("scene"), py::kw_only(), py::arg("time") = 0.0, py::arg("sensors") = py::none(),
      py::arg("method") = py::none(), py::arg("threads") = py::none(), py::arg("seed") = py::none(),
      py::arg("progress") = py::none(),
      "Renders the scene at `time` (s): {sensor name: SensorImage}. method, threads and seed "
      "override the scene's settings for this call; progress(dict) is called as rows complete. "
      "Images are bit-identical to `obscura render --at TIME` for the same seed, at any thread "
      "count. Ctrl-C stops the render at the next row (KeyboardInterrupt).");
}

}  // namespace obscura::python
