#pragma once
// `obscura prepare`: the preparation phase of the source paper, from a JSON
// configuration (docs/preparation.md): particle concentrations over time, from
// the built-in dispersion model or from CFD output (VTK legacy, NetCDF-CF),
// and a material's optics (optics/material.h) become cloud keyframes (OpenVDB,
// σa, σs, g per spectral sample and temperature, or the compact species form:
// concentration and temperature with the optics table) and a manifest with a
// lifecycle (docs/time-varying-clouds.md), ready for a scene's "animated"
// cloud.
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "obscura/medium/lifecycle.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {

struct PrepareOptions {
  int threads = 0;  // 0: all cores
  // Progress lines ("frame 3 of 31 ...") for a long run; may be empty.
  std::function<void(const std::string&)> progress;
  std::string command_line;  // recorded in every keyframe's metadata
};

struct PrepareReport {
  std::filesystem::path manifest;  // out_dir / "cloud.json"
  std::vector<std::filesystem::path> keyframes;
  std::vector<double> times_s;
  GridDims dims;
  double voxel_size_m = 0;
  std::vector<double> wavelengths_um;
  std::string material;
  std::string output_form = "spectral";  // keyframe form: "spectral" or "species"
  LifecycleSpec lifecycle;
  bool lifecycle_suggested = true;
  double released_mass_g = 0;  // dispersion source only
  std::vector<std::string> warnings;
  std::uintmax_t bytes_written = 0;
  double seconds_concentrations = 0, seconds_optics = 0, seconds_keyframes = 0;
};

// Reads `config`, computes, and writes the cloud into `out_dir`, which must
// not exist or be empty. Everything is written into a sibling temporary folder
// first and renamed at the end, so a failed run leaves nothing behind. Throws
// InputError naming the file and JSON path on bad input.
PrepareReport prepare_cloud(const std::filesystem::path& config,
                            const std::filesystem::path& out_dir,
                            const PrepareOptions& options = {});

// The same from an already-parsed configuration (a parameter study's case,
// study/study_spec.h): `config_path` names it in errors, and relative paths
// in it are relative to its folder.
PrepareReport prepare_cloud(const nlohmann::json& config, const std::filesystem::path& config_path,
                            const std::filesystem::path& out_dir,
                            const PrepareOptions& options = {});

}  // namespace obscura
