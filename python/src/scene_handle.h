#pragma once
// What obscura.Scene holds: a loaded scene and a lock. Rendering stages the
// scene at a time and reads its settings, so two Python threads rendering
// the same Scene at once (each with the GIL released) take turns.
#include <pybind11/pybind11.h>

#include <filesystem>
#include <mutex>
#include <optional>

#include "obscura/scene/scene.h"

namespace obscura::python {

struct SceneHandle {
  Scene scene;
  std::mutex mutex;
};

// A JSON document as Python objects (dict, list, str, float, int, bool, None).
pybind11::object json_to_python(const nlohmann::json& value);
// A Python object as JSON, through Python's json module (allow_nan=False:
// NaN is not JSON); TypeError names what json cannot encode.
nlohmann::json python_to_json(const pybind11::handle& value);

// A scene's spectral_nodes_per_band as its file writes it: a count for every
// band, or {"*": count, band: count, …} where bands have their own.
pybind11::object spectral_nodes_object(const RenderSettings& settings);

// A configuration given as a file or as a dict with a file's content (prepare,
// study): the document and the file that names it in errors, whose folder
// relative paths in it resolve against. A dict stands for `path`, else
// `default_name` in the current folder; `path` with a file is an error.
struct JsonArgument {
  std::filesystem::path file;
  nlohmann::json doc;
};
JsonArgument json_argument(const pybind11::object& value,
                           const std::optional<std::filesystem::path>& path,
                           const char* default_name);

}  // namespace obscura::python
