// The optics layer in Python: Lorenz–Mie efficiencies of a sphere, as
// `obscura mie` prints them (docs/optics.md).
#include <pybind11/complex.h>

#include <complex>

#include "bindings.h"
#include "obscura/optics/mie.h"

namespace obscura::python {

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
}

}  // namespace obscura::python
