// `obscura validate`: canonical cases with known answers, run through the same
// transport code that renders images; a table (or JSON) and a non-zero exit on
// any failure.
#include <iostream>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.h"
#include "obscura/core/error.h"
#include "obscura/validation/validation_cases.h"

namespace obscura::cli {

Command add_validate_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "validate",
      "Run canonical radiative-transfer cases (furnace, equilibrium, emitting-slab, "
      "single-scatter, puff-transmittance, or all) against their known answers");
  struct Options {
    std::string name;
    std::optional<double> tau, g;
    double albedo = 0.8, temperature = 300.0;
    std::optional<int> samples;
    std::uint64_t seed = 1;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("case", o->name, "furnace | equilibrium | emitting-slab | single-scatter | "
                                   "puff-transmittance | all")
      ->required()
      ->check(CLI::IsMember({"furnace", "equilibrium", "emitting-slab", "single-scatter",
                             "puff-transmittance", "all"}));
  cmd->add_option("--tau", o->tau,
                  "Optical thickness (default 1; single-scatter 0.002)");
  cmd->add_option("--g", o->g, "Henyey-Greenstein asymmetry (default 0.5)");
  cmd->add_option("--albedo", o->albedo, "Single-scattering albedo (equilibrium)")->capture_default_str();
  cmd->add_option("--temperature", o->temperature, "Temperature, K (equilibrium, emitting-slab)")
      ->capture_default_str();
  cmd->add_option("--samples", o->samples,
                  "Monte Carlo samples per quantity (default: batches until the standard error is "
                  "below half the case's tolerance)");
  cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  cmd->add_flag("--json", o->json, "Print a JSON array of rows instead of a table");
  return {cmd, [o]() {
            const double g = o->g.value_or(0.5);
            const ValidationOptions options{o->samples.value_or(0), o->seed};
            std::vector<ValidationRow> rows;
            auto add = [&](std::vector<ValidationRow> r) { rows.insert(rows.end(), r.begin(), r.end()); };
            const bool all = o->name == "all";
            if (all || o->name == "furnace") add(validate_furnace(o->tau.value_or(1.0), g, options));
            if (all || o->name == "equilibrium")
              add(validate_equilibrium(o->albedo, o->tau.value_or(1.0), g, o->temperature, options));
            if (all || o->name == "emitting-slab")
              add(validate_emitting_slab(o->tau.value_or(1.0), o->temperature, options));
            if (all || o->name == "single-scatter")
              add(validate_single_scatter(o->tau.value_or(0.002), g, options));
            if (all || o->name == "puff-transmittance") add(validate_puff_transmittance(options));
            bool ok = true;
            nlohmann::json out = nlohmann::json::array();
            for (const auto& r : rows) {
              ok = ok && r.pass;
              out.push_back({{"case", r.case_name}, {"quantity", r.quantity}, {"reference", r.reference},
                             {"obtained", r.obtained}, {"relative_error", r.relative_error()},
                             {"stderr", r.stderr_mean}, {"tolerance", r.tolerance},
                             {"samples", r.samples}, {"pass", r.pass}});
            }
            if (o->json) {
              std::cout << out.dump(2) << "\n";
            } else {
              std::cout << fmt::format("{:<44} {:<18} {:>12} {:>12} {:>10} {:>10} {:>9}  {}\n", "case",
                                       "quantity", "reference", "obtained", "rel.error", "stderr",
                                       "samples", "result");
              for (const auto& r : rows)
                std::cout << fmt::format("{:<44} {:<18} {:>12.6g} {:>12.6g} {:>10.2e} {:>10.2e} {:>9}  {}\n",
                                         r.case_name, r.quantity, r.reference, r.obtained,
                                         r.relative_error(), r.stderr_mean, r.samples,
                                         r.pass ? "pass" : "FAIL");
              std::cout << fmt::format("{} of {} passed (pass: |difference| <= max(3 stderr, tolerance) "
                                       "and stderr <= tolerance)\n",
                                       std::count_if(rows.begin(), rows.end(), [](auto& r) { return r.pass; }),
                                       rows.size());
            }
            return ok ? 0 : 1;
          }};
}

}  // namespace obscura::cli
