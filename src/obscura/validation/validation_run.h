#pragma once
// The canonical cases run by name with their parameters, as `obscura
// validate` and Python's obscura.validate ask for them: one request, the
// rows of every case it names, and those rows as the JSON the CLI prints.
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "obscura/validation/validation_cases.h"

namespace obscura {

// The case names a request takes: one case, or "all".
const std::vector<std::string>& validation_case_names();

struct ValidationRequest {
  std::string name = "all";  // validation_case_names()
  // Unset: each case's default (tau 1, single-scatter 0.002; g 0.5; albedo:
  // slab 0.9, equilibrium 0.8).
  std::optional<double> tau, g, albedo;
  double temperature_k = 300.0;      // equilibrium, emitting-slab
  std::string incidence = "normal";  // slab: normal, collimated (at mu0) or diffuse
  double mu0 = 1.0;
  std::optional<double> half_width_m;  // slab; default 1e6 m, photonmap 20 m
  std::string reference;               // slab table; empty: the data folder's
  // The solver and its settings; photons_per_node unset: 200 000 for the
  // photon map, 4e6 for the radiance cache (the closed forms resolve 0.5 %).
  RenderSettings settings = ValidationOptions().settings;
  std::optional<long long> photons_per_node;
  int samples = 0;  // 0: batches until the standard error is small enough
};

struct ValidationRun {
  std::vector<ValidationRow> rows;
  std::optional<SlabReference> slab_reference;  // the slab's table row, when run
  bool ok() const;                              // every judged row passed
};

// Runs the request's cases. Throws InputError (no file; the field is the
// parameter as `obscura validate` names it: "case", "--incidence", "--mu0",
// "--tau", …, as the cases do) on bad parameters.
ValidationRun run_validation(const ValidationRequest& request);

// What `obscura validate --json` prints: an array of {case, quantity,
// reference, obtained, relative_error, stderr, tolerance, samples, pass},
// null where a row has no reference.
nlohmann::json validation_rows_json(const std::vector<ValidationRow>& rows);

}  // namespace obscura
