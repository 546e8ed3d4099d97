// `obscura validate`: canonical cases with known answers, run through the same
// transport code that renders images; a table (or JSON) and a non-zero exit on
// any failure.
#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.h"
#include "memory_option.h"
#include "obscura/core/error.h"
#include "obscura/validation/validation_run.h"

namespace obscura::cli {

namespace {

struct ValidateOptions {
  std::string name;
  std::optional<double> tau, g, albedo;
  double temperature = 300.0;
  std::string incidence = "normal";
  double mu0 = 1.0;
  std::optional<double> half_width;
  std::string method = "path-tracer";
  RenderSettings settings;
  std::string form = "hybrid";
  std::string reference;
  std::optional<int> samples;
  std::optional<long long> photons;
  bool json = false;
};

void add_options(CLI::App* cmd, ValidateOptions* o) {
  cmd->add_option("case", o->name,
                  "slab | furnace | equilibrium | emitting-slab | single-scatter | "
                  "puff-transmittance | all")
      ->required()
      ->check(CLI::IsMember(validation_case_names()));
  cmd->add_option("--tau", o->tau, "Optical thickness (default 1; single-scatter 0.002)");
  cmd->add_option("--g", o->g, "Henyey-Greenstein asymmetry (default 0.5)");
  cmd->add_option("--albedo", o->albedo,
                  "Single-scattering albedo (default: slab 0.9, equilibrium 0.8)");
  cmd->add_option("--incidence", o->incidence,
                  "Slab illumination: normal (collimated beam along the normal), collimated (at "
                  "--mu0), diffuse (isotropic radiance from above)")
      ->check(CLI::IsMember({"normal", "collimated", "diffuse"}))
      ->capture_default_str();
  cmd->add_option("--mu0", o->mu0, "Slab, collimated: cosine of the beam's zenith angle")
      ->capture_default_str();
  cmd->add_option("--half-width", o->half_width,
                  "Slab half-width, m (the slab is 1 m thick; default 1e6, photonmap 20; "
                  "docs/validation.md measures the edge loss)");
  std::vector<std::string> methods;
  for (RenderMethod m : kRenderMethods) methods.emplace_back(render_method_name(m));
  cmd->add_option("--method", o->method,
                  "Solver: " + render_method_names() +
                      " (photonmap judged at 2 %; emission-absorption only on cases without "
                      "scattering)")
      ->check(CLI::IsMember(methods))
      ->capture_default_str();
  PhotonMapSettings& pm = o->settings.photon_map;
  cmd->add_option(
      "--photons", o->photons,
      "photonmap, radiance-cache: photons launched per spectral node (default: "
      "200000; radiance-cache 16000000, slab 4000000: the closed-form cases resolve 0.5 %)");
  cmd->add_option("--k", pm.k, "photonmap: nearest photons per estimate")->capture_default_str();
  cmd->add_option("--max-radius", pm.max_radius_m, "photonmap: search radius cap, m")
      ->capture_default_str();
  cmd->add_option("--step", pm.step_m, "photonmap: longest marching segment, m")
      ->capture_default_str();
  RadianceCacheSettings& rc = o->settings.radiance_cache;
  cmd->add_option("--voxel", rc.voxel_m,
                  "radiance-cache: lattice spacing, m (0: the medium's largest side / 32)")
      ->capture_default_str();
  cmd->add_option("--sh-degree", rc.sh_degree,
                  "radiance-cache: spherical-harmonic degree of the incident radiance, 1-6 (6 for "
                  "a phase function as peaked as g = 0.85)")
      ->check(CLI::Range(1, 6))
      ->capture_default_str();
  cmd->add_option("--kernel", rc.kernel_radius_nodes,
                  "radiance-cache: splatting kernel half-width, lattice spacings")
      ->capture_default_str();
  cmd->add_option("--form", o->form,
                  "photonmap: hybrid (shadow rays for single scattering) or pure")
      ->check(CLI::IsMember({"hybrid", "pure"}))
      ->capture_default_str();
  cmd->add_option("--reference", o->reference,
                  "Slab reference table (default: data/validation/slab_reference.csv)");
  cmd->add_option("--temperature", o->temperature, "Temperature, K (equilibrium, emitting-slab)")
      ->capture_default_str();
  cmd->add_option("--samples", o->samples,
                  "Monte Carlo samples per quantity (default: batches until the standard error is "
                  "below half the case's tolerance)");
  cmd->add_option("--seed", o->settings.seed, "Random seed")->capture_default_str();
  cmd->add_option("--threads", o->settings.threads,
                  "Threads (0: all cores); results do not depend on it")
      ->capture_default_str();
  cmd->add_flag("--json", o->json, "Print a JSON array of rows instead of a table");
}

// The request the command line makes (validation/validation_run.h), whose
// errors name the options.
ValidationRun run_cases(const ValidateOptions& o) {
  ValidationRequest r;
  r.name = o.name;
  r.tau = o.tau;
  r.g = o.g;
  r.albedo = o.albedo;
  r.temperature_k = o.temperature;
  r.incidence = o.incidence;
  r.mu0 = o.mu0;
  r.half_width_m = o.half_width;
  r.reference = o.reference;
  r.settings = o.settings;
  r.settings.method = *parse_render_method(o.method);  // CLI::IsMember checked it
  r.settings.photon_map.pure = o.form == "pure";
  r.photons_per_node = o.photons;
  r.samples = o.samples.value_or(0);
  return run_validation(r);
}

// The slab's own keys (R, T, T_direct with standard errors), its reference and its rows.
nlohmann::json slab_json(const std::vector<ValidationRow>& rows,
                         const std::optional<SlabReference>& reference, bool ok) {
  nlohmann::json slab = {{"case", rows[0].case_name}};
  for (const auto& r : rows) {
    slab[r.quantity] = r.obtained;
    slab[r.quantity + "_stderr"] = r.stderr_mean;
  }
  slab["reference"] = reference ? nlohmann::json{{"R", reference->r},
                                                 {"T", reference->t},
                                                 {"T_direct", reference->t_direct},
                                                 {"source", reference->source}}
                                : nlohmann::json();
  slab["rows"] = validation_rows_json(rows);
  slab["pass"] = ok;
  return slab;
}

std::string rows_table(const std::vector<ValidationRow>& rows,
                       const std::optional<SlabReference>& slab_reference) {
  std::string text =
      fmt::format("{:<44} {:<18} {:>12} {:>12} {:>10} {:>10} {:>9}  {}\n", "case", "quantity",
                  "reference", "obtained", "rel.error", "stderr", "samples", "result");
  for (const auto& r : rows) {
    if (r.judged)
      text += fmt::format("{:<44} {:<18} {:>12.6g} {:>12.6g} {:>10.2e} {:>10.2e} {:>9}  {}\n",
                          r.case_name, r.quantity, r.reference, r.obtained, r.relative_error(),
                          r.stderr_mean, r.samples, r.pass ? "pass" : "FAIL");
    else
      text +=
          fmt::format("{:<44} {:<18} {:>12} {:>12.6g} {:>10} {:>10.2e} {:>9}  {}\n", r.case_name,
                      r.quantity, "-", r.obtained, "-", r.stderr_mean, r.samples, "no reference");
  }
  if (slab_reference && !slab_reference->source.empty())
    text += "slab reference: " + slab_reference->source + "\n";
  const auto judged = std::count_if(rows.begin(), rows.end(), [](auto& r) { return r.judged; });
  text += fmt::format(
      "{} of {} passed (pass: |difference| <= max(3 stderr, tolerance) and stderr <= "
      "tolerance)\n",
      std::count_if(rows.begin(), rows.end(), [](auto& r) { return r.judged && r.pass; }), judged);
  return text;
}

}  // namespace

Command add_validate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "validate",
      "Run canonical radiative-transfer cases (slab, furnace, equilibrium, emitting-slab, "
      "single-scatter, puff-transmittance, or all) against their known answers");
  auto o = std::make_shared<ValidateOptions>();
  add_options(cmd, o.get());
  auto max_memory = std::make_shared<std::string>();
  add_max_memory_option(cmd, max_memory);
  return {cmd, [o, max_memory]() {
            apply_max_memory(*max_memory);
            const ValidationRun run = run_cases(*o);
            const std::vector<ValidationRow>& rows = run.rows;
            const std::optional<SlabReference>& slab_reference = run.slab_reference;
            const bool ok = run.ok();
            if (o->json && o->name == "slab")
              std::cout << slab_json(rows, slab_reference, ok).dump(2) << "\n";
            else if (o->json)
              std::cout << validation_rows_json(rows).dump(2) << "\n";
            else
              std::cout << rows_table(rows, slab_reference);
            return ok ? 0 : 1;
          }};
}

}  // namespace obscura::cli
