// `obscura mie`: Lorenz–Mie efficiencies of one homogeneous sphere, given its
// size parameter, or its radius and the wavelength (docs/optics.md).
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <complex>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <optional>
#include <string>

#include "commands.h"
#include "obscura/core/error.h"
#include "obscura/optics/mie.h"
#include "option_parsing.h"

namespace obscura::cli {
namespace {

double parse_positive(const std::string& text, const char* option, const char* what) {
  const double v = parse_number(text, option);
  if (!(v > 0)) throw InputError("", option, fmt::format("{} must be > 0, got {}", what, text));
  return v;
}

// "RE,IM" (or "RE" for a non-absorbing sphere): m = RE + i·IM, IM ≥ 0 absorbing.
std::complex<double> parse_index(const std::string& text) {
  const auto comma = text.find(',');
  const double re = parse_number(text.substr(0, comma), "--index");
  const double im =
      comma == std::string::npos ? 0.0 : parse_number(text.substr(comma + 1), "--index");
  if (!(re > 0))
    throw InputError("", "--index", fmt::format("the real part must be > 0, got '{}'", text));
  if (!(im >= 0))
    throw InputError(
        "", "--index",
        fmt::format("the imaginary part must be >= 0 (k >= 0 is absorbing), got '{}'", text));
  return {re, im};
}

}  // namespace

Command add_mie_command(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "mie", "Mie efficiencies (Qext, Qsca, Qabs, Qback, g) of a homogeneous sphere");
  struct Options {
    std::optional<std::string> size_parameter, radius, wavelength;
    std::string index;
    bool json = false;
  };
  auto o = std::make_shared<Options>();
  cmd->add_option("--size-parameter", o->size_parameter, "Size parameter x = 2πr/λ")
      ->type_name("X");
  cmd->add_option("--radius-um", o->radius, "Sphere radius, µm (with --wavelength-um)")
      ->type_name("R");
  cmd->add_option("--wavelength-um", o->wavelength, "Wavelength in the surrounding medium, µm")
      ->type_name("L");
  cmd->add_option("--index", o->index,
                  "Relative refractive index: m = RE + i·IM, IM >= 0 absorbing (required)")
      ->type_name("RE,IM");
  cmd->add_flag("--json", o->json, "Print a JSON object instead of text");
  return {cmd, [o]() {
            if (o->index.empty())
              throw InputError("", "--index", "give the refractive index as RE,IM");
            const std::complex<double> m = parse_index(o->index);
            if (o->size_parameter && (o->radius || o->wavelength))
              throw InputError(
                  "", "--size-parameter",
                  "give either --size-parameter or --radius-um with --wavelength-um, not both");
            double x = 0;
            std::optional<double> radius_um, wavelength_um;
            if (o->size_parameter) {
              x = parse_positive(*o->size_parameter, "--size-parameter", "the size parameter");
            } else if (o->radius || o->wavelength) {
              if (!o->radius)
                throw InputError("", "--radius-um", "give the radius with --wavelength-um");
              if (!o->wavelength)
                throw InputError("", "--wavelength-um", "give the wavelength with --radius-um");
              radius_um = parse_positive(*o->radius, "--radius-um", "the radius");
              wavelength_um = parse_positive(*o->wavelength, "--wavelength-um", "the wavelength");
              x = 2.0 * std::numbers::pi * *radius_um / *wavelength_um;
            } else {
              throw InputError("", "--size-parameter",
                               "give --size-parameter X, or --radius-um R with --wavelength-um L");
            }
            if (x > kMaxMieSizeParameter)
              throw InputError("", radius_um ? "--radius-um" : "--size-parameter",
                               fmt::format("size parameter {:.6g} is beyond the Mie limit {:g}", x,
                                           kMaxMieSizeParameter));

            const MieEfficiencies q = mie_sphere(x, m);
            if (o->json) {
              nlohmann::json out = {{"size_parameter", x},
                                    {"index", {{"real", m.real()}, {"imag", m.imag()}}},
                                    {"qext", q.qext},
                                    {"qsca", q.qsca},
                                    {"qabs", q.qabs},
                                    {"qback", q.qback},
                                    {"g", q.g}};
              if (radius_um) {
                out["radius_um"] = *radius_um;
                out["wavelength_um"] = *wavelength_um;
              }
              std::cout << out.dump(2) << "\n";
              return 0;
            }
            if (radius_um)
              std::cout << fmt::format("sphere of radius {} µm at wavelength {} µm\n", *radius_um,
                                       *wavelength_um);
            std::cout << fmt::format(
                             "size parameter x = {:.10g}, index m = {} + {}i ({} partial waves)\n",
                             x, m.real(), m.imag(), q.terms)
                      << fmt::format("  Qext   {:.10g}\n", q.qext)
                      << fmt::format("  Qsca   {:.10g}\n", q.qsca)
                      << fmt::format("  Qabs   {:.10g}\n", q.qabs)
                      << fmt::format("  Qback  {:.10g}\n", q.qback)
                      << fmt::format("  g      {:.10g}\n", q.g);
            return 0;
          }};
}

}  // namespace obscura::cli
