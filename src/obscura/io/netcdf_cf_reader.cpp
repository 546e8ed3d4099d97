// The CF reader (io/netcdf_cf.h): the file's concentration variable, its
// axes and coordinates, the memory check, and the frames, one per time step.
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <system_error>
#include <vector>

#include "obscura/core/error.h"
#include "obscura/core/memory_limit.h"
#include "obscura/io/netcdf_cf.h"
#include "obscura/io/netcdf_cf_axes.h"
#include "obscura/io/netcdf_cf_data_variable.h"
#include "obscura/io/netcdf_cf_units.h"
#include "obscura/io/netcdf_child_read.h"
#include "obscura/io/netcdf_classic_check.h"
#include "obscura/io/netcdf_file.h"
#include "obscura/medium/voxel_grid.h"

namespace obscura {
namespace {

using netcdf_cf::AxisInfo;
using netcdf_cf::Coordinates;
using netcdf_cf::DataVar;
using netcdf_cf::kT;
using netcdf_cf::kUniformTolerance;
using netcdf_cf::kX;
using netcdf_cf::kY;
using netcdf_cf::kZ;
using netcdf_cf::NcHandle;
using netcdf_cf::NcReader;

// The four axes of the concentration variable's dimensions.
std::array<AxisInfo, 4> concentration_axes(const NcReader& r, const NetcdfReadOptions& opt) {
  const int conc_id = r.find_variable(opt.concentration);
  const std::vector<int> dims = r.var_dims(conc_id);
  if (dims.size() != 4) {
    std::string list;
    for (std::size_t i = 0; i < dims.size(); ++i) list += (i ? ", " : "") + r.dim_name(dims[i]);
    r.fail(opt.concentration,
           fmt::format("has {} dimensions ({}); expected 4: (time, z, y, x)", dims.size(), list));
  }
  return netcdf_cf::identify_axes(r, conc_id, dims);
}

// Sizes before any allocation: every frame's grids plus one staging slab.
// Returns the voxels of one frame.
std::uint64_t check_memory(const NcReader& r, const std::array<AxisInfo, 4>& axes,
                           const NetcdfReadOptions& opt) {
  for (int a = 0; a < 3; ++a)
    if (axes[a].len > static_cast<std::size_t>(std::numeric_limits<int>::max()))
      r.fail(axes[a].name, fmt::format("length {} is too large", axes[a].len));
  const std::uint64_t channels = opt.temperature.empty() ? 1 : 2;
  std::uint64_t voxels = 0, grid_bytes = 0, total = 0;
  const bool overflow =
      __builtin_mul_overflow(static_cast<std::uint64_t>(axes[kX].len),
                             static_cast<std::uint64_t>(axes[kY].len), &voxels) ||
      __builtin_mul_overflow(voxels, static_cast<std::uint64_t>(axes[kZ].len), &voxels) ||
      __builtin_mul_overflow(voxels, static_cast<std::uint64_t>(axes[kT].len) * channels * 4,
                             &grid_bytes) ||
      __builtin_add_overflow(grid_bytes, voxels * 8, &total);
  if (overflow || total > memory_limit_bytes())
    r.fail(
        opt.concentration,
        fmt::format("{} time steps of {} x {} x {} voxels ({} {}) need {:.3g} GiB but only {}",
                    axes[kT].len, axes[kX].len, axes[kY].len, axes[kZ].len, channels,
                    channels == 1 ? "variable" : "variables",
                    static_cast<double>(axes[kX].len) * static_cast<double>(axes[kY].len) *
                        static_cast<double>(axes[kZ].len) *
                        (4.0 * static_cast<double>(channels * axes[kT].len) + 8.0) / 1073741824.0,
                    memory_limit_text()));
  return voxels;
}

// The voxels' placement: cubic (ScalarGrid has one voxel size), with the
// smallest coordinates at the first voxel centre.
GridPlacement grid_placement(const NcReader& r, const std::array<AxisInfo, 4>& axes,
                             const std::array<Coordinates, 3>& coords) {
  const double h = std::abs(coords[kX].spacing);
  for (int a = 1; a < 3; ++a)
    if (std::abs(std::abs(coords[a].spacing) - h) >
        kUniformTolerance * h + coords[a].spacing_rounding + coords[kX].spacing_rounding)
      r.fail(axes[a].name,
             fmt::format("spacing {} m differs from {}'s {} m: obscura grids have "
                         "cubic voxels, so x, y and z must be equally spaced (to a "
                         "relative {}); resample the data onto an isotropic grid",
                         std::abs(coords[a].spacing), axes[kX].name, h, kUniformTolerance));
  GridPlacement placement;
  placement.voxel_size_m = h;
  placement.origin_m = {coords[kX].min_centre - 0.5 * h, coords[kY].min_centre - 0.5 * h,
                        coords[kZ].min_centre - 0.5 * h};
  return placement;
}

// The factor from the concentration's units (or the caller's default) to g/m³.
double concentration_factor(const NcReader& r, const DataVar& conc, const NetcdfReadOptions& opt) {
  std::optional<std::string> cu = r.text_attribute(conc.varid, "units");
  if (!cu && !opt.concentration_units_if_missing.empty()) cu = opt.concentration_units_if_missing;
  if (!cu)
    r.fail(opt.concentration + ":units",
           "missing; expected a mass concentration such as g m-3, kg m-3 or mg m-3");
  const auto conc_factor = netcdf_cf::concentration_to_g_m3(*cu);
  if (!conc_factor)
    r.fail(opt.concentration + ":units",
           fmt::format("'{}' is not a mass concentration; expected g m-3, kg m-3, mg m-3 or ug m-3",
                       *cu));
  return *conc_factor;
}

// The offset from the temperature's units to kelvin.
double temperature_offset(const NcReader& r, const DataVar& temp, const NetcdfReadOptions& opt) {
  const auto tu = r.text_attribute(temp.varid, "units");
  if (!tu) r.fail(opt.temperature + ":units", "missing; expected K or degC");
  const auto off = netcdf_cf::temperature_offset_to_k(*tu);
  if (!off)
    r.fail(opt.temperature + ":units",
           fmt::format("'{}' is not a temperature unit; expected K or degC", *tu));
  return *off;
}

// `header_read` is called once everything before the data is read
// (netcdf_child_read.h).
ConcentrationSeries read_locked(const std::filesystem::path& path, const NetcdfReadOptions& opt,
                                const std::function<void()>& header_read) {
  const std::string file = path.string();
  // Counts and lengths against the file's size first: nc_open allocates what
  // a classic header says (netcdf_classic_check.h).
  netcdf_cf::check_netcdf_classic_header(path);
  NcHandle handle;
  const int status = nc_open(path.c_str(), NC_NOWRITE, &handle.id);
  if (status != NC_NOERR) {
    handle.id = -1;
    if (status == NC_EHDFERR)  // an HDF5 signature, and HDF5 could not read on
      throw InputError(file, "",
                       "a netCDF-4 (HDF5) file that HDF5 cannot read: it is truncated or "
                       "corrupt");
    throw InputError(file, "", fmt::format("not a readable netCDF file: {}", nc_strerror(status)));
  }
  const NcReader r(file, handle.id);
  const std::array<AxisInfo, 4> axes = concentration_axes(r, opt);
  const std::uint64_t voxels = check_memory(r, axes, opt);
  std::array<Coordinates, 3> coords;
  for (int a = 0; a < 3; ++a) coords[a] = netcdf_cf::spatial_coordinates(r, axes[a]);
  const std::vector<double> times = netcdf_cf::time_coordinates(r, axes[kT]);
  const GridPlacement placement = grid_placement(r, axes, coords);
  const GridDims gd{static_cast<int>(axes[kX].len), static_cast<int>(axes[kY].len),
                    static_cast<int>(axes[kZ].len)};

  const DataVar conc = netcdf_cf::data_variable(r, opt.concentration, axes);
  const double conc_factor = concentration_factor(r, conc, opt);
  std::optional<DataVar> temp;
  double temp_offset = 0;
  if (!opt.temperature.empty()) {
    temp = netcdf_cf::data_variable(r, opt.temperature, axes);
    temp_offset = temperature_offset(r, *temp, opt);
  }
  header_read();

  ConcentrationSeries series;
  series.source = file;
  series.frames.reserve(times.size());
  std::vector<double> staging(static_cast<std::size_t>(voxels));
  const std::optional<float> conc_missing =
      opt.missing_concentration_as_zero ? std::optional<float>(0.0f) : std::nullopt;
  for (std::size_t t = 0; t < times.size(); ++t) {
    ConcentrationFrame frame;
    frame.time_s = times[t];
    ScalarGrid& c = frame.concentration_g_m3;
    c.dims = gd;
    c.placement = placement;
    c.values.resize(static_cast<std::size_t>(voxels));
    netcdf_cf::read_frame(r, conc, axes, coords, t, conc_factor, 0.0, conc_missing, staging, c,
                          "concentration", "g/m³", false);
    if (temp) {
      ScalarGrid g;
      g.dims = gd;
      g.placement = placement;
      g.values.resize(static_cast<std::size_t>(voxels));
      netcdf_cf::read_frame(r, *temp, axes, coords, t, 1.0, temp_offset, std::nullopt, staging, g,
                            "temperature", "K", true);
      frame.temperature_k = std::move(g);
    }
    series.frames.push_back(std::move(frame));
  }
  return series;
}

}  // namespace

ConcentrationSeries read_netcdf_cf(const std::filesystem::path& path,
                                   const NetcdfReadOptions& options) {
  const std::string file = path.string();
  if (options.concentration.empty())
    throw InputError(file, "concentration", "the concentration variable name is empty");
  if (options.temperature == options.concentration)
    throw InputError(file, "temperature", "the temperature variable is the concentration's");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "", "file not found");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(file, "", "not a regular file");
  std::lock_guard lock(netcdf_cf::netcdf_mutex());
  // HDF5 may crash or hang on a corrupt netCDF-4 file: a child process reads
  // it (netcdf_child_read.h).
  if (netcdf_cf::is_hdf5_container(path))
    return netcdf_cf::read_in_child_process(file, [&](const std::function<void()>& header_read) {
      return read_locked(path, options, header_read);
    });
  return read_locked(path, options, [] {});
}

}  // namespace obscura
