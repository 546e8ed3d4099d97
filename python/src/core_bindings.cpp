// The core layer in Python: obscura.Error and obscura.InputError (the
// library's exceptions, with the CLI's messages), Band, Planck's law, band
// radiance and the apparent temperature.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings.h"
#include "obscura/core/band.h"
#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "obscura/core/version.h"

namespace obscura::python {
namespace {

// A band argument: a Band, or a string as the CLI's --band takes it ("mwir",
// "3:5"); errors name the argument `field`.
Band band_argument(const py::object& band, const std::string& field) {
  if (py::isinstance<Band>(band)) return band.cast<Band>();
  if (py::isinstance<py::str>(band)) return Band::parse(band.cast<std::string>(), field);
  throw InputError("", field, "must be a Band or a band name or \"LO:HI\" in um");
}

void register_errors(py::module_& m) {
  // obscura.Error is a RuntimeError: any failure the caller can report.
  // obscura.InputError (bad input) is also a ValueError and carries the file
  // and field the library names. str(e) is what the CLI prints after
  // "obscura: error: ".
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::object bases = py::make_tuple(error, py::handle(PyExc_ValueError));
  // Owned by the module for the life of the process (never released: the
  // translator may run until the interpreter ends).
  static PyObject* input_error = PyErr_NewException("obscura.InputError", bases.ptr(), nullptr);
  m.attr("InputError") = py::handle(input_error);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::object instance = py::handle(input_error)(e.what());
      instance.attr("file") = e.file();
      instance.attr("field") = e.field();
      instance.attr("detail") = e.detail();
      PyErr_SetObject(input_error, instance.ptr());
    } catch (const Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
}

void bind_band(py::module_& m) {
  py::class_<Band>(m, "Band", "A sensor band: a wavelength interval (um) with a relative response.")
      .def(py::init([](const std::string& text) { return Band::parse(text, "band"); }),
           py::arg("text"), "A preset name (visible, laser1064, mwir, lwir) or \"LO:HI\" in um.")
      .def_static("flat", &Band::flat, py::arg("name"), py::arg("lo_um"), py::arg("hi_um"))
      .def_static(
          "tabulated",
          [](std::string name, const std::vector<std::pair<double, double>>& table) {
            std::vector<ResponsePoint> points;
            for (const auto& [wl, r] : table) points.push_back({wl, r});
            return Band::tabulated(std::move(name), std::move(points));
          },
          py::arg("name"), py::arg("response"),
          "A tabulated response: [(wavelength_um, response), ...], wavelengths increasing.")
      .def_static("preset", &Band::preset, py::arg("name"))
      .def_static("preset_names", &Band::preset_names)
      .def_property_readonly("name", &Band::name)
      .def_property_readonly("lo_um", &Band::lo_um)
      .def_property_readonly("hi_um", &Band::hi_um)
      .def("response", &Band::response, py::arg("wavelength_um"))
      .def("__repr__", [](const Band& b) {
        return "Band('" + b.name() + "', " + std::to_string(b.lo_um()) + "-" +
               std::to_string(b.hi_um()) + " um)";
      });
}

void bind_radiometry(py::module_& m) {
  m.def("planck", py::vectorize(&planck_radiance), py::arg("wavelength_um"),
        py::arg("temperature_k"),
        "Blackbody spectral radiance B_lambda(T), W m-2 sr-1 um-1 (numpy broadcasting).");
  // The accurate quadrature is the one `obscura radiance` uses, so the two
  // print the same numbers.
  m.def(
      "band_radiance",
      [](const py::array_t<double>& temperature_k, const py::object& band) {
        const BandQuadrature q = BandQuadrature::accurate(band_argument(band, "band"));
        return py::vectorize([&q](double t) { return q.blackbody_radiance(t); })(temperature_k);
      },
      py::arg("temperature_k"), py::arg("band"),
      "Blackbody band radiance, W m-2 sr-1: the integral of R(lambda) B_lambda(T).");
  m.def(
      "apparent_temperature",
      [](const py::array_t<double>& band_radiance, const py::object& band) {
        const BandQuadrature q = BandQuadrature::accurate(band_argument(band, "band"));
        return py::vectorize([&q](double l) { return q.apparent_temperature(l); })(band_radiance);
      },
      py::arg("band_radiance"), py::arg("band"),
      "The blackbody temperature (K) with this band radiance (W m-2 sr-1); 0 for <= 0.");
}

}  // namespace

void bind_core(py::module_& m) {
  register_errors(m);
  m.attr("__version__") = kVersion;
  bind_band(m);
  bind_radiometry(m);
}

}  // namespace obscura::python
