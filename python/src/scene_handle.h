#pragma once
// What obscura.Scene holds: a loaded scene and a lock. Rendering stages the
// scene at a time and reads its settings, so two Python threads rendering
// the same Scene at once (each with the GIL released) take turns.
#include <pybind11/pybind11.h>

#include <mutex>

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

}  // namespace obscura::python
