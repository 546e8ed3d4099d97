#pragma once
// The Python module `obscura` is organised like the library: one binding
// file per layer (docs/conventions.md §15), each adding its names to the
// extension module `obscura._obscura` that python/obscura/__init__.py
// re-exports. The bindings are thin: every check and every message is the
// library's, so Python and the CLI fail on the same input with the same words.
#include <pybind11/pybind11.h>

namespace obscura::python {

namespace py = pybind11;

void bind_core(py::module_& m);        // errors, bands, Planck, apparent temperature
void bind_medium(py::module_& m);      // VoxelGrid from numpy arrays
void bind_io(py::module_& m);          // keyframe writing, EXR reading
void bind_optics(py::module_& m);      // Mie efficiencies, a material's coefficients
void bind_scene(py::module_& m);       // Scene: load, from_dict, what it holds
void bind_render(py::module_& m);      // render at one time → numpy images
void bind_analysis(py::module_& m);    // screening metrics of images as arrays
void bind_validation(py::module_& m);  // the canonical cases with known answers
void bind_prep(py::module_& m);        // prepare: concentrations → cloud keyframes
void bind_sequence(py::module_& m);    // render over times → arrays and metrics
void bind_study(py::module_& m);       // parameter studies

}  // namespace obscura::python
