#pragma once
// A `prepare` configuration read and checked in full before anything is
// computed (docs/preparation.md): a misspelt key or a bad value is reported
// at once, not after a long dispersion run. Reading it touches no file other
// than the material's; the CFD files it names are read by prepare_cloud.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "obscura/io/netcdf_cf.h"
#include "obscura/io/vtk_structured_points.h"
#include "obscura/medium/lifecycle.h"
#include "obscura/optics/material.h"
#include "obscura/prep/dispersion/dispersion_config.h"

namespace obscura {

// "source": "dispersion": the built-in model at the given times and voxel size.
struct DispersionSource {
  DispersionConfig config;
  std::vector<double> times_s;  // >= 2, strictly increasing, >= 0
  double voxel_size_m = 0;
};

// "source": "vtk": one legacy structured-points file per frame.
struct VtkSource {
  VtkArrayNames names;
  std::vector<std::pair<double, std::string>> time_and_path;  // paths resolved
  double ambient_temperature_k = 288.15;
};

// "source": "netcdf": one CF file holding every frame.
struct NetcdfSource {
  std::filesystem::path file;  // resolved
  NetcdfReadOptions options;
  double ambient_temperature_k = 288.15;
};

struct PrepareConfig {
  std::string file;  // the configuration, as errors name it
  Material material;
  double relative_humidity = 0;          // [0, 1)
  std::vector<double> wavelengths_um;    // > 0, strictly increasing
  std::string output_form = "spectral";  // "spectral" or "species"
  std::variant<DispersionSource, VtkSource, NetcdfSource> source;
  // Given by the user; otherwise suggested from the frames' timing. Checked
  // against the frames' times once they are known (a NetCDF file's are in it).
  std::optional<LifecycleSpec> lifecycle;
};

// Reads and checks `doc`; `config_path` names it in errors, and relative file
// names in it are relative to its folder. Unknown keys are errors. Throws
// InputError naming the file and JSON path.
PrepareConfig read_prepare_config(const nlohmann::json& doc,
                                  const std::filesystem::path& config_path);

}  // namespace obscura
