// The optics layer in Python: Lorenz–Mie efficiencies of a sphere, as
// `obscura mie` prints them (docs/optics.md), and a material's bulk
// coefficients from the materials database, as `obscura optics` prints them
// (docs/materials.md).
#include <fmt/format.h>
#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <complex>
#include <vector>

#include "bindings.h"
#include "obscura/core/error.h"
#include "obscura/optics/material.h"
#include "obscura/optics/mie.h"

namespace obscura::python {
namespace {

// One column of the optics table as a float64 array.
py::array_t<double> column(const std::vector<MaterialOptics>& rows, double MaterialOptics::*field) {
  py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
  for (std::size_t i = 0; i < rows.size(); ++i) a.mutable_data()[i] = rows[i].*field;
  return a;
}

py::dict material_optics(const std::string& name, const std::vector<double>& wavelengths_um,
                         double relative_humidity) {
  if (wavelengths_um.empty())
    throw InputError("", "wavelengths_um", "give the wavelengths in um, e.g. [0.55, 4, 10]");
  for (double w : wavelengths_um)
    if (!(w > 0))
      throw InputError("", "wavelengths_um", fmt::format("wavelengths must be > 0 um, got {}", w));
  const Material material = load_material_by_name(name);
  std::vector<MaterialOptics> rows;
  {
    py::gil_scoped_release release;  // Mie sums over the size distribution
    rows = optics_at(material, wavelengths_um, relative_humidity);
  }
  py::dict d;
  d["material"] = material.name;
  d["kind"] = std::string(to_string(material.kind));
  d["mass_basis"] = material.mass_basis;
  d["file"] = material.file;
  d["relative_humidity"] = relative_humidity;
  d["wavelength_um"] = column(rows, &MaterialOptics::wavelength_um);
  d["mass_extinction_m2_g"] = column(rows, &MaterialOptics::mass_extinction_m2_g);
  d["mass_extinction_min_m2_g"] = column(rows, &MaterialOptics::mass_extinction_min_m2_g);
  d["mass_extinction_max_m2_g"] = column(rows, &MaterialOptics::mass_extinction_max_m2_g);
  d["mass_scattering_m2_g"] = column(rows, &MaterialOptics::mass_scattering_m2_g);
  d["mass_absorption_m2_g"] = column(rows, &MaterialOptics::mass_absorption_m2_g);
  d["single_scattering_albedo"] = column(rows, &MaterialOptics::single_scattering_albedo);
  d["asymmetry"] = column(rows, &MaterialOptics::asymmetry);
  d["hydrated_mass_factor"] = column(rows, &MaterialOptics::hydrated_mass_factor);
  py::list methods, notes;
  for (const MaterialOptics& o : rows) {
    methods.append(o.method);
    notes.append(o.note);
  }
  d["method"] = methods;
  d["note"] = notes;
  d["units"] = py::dict(
      py::arg("wavelength_um") = "um", py::arg("mass_extinction_m2_g") = "m2 g-1",
      py::arg("mass_extinction_min_m2_g") = "m2 g-1",
      py::arg("mass_extinction_max_m2_g") = "m2 g-1", py::arg("mass_scattering_m2_g") = "m2 g-1",
      py::arg("mass_absorption_m2_g") = "m2 g-1", py::arg("single_scattering_albedo") = "1",
      py::arg("asymmetry") = "1", py::arg("hydrated_mass_factor") = "1");
  return d;
}

}  // namespace

void bind_optics(py::module_& m) {
  m.def(
      "mie",
      [](double size_parameter, std::complex<double> index) {
        const MieEfficiencies e = mie_sphere(size_parameter, index);
        py::dict d;
        d["qext"] = e.qext;
        d["qsca"] = e.qsca;
        d["qabs"] = e.qabs;
        d["qback"] = e.qback;
        d["g"] = e.g;
        d["terms"] = e.terms;
        return d;
      },
      py::arg("size_parameter"), py::arg("index"),
      "Efficiencies of a sphere of size parameter x = 2 pi r / lambda and relative index "
      "m = n + ik (k >= 0 absorbing): {qext, qsca, qabs, qback, g, terms}.");
  m.def("optics", &material_optics, py::arg("material"), py::arg("wavelengths_um"), py::kw_only(),
        py::arg("relative_humidity") = 0.0,
        "Bulk coefficients of a material of the database (a name, or a material file) at "
        "each wavelength (um): {wavelength_um, mass_extinction_m2_g, mass_scattering_m2_g, "
        "mass_absorption_m2_g, single_scattering_albedo, asymmetry, ...} as float64 arrays "
        "(NaN where the sources give extinction only), per gram of the material's mass basis, "
        "with their 'units'; as `obscura optics` prints them.");
}

}  // namespace obscura::python
