#pragma once
// --format on `render`: optional outputs beyond the EXR, PNG, CSV and JSON files
// every render writes (scene/output_formats.h). Repeated or a comma list
// (--format netcdf,envi); it adds to the scene's "outputs". An unknown name is a
// usage error (exit 64, docs/errors.md), as an unknown option is.
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "obscura/scene/output_formats.h"
#include "obscura/scene/scene.h"

namespace obscura::cli {

inline void add_format_option(CLI::App* cmd, std::vector<std::string>& names) {
  const CLI::Validator known(
      [](std::string& name) {
        return parse_output_format(name) ? std::string() : unknown_output_format_message(name);
      },
      "FORMAT");
  cmd->add_option("--format", names,
                  "Also write FORMAT (repeat or comma list): netcdf writes render.nc, every "
                  "frame, sensor and band in one NetCDF-CF file; envi writes each sensor's band "
                  "radiance per frame as an ENVI cube, SENSOR[_fNNNN]_radiance.img and .hdr "
                  "(docs/formats.md); adds to the scene's \"outputs\"")
      ->delimiter(',')
      ->check(known);
}

// The scene's outputs plus those named (checked by the option's validator).
inline void apply_formats(const std::vector<std::string>& names, Scene& scene) {
  for (const std::string& name : names)
    if (const auto format = parse_output_format(name)) add_output_format(scene.outputs, *format);
}

}  // namespace obscura::cli
