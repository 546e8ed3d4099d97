// The VTK readers' entry points: argument checks, one file, and a series of
// files on one grid. The parsing is in vtk_dataset_parser.cpp, the writer in
// vtk_structured_points_writer.cpp.
#include "obscura/io/vtk_structured_points.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <system_error>

#include "obscura/core/error.h"
#include "obscura/io/vtk_dataset_parser.h"

namespace obscura {
namespace {

// Frames of a series share a grid when origins agree to this fraction of a voxel.
constexpr double kSameGridTolerance = 1e-9;

void check_names(const std::string& file, const VtkArrayNames& names) {
  if (names.concentration.empty())
    throw InputError(file, "concentration", "the concentration array name is empty");
  if (names.temperature == names.concentration)
    throw InputError(
        file, "temperature",
        fmt::format("the temperature array name '{}' is the concentration's", names.temperature));
  if (!(std::isfinite(names.concentration_to_g_m3) && names.concentration_to_g_m3 > 0.0))
    throw InputError(file, "concentration_to_g_m3",
                     fmt::format("scale {} must be finite and > 0", names.concentration_to_g_m3));
}

// Times first: they are cheap to check and an unsorted list is a caller
// error that reading gigabytes would only delay.
void check_times(const std::vector<std::pair<double, std::string>>& time_and_path) {
  for (std::size_t i = 0; i < time_and_path.size(); ++i) {
    const auto& [t, p] = time_and_path[i];
    if (!std::isfinite(t))
      throw InputError(p, fmt::format("time[{}]", i), fmt::format("time {} s is not finite", t));
    if (i > 0 && !(t > time_and_path[i - 1].first))
      throw InputError(p, fmt::format("time[{}]", i),
                       fmt::format("time {} s is not after the previous frame's {} s ({}): "
                                   "times must be strictly increasing",
                                   t, time_and_path[i - 1].first, time_and_path[i - 1].second));
  }
}

// `frame` (read from `path`) must be on the grid of `first` (read from
// `first_path`); it then takes that placement bit for bit, so that downstream
// code may compare placements exactly.
void adopt_first_grid(ConcentrationFrame& frame, const std::string& path, const ScalarGrid& first,
                      const std::string& first_path) {
  const ScalarGrid& a = first;
  const ScalarGrid& b = frame.concentration_g_m3;
  const double h = a.placement.voxel_size_m;
  const Vec3 d = b.placement.origin_m - a.placement.origin_m;
  const bool same =
      a.dims == b.dims && std::abs(b.placement.voxel_size_m - h) <= kSameGridTolerance * h &&
      std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)}) <= kSameGridTolerance * h;
  if (!same)
    throw InputError(
        path, "grid",
        fmt::format("grid {}x{}x{} voxels of {} m at ({}, {}, {}) differs from the first "
                    "frame's {}x{}x{} of {} m at ({}, {}, {}) ({}): every frame of a series "
                    "must share one grid",
                    b.dims.nx, b.dims.ny, b.dims.nz, b.placement.voxel_size_m,
                    b.placement.origin_m.x, b.placement.origin_m.y, b.placement.origin_m.z,
                    a.dims.nx, a.dims.ny, a.dims.nz, h, a.placement.origin_m.x,
                    a.placement.origin_m.y, a.placement.origin_m.z, first_path));
  frame.concentration_g_m3.placement = a.placement;
  if (frame.temperature_k) frame.temperature_k->placement = a.placement;
}

}  // namespace

ConcentrationFrame read_vtk_structured_points(const std::filesystem::path& path, double time_s,
                                              const VtkArrayNames& names) {
  const std::string file = path.string();
  check_names(file, names);
  if (!std::isfinite(time_s)) throw InputError(file, "time", "time must be finite");
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(file, "", "file not found");
  vtk_legacy::DatasetParser parser(path, names);
  return parser.run(time_s);
}

ConcentrationSeries read_vtk_series(
    const std::vector<std::pair<double, std::string>>& time_and_path, const VtkArrayNames& names) {
  if (time_and_path.empty()) throw InputError("", "", "a VTK series needs at least one file");
  check_times(time_and_path);
  ConcentrationSeries series;
  series.source = time_and_path.front().second;
  if (time_and_path.size() > 1)
    series.source += fmt::format(" (+{} files)", time_and_path.size() - 1);
  for (const auto& [t, p] : time_and_path) {
    ConcentrationFrame frame = read_vtk_structured_points(p, t, names);
    if (!series.frames.empty())
      adopt_first_grid(frame, p, series.frames.front().concentration_g_m3,
                       time_and_path.front().second);
    series.frames.push_back(std::move(frame));
  }
  return series;
}

}  // namespace obscura
