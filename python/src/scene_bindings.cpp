// The scene layer in Python: obscura.Scene, loaded from a file or built from
// a dict through the same loader (so the same validation and messages), and
// what it holds (sensors, bands, settings, the document as read).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <memory>
#include <string>

#include "bindings.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/io/json_reader.h"
#include "obscura/scene/render_settings.h"
#include "scene_handle.h"

namespace obscura::python {

py::object json_to_python(const nlohmann::json& value) {
  return py::module_::import("json").attr("loads")(value.dump());
}

nlohmann::json python_to_json(const py::handle& value) {
  const std::string text = py::module_::import("json")
                               .attr("dumps")(value, py::arg("allow_nan") = false)
                               .cast<std::string>();
  return nlohmann::json::parse(text);
}

JsonArgument json_argument(const py::object& value,
                           const std::optional<std::filesystem::path>& path,
                           const char* default_name) {
  if (py::isinstance<py::dict>(value)) return {path.value_or(default_name), python_to_json(value)};
  if (path) throw InputError("", "path", "names the file a dict stands for; give a dict with it");
  const auto file = value.cast<std::filesystem::path>();
  return {file, read_json_file(file.string())};
}

namespace {

py::dict sensor_dict(const Sensor& s) {
  py::dict d;
  d["name"] = s.name;
  d["width"] = s.camera.width();
  d["height"] = s.camera.height();
  py::list bands;
  for (const Band& b : s.bands) bands.append(py::cast(b));
  d["bands"] = bands;
  return d;
}

py::dict settings_dict(const RenderSettings& r) {
  py::dict d;
  d["method"] = std::string(render_method_name(r.method));
  d["samples_per_pixel"] = r.samples_per_pixel;
  d["adaptive_threshold"] = r.adaptive_threshold;
  d["target_relative_stderr"] = r.target_relative_stderr;
  d["max_samples_per_pixel"] = r.max_samples_per_pixel;
  d["spectral_nodes_per_band"] = spectral_nodes_object(r);
  d["relative_tolerance"] = r.relative_tolerance;
  d["camera_sees_sun"] = r.camera_sees_sun;
  d["seed"] = r.seed;
  d["threads"] = r.threads;
  return d;
}

}  // namespace

py::object spectral_nodes_object(const RenderSettings& settings) {
  if (settings.spectral_nodes_by_band.empty()) return py::int_(settings.spectral_nodes_per_band);
  py::dict nodes;
  nodes["*"] = settings.spectral_nodes_per_band;
  for (const auto& [band, n] : settings.spectral_nodes_by_band) nodes[band.c_str()] = n;
  return std::move(nodes);
}

void bind_scene(py::module_& m) {
  py::class_<SceneHandle, std::shared_ptr<SceneHandle>>(
      m, "Scene", "A scene (docs/formats.md): sensors, clouds, surfaces, sky, render settings.")
      .def_static(
          "load",
          [](const std::filesystem::path& path) {
            auto h = std::make_shared<SceneHandle>();
            h->scene = load_scene(path);
            return h;
          },
          py::arg("path"),
          "Loads and validates a scene file, as `obscura render` does (same errors).")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::filesystem::path& path) {
            const nlohmann::json doc = python_to_json(d);
            auto h = std::make_shared<SceneHandle>();
            h->scene = parse_scene(doc, path);
            return h;
          },
          py::arg("d"), py::arg("path") = std::filesystem::path("scene.json"),
          "A scene from a dict with a scene file's content. `path` stands for the file: "
          "errors name it and relative paths in the scene are relative to its folder.")
      .def_property_readonly(
          "sensors",
          [](const SceneHandle& h) {
            py::list l;
            for (const Sensor& s : h.scene.sensors) l.append(sensor_dict(s));
            return l;
          },
          "Each sensor: name, width and height (px), bands.")
      .def_property_readonly(
          "bands",
          [](const SceneHandle& h) {
            py::dict d;
            for (const Sensor& s : h.scene.sensors) {
              py::list l;
              for (const Band& b : s.bands) l.append(py::cast(b));
              d[py::str(s.name)] = l;
            }
            return d;
          },
          "The bands of each sensor, by sensor name.")
      .def_property_readonly(
          "settings", [](const SceneHandle& h) { return settings_dict(h.scene.settings); },
          "The render settings the scene resolved to (defaults filled in).")
      .def_property_readonly(
          "has_target", [](const SceneHandle& h) { return scene_has_target(h.scene); },
          "Whether a surface is marked as the target (screening metrics are measured).")
      .def_property_readonly(
          "input_files", [](const SceneHandle& h) { return h.scene.input_files; },
          "The scene file and the files it references.")
      .def(
          "to_dict", [](const SceneHandle& h) { return json_to_python(h.scene.source); },
          "The scene document as read (a copy: editing it does not change the scene; "
          "Scene.from_dict makes a new scene from an edited copy).");
}

}  // namespace obscura::python
