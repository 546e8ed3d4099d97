// `obscura optics`: bulk optical coefficients of an obscurant from the
// materials database at chosen wavelengths, with the sources of its numbers
// (docs/materials.md); `--list` shows the shipped materials.
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "commands.h"
#include "obscura/core/error.h"
#include "obscura/optics/material.h"
#include "option_parsing.h"

namespace obscura::cli {
namespace {

// "0.55,1.064,4,10": wavelengths in µm, each > 0.
std::vector<double> parse_wavelengths(const std::string& text) {
  std::vector<double> out;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string item = text.substr(start, comma == std::string::npos ? comma : comma - start);
    const double v = parse_number(item, "--wavelengths");
    if (!(v > 0))
      throw InputError("", "--wavelengths",
                       fmt::format("wavelengths must be > 0 µm, got {}", item));
    out.push_back(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

// Unknown values (NaN: not given by the sources) print as "—" and null.
std::string cell(double v) { return std::isnan(v) ? "—" : fmt::format("{:.4g}", v); }
nlohmann::json json_value(double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); }

int list(bool json) {
  const auto entries = list_materials();
  if (json) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& e : entries)
      out.push_back({{"name", e.name},
                     {"kind", e.kind},
                     {"description", e.description},
                     {"file", e.file.string()}});
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::size_t width = 4;
  for (const auto& e : entries) width = std::max(width, e.name.size());
  for (const auto& e : entries)
    std::cout << fmt::format("{:<{}}  {:<10}  {}\n", e.name, width, e.kind, e.description);
  return 0;
}

void print_text(const Material& m, const std::vector<MaterialOptics>& rows, double rh) {
  std::cout << fmt::format("{} ({}): {}\n", m.name, to_string(m.kind), m.description)
            << fmt::format("file: {}\n", m.file) << fmt::format("mass basis: {}\n", m.mass_basis);
  if (m.mie && m.mie->humidity) {
    const HumidityState s = humidity_state(*m.mie, rh);
    std::cout << fmt::format(
        "relative humidity {}: {:.4g} g of droplets per reference gram, radii ×{:.4g}\n", rh,
        s.mass_factor, s.radius_growth);
  } else if (rh > 0) {
    std::cout << fmt::format("relative humidity {}: no growth rule, no effect\n", rh);
  }
  std::cout << "\n"
            << fmt::format("{:>10}  {:>10}  {:>15}  {:>10}  {:>10}  {:>7}  {:>7}  {}\n",
                           "wavelength", "extinction", "(cited range)", "scattering", "absorption",
                           "albedo", "g", "method")
            << fmt::format("{:>10}  {:>10}  {:>15}  {:>10}  {:>10}  {:>7}  {:>7}\n", "µm", "m²/g",
                           "m²/g", "m²/g", "m²/g", "", "");
  std::vector<std::string> notes;
  for (const auto& o : rows) {
    const bool range = o.mass_extinction_min_m2_g != o.mass_extinction_max_m2_g;
    std::string method = o.method;
    if (!o.note.empty()) {
      notes.push_back(fmt::format("[{}] {} µm: {}", notes.size() + 1, o.wavelength_um, o.note));
      method += fmt::format(" [{}]", notes.size());
    }
    std::cout << fmt::format("{:>10}  {:>10}  {:>15}  {:>10}  {:>10}  {:>7}  {:>7}  {}\n",
                             fmt::format("{:g}", o.wavelength_um), cell(o.mass_extinction_m2_g),
                             range ? fmt::format("({:.4g}–{:.4g})", o.mass_extinction_min_m2_g,
                                                 o.mass_extinction_max_m2_g)
                                   : "",
                             cell(o.mass_scattering_m2_g), cell(o.mass_absorption_m2_g),
                             cell(o.single_scattering_albedo), cell(o.asymmetry), method);
  }
  for (const auto& n : notes) std::cout << n << "\n";
  if (m.tabulated) std::cout << "\ntabulated values: " << m.tabulated->note << "\n";
  if (!m.notes.empty()) {
    std::cout << "\nnotes:\n";
    for (const auto& n : m.notes) std::cout << "  - " << n << "\n";
  }
  std::cout << "\nsources:\n";
  for (const auto& [what, source] : material_sources(m))
    std::cout << fmt::format("  {}: {}\n", what, source);
}

void print_json(const Material& m, const std::vector<MaterialOptics>& rows, double rh) {
  nlohmann::json out = {
      {"material", m.name}, {"kind", to_string(m.kind)},  {"description", m.description},
      {"file", m.file},     {"mass_basis", m.mass_basis}, {"relative_humidity", rh},
      {"notes", m.notes}};
  nlohmann::json r = nlohmann::json::array();
  for (const auto& o : rows)
    r.push_back(
        {{"wavelength_um", o.wavelength_um},
         {"mass_extinction_m2_g", o.mass_extinction_m2_g},
         {"mass_extinction_range_m2_g", {o.mass_extinction_min_m2_g, o.mass_extinction_max_m2_g}},
         {"mass_scattering_m2_g", json_value(o.mass_scattering_m2_g)},
         {"mass_absorption_m2_g", json_value(o.mass_absorption_m2_g)},
         {"single_scattering_albedo", json_value(o.single_scattering_albedo)},
         {"asymmetry", json_value(o.asymmetry)},
         {"hydrated_mass_factor", o.hydrated_mass_factor},
         {"method", o.method},
         {"note", o.note}});
  out["rows"] = std::move(r);
  nlohmann::json sources = nlohmann::json::array();
  for (const auto& [what, source] : material_sources(m))
    sources.push_back({{"what", what}, {"source", source}});
  out["sources"] = std::move(sources);
  if (m.tabulated) out["tabulated_note"] = m.tabulated->note;
  std::cout << out.dump(2) << "\n";
}

}  // namespace

Command add_optics_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "optics",
      "Mass extinction and scattering (m²/g), albedo and g of an obscurant from the materials "
      "database");
  struct Options {
    std::string material, wavelengths;
    std::optional<std::string> humidity;
    bool list = false, json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--material", o->material,
                  "Material name (obscura optics --list) or path of a material JSON file")
      ->type_name("NAME|FILE");
  cmd->add_option("--wavelengths", o->wavelengths, "Vacuum wavelengths, µm, comma-separated")
      ->type_name("L1,L2,...");
  cmd->add_option("--humidity", o->humidity,
                  "Relative humidity as a fraction in [0, 1) (hygroscopic droplets grow)")
      ->type_name("RH");
  cmd->add_flag("--list", o->list, "List the shipped materials");
  cmd->add_flag("--json", o->json, "Print JSON instead of text");
  return {
      cmd, [o]() {
        if (o->list) {
          if (!o->material.empty() || !o->wavelengths.empty())
            throw InputError("", "--list", "--list takes no --material or --wavelengths");
          return list(o->json);
        }
        if (o->material.empty())
          throw InputError("", "--material",
                           "give --material NAME with --wavelengths L1,L2,..., or --list");
        if (o->wavelengths.empty())
          throw InputError("", "--wavelengths", "give the wavelengths in µm, e.g. 0.55,1.064,4,10");
        const std::vector<double> wavelengths = parse_wavelengths(o->wavelengths);
        double rh = 0;
        if (o->humidity) {
          rh = parse_number(*o->humidity, "--humidity");
          if (!(rh >= 0 && rh < 1))
            throw InputError(
                "", "--humidity",
                fmt::format("must lie in [0, 1) (a fraction, not per cent), got {}", *o->humidity));
        }
        Material material;
        try {
          material = load_material_by_name(o->material);
        } catch (const InputError& e) {
          if (e.file().empty() && e.field() == "material")
            throw InputError("", "--material", e.detail());
          throw;
        }
        const auto rows = optics_at(material, wavelengths, rh);
        if (o->json)
          print_json(material, rows, rh);
        else
          print_text(material, rows, rh);
        return 0;
      }};
}

}  // namespace obscura::cli
