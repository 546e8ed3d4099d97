// The validation layer in Python: obscura.validate runs the canonical cases
// with known answers (docs/validation.md) through the library's
// run_validation, the call behind `obscura validate`, and returns the rows
// `obscura validate --json` prints.
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>

#include "bindings.h"
#include "obscura/validation/validation_run.h"
#include "scene_handle.h"

namespace obscura::python {

void bind_validation(py::module_& m) {
  m.def(
      "validate",
      [](const std::string& name, const std::string& method, std::optional<double> tau,
         std::optional<double> g, std::optional<double> albedo, double temperature,
         const std::string& incidence, double mu0, std::optional<double> half_width,
         std::optional<int> samples, std::optional<long long> photons,
         std::optional<std::uint64_t> seed, std::optional<int> threads,
         const std::string& reference, bool pure_photon_map) {
        ValidationRequest r;
        r.name = name;
        const auto parsed = parse_render_method(method);
        if (!parsed)
          throw InputError("", "--method",
                           "unknown render method '" + method +
                               "' (expected one of: " + render_method_names() + ")");
        r.settings.method = *parsed;
        r.settings.photon_map.pure = pure_photon_map;
        if (seed) r.settings.seed = *seed;
        if (threads) r.settings.threads = *threads;
        r.tau = tau;
        r.g = g;
        r.albedo = albedo;
        r.temperature_k = temperature;
        r.incidence = incidence;
        r.mu0 = mu0;
        r.half_width_m = half_width;
        r.samples = samples.value_or(0);
        r.photons_per_node = photons;
        r.reference = reference;
        ValidationRun run;
        {
          py::gil_scoped_release release;  // Monte Carlo batches until converged
          run = run_validation(r);
        }
        return json_to_python(validation_rows_json(run.rows));
      },
      py::arg("case") = "all", py::kw_only(), py::arg("method") = "path-tracer",
      py::arg("tau") = py::none(), py::arg("g") = py::none(), py::arg("albedo") = py::none(),
      py::arg("temperature") = 300.0, py::arg("incidence") = "normal", py::arg("mu0") = 1.0,
      py::arg("half_width") = py::none(), py::arg("samples") = py::none(),
      py::arg("photons") = py::none(), py::arg("seed") = py::none(),
      py::arg("threads") = py::none(), py::arg("reference") = "",
      py::arg("pure_photon_map") = false,
      "Runs a canonical case (slab, furnace, equilibrium, emitting-slab, single-scatter, "
      "puff-transmittance, or all) as `obscura validate` does and returns its rows: "
      "[{case, quantity, reference, obtained, relative_error, stderr, tolerance, samples, "
      "pass}], reference, relative_error and pass None where a row has no reference.");
}

}  // namespace obscura::python
