// The extension module obscura._obscura: each layer's bindings, bottom to
// top, so that a layer's types exist before the layers above use them.
#include "bindings.h"

PYBIND11_MODULE(_obscura, m) {
  m.doc() = "obscura: radiative transfer through obscurant clouds (docs/python.md)";
  obscura::python::bind_core(m);
  obscura::python::bind_medium(m);
  obscura::python::bind_io(m);
  obscura::python::bind_optics(m);
  obscura::python::bind_scene(m);
  obscura::python::bind_render(m);
  obscura::python::bind_analysis(m);
  obscura::python::bind_validation(m);
  obscura::python::bind_prep(m);
  obscura::python::bind_sequence(m);
  obscura::python::bind_study(m);
}
